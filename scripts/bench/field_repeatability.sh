#!/usr/bin/env bash
# What the Kok walks' field and reference allow a magnetic loop closer: how well the field
# repeats between passes against how far apart the reference says they ran (along, across;
# bench/bench_field_repeatability.cpp), and the ATE each closer leaves when the odometry has no
# error at all (bench_magnetic_recall --drift-scale 0, one seed: without drift every seed is the
# same run) - what the closures alone do to the reference trajectory. The walks are read in
# place from ../shared/data/magnetic/kok (skipped when absent).
# Usage: scripts/bench/field_repeatability.sh   (seconds)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
data="$root/../shared/data/magnetic"
if [ ! -f "$data/kok/eight.csv" ]; then
    echo "skipped: $data/kok is absent (Kok & Solin's walks)"
    exit 0
fi
"$root/scripts/build.sh" > /dev/null
"$root/build/bench/bench_field_repeatability" "$data/kok/eight.csv" "$data/kok/square.csv"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo
echo "#### The closures alone: odometry without error (--drift-scale 0)"
echo
"$root/build/bench/bench_magnetic_recall" "$data" "$out" 1 magnetic_gp.ini magnetic_window.ini \
    --only kok --drift-scale 0 2> /dev/null | grep -v "^\[" | sed '/^Passes each closer missed/,$d'
