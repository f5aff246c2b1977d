#!/usr/bin/env bash
# Kidnap recovery benchmark (issue #12), printed as markdown: each kidnap scenario is run
# through lodestone-slam with slam.ini on the simulator, then judged by
# `lodestone-eval relocation` against the simulator's ground truth and kidnap events: per
# kidnap relocated or not, time and odometry travel from the put-down to the verified
# relocation, pose error there (the map aligned on the nodes mapped before the first lift),
# wrong (> 0.5 m or 10 deg); then the map's damage (ATE of the pre-lift nodes at the lift and
# at the end) and the whole run's ATE.
# Usage: scripts/bench/kidnap.sh [SCENARIO.ini ...]   (default: config_ini/paper_kidnap.ini,
#        830 s of 640x480 data: about ten minutes on one core)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
slam="$root/build/apps/lodestone-slam/lodestone-slam"
evaluate="$root/build/apps/lodestone-eval/lodestone-eval"
pin=()
command -v taskset > /dev/null && pin=(taskset -c 0)
scenarios=("$@")
[ ${#scenarios[@]} -gt 0 ] || scenarios=("$root/config_ini/paper_kidnap.ini")
out="${LODESTONE_BENCH_OUT:-$root/out/bench_kidnap}"
mkdir -p "$out"

for s in "${scenarios[@]}"; do
    name=$(basename "$s" .ini)
    dir="$out/$name"
    start=$(date +%s)
    "${pin[@]}" "$slam" --sim "$s" --config "$root/config_ini/slam.ini" --out "$dir" --quiet > "$dir.log" 2>&1 \
        || { echo "lodestone-slam failed on $s (see $dir.log)" >&2; exit 1; }
    echo "### $name (slam.ini, wall $(( $(date +%s) - start )) s)"
    echo
    "$evaluate" relocation "$dir"
    echo
done
