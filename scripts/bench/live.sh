#!/usr/bin/env bash
# Live grabbing with live SLAM: lodestone-grab streams a simulated robot
# (CSimulatedRobot) in real time with --slam config_ini/slam/slam.ini; then lodestone-slam runs
# offline on the grabbed rawlog. Prints a markdown table: the live run's lag behind the newest
# observation (p50 / p99 / max), RGB-D frames skipped, ATE of the live and of the offline run
# against the driver's ground truth, and the grab's own counts.
# Usage: [VIEW=1] scripts/bench/live.sh [SCENARIO CAMERA SECONDS]...
#   default: office 320x240@15 30   paper_loop 640x480@30 60
#   VIEW=1: live SLAM with its 3D window (--view) on an Xvfb display (xvfb-run)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build="$root/build"
grab="$build/apps/lodestone-grab/lodestone-grab"
slam="$build/apps/lodestone-slam/lodestone-slam"
eval_="$build/apps/lodestone-eval/lodestone-eval"
out="$root/out/bench_live"
mkdir -p "$out"
runs=("$@")
[ ${#runs[@]} -gt 0 ] || runs=(office 320x240@15 30 paper_loop 640x480@30 60)

echo "| scenario | camera | seconds | observations | lag p50 [s] | lag p99 [s] | lag max [s] | RGB-D skipped | ATE live [m] | ATE offline [m] |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for ((i = 0; i < ${#runs[@]}; i += 3)); do
    scenario=${runs[i]} camera=${runs[i + 1]} seconds=${runs[i + 2]}
    run="$out/${scenario}_${camera//[^0-9a-z]/_}"
    rm -rf "$run" "$run"_* && mkdir -p "$run"
    cat > "$run/grab.ini" <<INI
[global]
rawlog_prefix = $run/grab

[SIM]
driver = CSimulatedRobot
process_rate = 100
scenario = $root/config_ini/scenarios/$scenario.ini
camera = $camera
time_scale = 1
max_seconds = $seconds
ground_truth = $run/grab.gt.tum
INI
    if [[ ${VIEW:-0} == 1 ]]; then
        xvfb-run -a -s "-screen 0 1280x1024x24" "$grab" "$run/grab.ini" -q --view --slam "$root/config_ini/slam/slam.ini" > "$run/grab.txt"
    else
        "$grab" "$run/grab.ini" -q --slam "$root/config_ini/slam/slam.ini" > "$run/grab.txt"
    fi
    summary=$(grep "live SLAM" "$run/grab.txt")
    p50=$(echo "$summary" | sed -E 's/.*p50 ([0-9.]+) s.*/\1/')
    p99=$(echo "$summary" | sed -E 's/.*p99 ([0-9.]+) s.*/\1/')
    max=$(echo "$summary" | sed -E 's/.*max ([0-9.]+) s.*/\1/')
    skipped=$(echo "$summary" | sed -E 's/.*; ([0-9]+ of [0-9]+) RGB-D.*/\1/')
    # (the optimizer's log lines may come first)
    obs=$(grep -m1 "^lodestone-grab:" "$run/grab.txt" | awk '{print $2}')
    live_ate=$("$eval_" "$run/grab_slam/trajectory.tum" "$run/grab.gt.tum" | awk '/^ATE/{print $3}')
    "$slam" --rawlog "$run/grab.rawlog.gz" --config "$root/config_ini/slam/slam.ini" --quiet --out "$run/offline" > /dev/null
    offline_ate=$("$eval_" "$run/offline/trajectory.tum" "$run/grab.gt.tum" | awk '/^ATE/{print $3}')
    echo "| $scenario | $camera | $seconds | $obs | $p50 | $p99 | $max | $skipped | $live_ate | $offline_ate |"
done
echo
echo "runs in $out"
