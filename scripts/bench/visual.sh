#!/usr/bin/env bash
# Visual loop closure benchmarks (OrbSubmapERD, config_ini/slam/visual_only.ini), printed as
# markdown tables:
#   1. closures on the simulator against ground truth, with submaps of 6 keyframes and with
#      single keyframes (no submaps), ATE of the graph;
#   2. the same runs from keyframes whose view is mostly plain wall;
#   3. matching and retrieval time per candidate / query;
#   4. candidate retrieval on synthetic catalogs of 100 to 10 000 submaps.
# Usage: scripts/bench/visual.sh [SCENARIO ...]   (default: paper_loop and corridor, 640x480 at 30 Hz,
#        379 s and 339 s of data: about five minutes per run, four runs)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
bin="$root/build/bench"
pin=()
command -v taskset > /dev/null && pin=(taskset -c 0)
scenarios=("$@")
[ ${#scenarios[@]} -gt 0 ] || scenarios=(paper_loop corridor)

rows=$(mktemp)
trap 'rm -f "$rows"' EXIT
for s in "${scenarios[@]}"; do
    for k in 6 1; do
        "${pin[@]}" "$bin/bench_visual" "$root/config_ini/scenarios/$s.ini" "$root/config_ini/slam/visual_only.ini" "$k" >> "$rows"
    done
done
echo "### Visual loop closures against ground truth (visual_only.ini)"
echo
echo "| scenario | submaps of | keyframes | submaps | closures | false (> 0.2 m or 5 deg) | phase 2 used | phase-2 error, median | closures per lap | textured revisits with a closure | ATE [m] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
sed -n 's/^CLOSURES //p' "$rows"
echo
echo "### From keyframes that see mostly plain wall (less than half the view textured)"
echo
echo "| scenario | submaps of | queries | best phase-1 matches, mean | phase-1 inliers, mean | closures |"
echo "|---|---|---|---|---|---|"
sed -n 's/^PLAIN //p' "$rows"
echo
echo "### Time (one core)"
echo
echo "| scenario | submaps of | candidates matched | match ms per candidate: mean / max | retrieval ms per query: mean / max |"
echo "|---|---|---|---|---|"
sed -n 's/^TIME //p' "$rows"
echo
echo "### Candidate retrieval on synthetic catalogs"
echo
echo "| submaps | queries | retrieval ms per query: mean / max | right submap first |"
echo "|---|---|---|---|"
"${pin[@]}" "$bin/bench_submap_retrieval" 100 1000 10000
