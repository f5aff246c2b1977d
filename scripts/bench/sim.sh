#!/usr/bin/env bash
# Simulator benchmarks, printed as markdown tables:
#   1. RGB-D frames rendered per second on one core (taskset -c 0), per scenario and size;
#   2. the magnetic field along each scenario's path.
# Usage: scripts/bench/sim.sh   (builds first; run from anywhere)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
bin="$root/build/bench"
pin=()
command -v taskset > /dev/null && pin=(taskset -c 0)

echo "### Simulator: RGB-D rendering, one core"
echo
echo "| scenario | size | frames | ms / frame | frames / s | pixels with depth |"
echo "|---|---|---|---|---|---|"
for scenario in paper_loop corridor office; do
    for size in 320x240 640x480; do
        "${pin[@]}" "$bin/bench_sim_render" "$root/config_ini/scenarios/$scenario.ini" "$size" 300
    done
done
echo
echo "### Simulator: magnetic field along the path (at the first magnetometer's height)"
echo
echo "| scenario | path [m] | earth field [uT] | abs(B) range [uT] | abs(B) std [uT] | largest anomaly [uT] | correlation length [m] |"
echo "|---|---|---|---|---|---|---|"
for scenario in office corridor paper_loop; do
    "$bin/bench_sim_field" "$root/config_ini/scenarios/$scenario.ini"
done
