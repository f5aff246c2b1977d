#!/usr/bin/env bash
# Writes the variants of config_ini/slam/slam.ini with one magnetic loop closer into DIR, for the
# benches that compare the closers (slam.ini itself runs both):
#   slam_gp.ini     - the GP sequence matcher alone (MagneticGpERD; slam.ini before 2026-11-26);
#   slam_window.ini - the window method alone (MagneticWindowERD).
# Usage: scripts/bench/window_inis.sh DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
dir=${1:?usage: window_inis.sh DIR}
mkdir -p "$dir"
children='^children = OrbSubmapERD MagneticGpERD MagneticWindowERD '
grep -q "$children" "$root/config_ini/slam/slam.ini" ||
    { echo "window_inis.sh: slam.ini's [CompositeERD] children line changed" >&2; exit 1; }
# without CLOSER: its name off the children line, its section left out
without() {
    sed "s/$children/children = OrbSubmapERD $2 /" "$root/config_ini/slam/slam.ini" |
        awk -v drop="[$1]" '/^\[/{skip = ($0 == drop)} !skip'
}
without MagneticWindowERD MagneticGpERD > "$dir/slam_gp.ini"
without MagneticGpERD MagneticWindowERD > "$dir/slam_window.ini"
