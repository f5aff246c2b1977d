#!/usr/bin/env bash
# Depth alignment beside the wheels (slam.ini): each scenario recorded to disk for seeds 1..N
# at 320x240 / 15 Hz and run from disk with slam.ini as shipped and with one of its
# [visual_odometry] depth keys changed: no depth alignment (slam.ini before 2026-11-26); depth
# solved with the features wherever both align (joined); depth alone counting only where it pins
# 5 of 6 directions (pinned5, rgbd_only.ini's rule); VO started only from a frame with features
# (no_start). A row per scenario, seed and INI: ATE, the frames depth alignment was tried on,
# aligned on, and why it failed (does not pin enough), and the run's wall time.
# Usage: scripts/bench/wheels_depth.sh [SEEDS] [SCENARIO ...]
#   (default: 3 seeds of corridor and paper_loop; about 25 minutes)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
seeds=${1:-3}
shift || true
scenarios=("$@")
[ ${#scenarios[@]} -gt 0 ] || scenarios=(corridor paper_loop)
sim="$root/build/apps/lodestone-sim/lodestone-sim"
slam="$root/build/apps/lodestone-slam/lodestone-slam"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
base="$root/config_ini/slam/slam.ini"
source "$root/scripts/bench/ini_variant.bash"
cp "$base" "$out/shipped.ini"
variant no_depth depth_alignment=false
variant joined depth_with_features=true
variant pinned5 depth_min_observed=5
variant no_start depth_start=false
inis=(no_depth shipped joined pinned5 no_start)

echo "| scenario | seed | INI | ATE [m] | depth tried / aligned (frames) | depth did not pin enough | wall [s] |"
echo "|---|---|---|---|---|---|---|"
for scenario in "${scenarios[@]}"; do
    for seed in $(seq 1 "$seeds"); do
        log="$out/$scenario-$seed"
        "$sim" -c "$root/config_ini/scenarios/$scenario.ini" --camera 320x240@15 -s "$seed" \
            -o "$log.rawlog" > /dev/null
        for ini in "${inis[@]}"; do
            run="$log-$ini"
            start=$(date +%s.%N)
            ate=$("$slam" --rawlog "$log.rawlog" --ground-truth "$log.gt.tum" --config "$out/$ini.ini" \
                --out "$run" 2> /dev/null | sed -n 's/^ATE RMSE \([0-9.]*\) m.*/\1/p')
            wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
            tried=$(field "$run/report.json" depth_tried)
            aligned=$(field "$run/report.json" depth_aligned)
            unpinned=$({ grep -o '"depth does not pin the motion": [0-9]*' "$run/report.json" || true; } | head -1 | sed 's/.*: //')
            printf "| %s | %s | %s | %s | %s / %s | %s | %.0f |\n" "$scenario" "$seed" "$ini" "$ate" \
                "${tried:--}" "${aligned:--}" "${unpinned:--}" "$wall"
            rm -rf "$run"
        done
        rm -rf "$log".rawlog "$log"_Images "$log".gt.tum "$log".events.txt
    done
done
