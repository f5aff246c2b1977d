#!/usr/bin/env bash
# Odometry benchmarks, printed as markdown tables:
#   1. wheel-only, VO-only and both fusions against the simulator's ground truth;
#   2. VO health and time per frame on the simulated runs (one core);
#   3. VO on the real Kinect frames of ../shared/data/rgbd/3dmatch (skipped when absent).
# Usage: scripts/bench/odometry.sh [--no-guided] [SCENARIO ...]   (default: office corridor
#        paper_loop; paper_loop is 640x480 at 30 Hz for 379 s and takes several minutes)
#   --no-guided   VO matches by brute force only (config_ini/slam/odometry.ini with guided_matching
#                 = false), for the before / after of guided matching
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
bin="$root/build/bench"
pin=()
command -v taskset > /dev/null && pin=(taskset -c 0)
odometry_ini="$root/config_ini/slam/odometry.ini"
tmp_ini=$(mktemp --suffix=.ini)
if [ "${1:-}" = "--no-guided" ]; then
    shift
    sed 's/^guided_matching *=.*/guided_matching = false/' "$odometry_ini" > "$tmp_ini"
    odometry_ini=$tmp_ini
fi
scenarios=("$@")
[ ${#scenarios[@]} -gt 0 ] || scenarios=(office corridor paper_loop)

vo_rows=$(mktemp)
trap 'rm -f "$vo_rows" "$tmp_ini"' EXIT
echo "### Odometry against ground truth (simulator, 640x480 at 30 Hz)"
echo
echo "| scenario | method | ATE RMSE [m] | RPE [m per s] | RPE [% of 1 m] | end-point drift [m] |"
echo "|---|---|---|---|---|---|"
for s in "${scenarios[@]}"; do
    "${pin[@]}" "$bin/bench_odometry" "$root/config_ini/scenarios/$s.ini" - 1e9 "$odometry_ini" 2>> "$vo_rows"
done
echo
echo "### Visual odometry on the same runs (time per frame on one core, ms)"
echo
echo "| scenario | camera | tracked | failed | LOST | guided / fell back | VO RPE where tracked [% of 1 m] | ... and the view textured | decode | ORB | matching | RANSAC | total |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
sed -n 's/^VO //p' "$vo_rows"
data="$root/../shared/data/rgbd/3dmatch"
if [ -d "$data" ]; then
    echo
    echo "### Visual odometry on real Kinect frames (3DMatch seq-01, read in place)"
    echo
    echo "| what | frames | result | | translation error / decode | rotation error / ... |"
    echo "|---|---|---|---|---|---|"
    "${pin[@]}" "$bin/bench_vo_real" "$data" 20
else
    echo
    echo "(real frames absent: $data)"
fi
