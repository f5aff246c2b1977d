#!/usr/bin/env bash
# The crossing closer (MagneticCrossingERD, opt-in) beside the window closer alone: the magnetic
# recall bench run with magnetic_window.ini and with the same INI whose CompositeERD children
# add MagneticCrossingERD (docs/results/magnetic-recall.md, "Where a run crosses its own path").
# Usage: scripts/bench/crossing.sh [SEEDS] [--only NAME]   (default 10 seeds, every recording;
#   e.g. `crossing.sh 10 --only aalto`; the simulated corridor part is skipped)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
seeds=${1:-10}
shift || true
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
children='^children = MagneticWindowERD MagneticFieldMapERD '
grep -q "$children" "$root/config_ini/slam/magnetic_window.ini" ||
    { echo "crossing.sh: magnetic_window.ini's [CompositeERD] children line changed" >&2; exit 1; }
sed "s/$children/children = MagneticWindowERD MagneticFieldMapERD MagneticCrossingERD /" \
    "$root/config_ini/slam/magnetic_window.ini" > "$dir/window_crossing.ini"
SIM_SEEDS=0 "$root/scripts/bench/magnetic_recall.sh" "$seeds" "$dir/window_crossing.ini" \
    magnetic_window.ini "$@"
