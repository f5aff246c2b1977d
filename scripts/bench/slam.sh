#!/usr/bin/env bash
# lodestone-slam benchmarks, printed as markdown tables:
#   1. the engine on simulated scenarios (640x480 at 30 Hz): ATE of the graph against the fused
#      odometry alone on the same nodes, engine time per frame (rendering excluded), real-time
#      factor and time per node by decile of the run;
#   2. synthetic pose graphs of 1 000 to 20 000 nodes replayed through the engine: time per
#      node by decile (flat = no growth with the graph).
# Usage: scripts/bench/slam.sh [SCENARIO ...]   (default: office paper_loop; paper_loop is
#        379 s of 640x480 data and takes about ten minutes)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
bin="$root/build/bench"
pin=()
command -v taskset > /dev/null && pin=(taskset -c 0)
scenarios=("$@")
[ ${#scenarios[@]} -gt 0 ] || scenarios=(office paper_loop)

echo "### lodestone-slam engine on the simulator (odometry_only.ini, one core)"
echo
echo "| scenario | camera | config | nodes | loop closures | ATE graph [m] | ATE fused odometry, same nodes [m] | difference [m] | engine ms per frame: mean / p99 | engine real-time factor | engine ms per node, by decile of the run |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for s in "${scenarios[@]}"; do
    "${pin[@]}" "$bin/bench_slam" "$root/config_ini/scenarios/$s.ini" "$root/config_ini/slam/odometry_only.ini"
done
echo
echo "### Engine + CeresGSO on synthetic graphs (laps of a 25 m square, a closure on every 8th node of every later lap, to the first or the previous lap)"
echo
echo "| closures to | nodes | loop closures | local / full solves | escalated | rejected | local / full solve time [s] | ms per node: mean | p99 | ms per node by decile | final solve [s] | position RMSE [m] (dead reckoning) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
"${pin[@]}" "$bin/bench_graph_scaling" previous 1000 5000 10000 20000
"${pin[@]}" "$bin/bench_graph_scaling" first 1000 5000 10000 20000
