#!/usr/bin/env bash
# Magnetic loop closure benchmarks (MagneticGpERD, config_ini/slam/magnetic_gp.ini), printed as
# markdown tables:
#   1. Aalto invensense trials 1-9 and Kok & Solin's walks, read in place from
#      ../shared/data/magnetic, each imported with the drift model for seeds 1..N (10) and run through
#      lodestone-slam's code path with odometry_only.ini and magnetic_gp.ini: median ATEs,
#      closures and their errors against the ground truth, and how much of each path comes back
#      near an earlier pass; then Kok's walks with the plane alignment, the vector field feature,
#      and the pre-fit hyperparameters instead; then every recording with the field map on;
#   2. time per new supernode with 1 000 and 10 000 supernodes stored, and the ERD's own on a
#      walk that stores over 10 000.
# Usage: scripts/bench/magnetic.sh [SEEDS]   (default 10; a few minutes in all)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
data="$root/../shared/data/magnetic"
"$root/scripts/build.sh" > /dev/null
bin="$root/build/bench"
pin=()
command -v taskset > /dev/null && pin=(taskset -c 0)
seeds=${1:-10}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
if [ -d "$data" ]; then
    echo "#### Magnetic SLAM on real recordings (median over seeds; one core)"
    echo
    # (the optimizer logs its rejections on stdout: kept out of the table)
    "${pin[@]}" "$bin/bench_magnetic" recordings "$data" "$out" "$seeds" 2> /dev/null | grep -v "^\["
    echo
    # One key or more changed in magnetic_gp.ini: "key=value ..." [ONLY]
    variant() {
        local ini="$out/variant.ini"
        cp "$root/config_ini/slam/magnetic_gp.ini" "$ini"
        for kv in $1; do sed -i "s|^${kv%%=*} *=[^;]*|${kv%%=*} = ${kv#*=} |" "$ini"; done
        echo "$1:"
        echo
        "${pin[@]}" "$bin/bench_magnetic" recordings "$data" "$out" "$seeds" "$ini" "${2:-}" 2> /dev/null | grep -v "^\["
        echo
    }
    echo "#### Kok walks: the alignment and the field feature compared (magnetic_gp.ini with one key changed)"
    echo
    for v in "alignment=plane" "field_mode=vector" "gp_sigma_f=4.0 gp_length_scale=0.3 gp_sigma_n=0.5"; do
        variant "$v" kok
    done
    echo "#### The field map (map_search = true; then with the cross-pass noise of a hand-held magnetometer)"
    echo
    for v in "map_search=true" "map_search=true map_sigma_n=1.0"; do variant "$v"; done
else
    echo "(real recordings absent: $data; table 1 skipped)"
fi
echo "#### Time per new supernode (synthetic field, one core)"
echo
"${pin[@]}" "$bin/bench_magnetic" timing
echo
echo "#### The ERD's own time per new supernode over a 2 530 m walk (magnetic_gp.ini; one core)"
echo
"${pin[@]}" "$bin/bench_magnetic" timing-run "$out" 2> /dev/null | grep -v "^\["
