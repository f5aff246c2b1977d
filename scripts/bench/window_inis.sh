#!/usr/bin/env bash
# Writes two variants of config_ini/slam/slam.ini into DIR for the magnetic benches:
#   slam_window.ini - its magnetic closer (MagneticGpERD) replaced by MagneticWindowERD with
#                     magnetic_window.ini's [MagneticWindowERD] section;
#   slam_both.ini   - both closers side by side.
# Usage: scripts/bench/window_inis.sh DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
dir=${1:?usage: window_inis.sh DIR}
mkdir -p "$dir"
section="$dir/window_section.ini"
awk '/^\[MagneticWindowERD\]/{on=1} /^\[/{if(!/^\[MagneticWindowERD\]/)on=0} on' \
    "$root/config_ini/slam/magnetic_window.ini" > "$section"
grep -q '^\[MagneticWindowERD\]' "$section" ||
    { echo "window_inis.sh: magnetic_window.ini has no [MagneticWindowERD] section" >&2; exit 1; }
children='^children = OrbSubmapERD MagneticGpERD '
grep -q "$children" "$root/config_ini/slam/slam.ini" ||
    { echo "window_inis.sh: slam.ini's [CompositeERD] children line changed" >&2; exit 1; }
sed "s/$children/children = OrbSubmapERD MagneticWindowERD /" "$root/config_ini/slam/slam.ini" |
    awk -v sec="$section" '
    /^\[MagneticGpERD\]/{skip=1; while ((getline line < sec) > 0) print line; next}
    /^\[/{skip=0} !skip' > "$dir/slam_window.ini"
sed "s/$children/children = OrbSubmapERD MagneticGpERD MagneticWindowERD /" \
    "$root/config_ini/slam/slam.ini" | awk -v sec="$section" '
    /^\[CeresGSO\]/{while ((getline line < sec) > 0) print line}
    {print}' > "$dir/slam_both.ini"
