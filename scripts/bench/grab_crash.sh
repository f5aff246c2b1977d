#!/usr/bin/env bash
# What a stopped grab keeps: lodestone-grab streams CSimulatedRobot (paper_loop,
# 640x480 @ 30 Hz, real time) and is stopped after 20 s by SIGINT, then by SIGKILL. SIGINT: the
# observations the driver produced (its summary) against those read back from the rawlog.
# SIGKILL: the seconds between the driver's last ground-truth line (written as each
# observation is emitted) and the last observation read back from the .partial rawlog.
# Prints a markdown table. Target: SIGINT loses nothing; SIGKILL loses <= 1 s.
# Usage: scripts/bench/grab_crash.sh [SECONDS]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build="$root/build"
grab="$build/apps/lodestone-grab/lodestone-grab"
inspect="$build/apps/lodestone-inspect/lodestone-inspect"
seconds=${1:-20}
out="$root/out/bench_grab_crash"
rm -rf "$out" && mkdir -p "$out"

echo "| signal after ${seconds} s | produced | read back | rawlog | last observation lost [s] |"
echo "|---|---|---|---|---|"
for sig in INT KILL; do
    run="$out/$sig"
    mkdir -p "$run"
    cat > "$run/grab.ini" <<INI
[global]
rawlog_prefix = $run/grab

[SIM]
driver = CSimulatedRobot
process_rate = 100
scenario = $root/config_ini/scenarios/paper_loop.ini
camera = 640x480@30
time_scale = 1
ground_truth = $run/grab.gt.tum
INI
    "$grab" "$run/grab.ini" -q > "$run/grab.txt" 2> "$run/grab.err" &
    pid=$!
    sleep "$seconds"
    kill -"$sig" "$pid"
    wait "$pid" || true
    rawlog="$run/grab.rawlog.gz" truth="$run/grab.gt.tum"
    [ -f "$rawlog" ] || rawlog="$rawlog.partial"
    [ -f "$truth" ] || truth="$truth.partial"
    produced=$(sed -nE 's/.*SIM \(CSimulatedRobot\): ([0-9]+) observations.*/\1/p' "$run/grab.txt")
    [ -n "$produced" ] || produced="(killed: no summary)"
    "$inspect" summary "$rawlog" > "$run/summary.txt" || true
    entries=$(awk -F: '/^Entries/{gsub(/ /,"",$2); print $2}' "$run/summary.txt")
    last=$(sed -nE 's/^Latest timestamp *: ([0-9.]+).*/\1/p' "$run/summary.txt")
    truth_last=$(tail -1 "$truth" | awk '{print $1}')
    lost=$(awk -v a="$truth_last" -v b="$last" 'BEGIN{printf "%.3f", a - b}')
    echo "| SIG$sig | $produced | $entries | $(basename "$rawlog") | $lost |"
done
