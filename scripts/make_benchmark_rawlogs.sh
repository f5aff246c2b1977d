#!/usr/bin/env bash
# Writes the large simulated rawlogs the benchmarks read, into out/rawlogs/ (not committed:
# paper_loop at 640x480 / 30 Hz is ~11 400 frames and several GB). Prints a markdown table of
# what was written and how long it took.
#   scripts/make_benchmark_rawlogs.sh [SCENARIO ...]   (default: every shipped scenario)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" > /dev/null
out="$root/out/rawlogs"
mkdir -p "$out"
scenarios=("$@")
[ ${#scenarios[@]} -gt 0 ] || scenarios=(office paper_loop_qvga corridor paper_kidnap paper_loop)

echo "| scenario | observations | RGB-D frames | simulated [s] | wall time [s] | rawlog + images |"
echo "|---|---|---|---|---|---|"
for s in "${scenarios[@]}"; do
    rm -rf "$out/$s.rawlog.gz" "$out/${s}_Images"
    start=$(date +%s.%N)
    log=$("$root/build/apps/lodestone-sim/lodestone-sim" --config "$root/config_ini/scenarios/$s.ini" \
        --out "$out/$s.rawlog.gz")
    end=$(date +%s.%N)
    summary=$(echo "$log" | grep "observations (")
    obs=$(echo "$summary" | awk '{print $1}')
    frames=$(echo "$summary" | sed -E 's/.*\(([0-9]+) RGB-D.*/\1/')
    simulated=$(echo "$summary" | sed -E 's/.*, ([0-9.]+) s simulated.*/\1/')
    size=$(du -shc "$out/$s.rawlog.gz" "$out/${s}_Images" 2>/dev/null | tail -1 | cut -f1)
    printf "| %s | %s | %s | %s | %.0f | %s |\n" "$s" "$obs" "$frames" "$simulated" \
        "$(awk -v a="$start" -v b="$end" 'BEGIN{print b-a}')" "$size"
done
echo
echo "rawlogs in $out"
