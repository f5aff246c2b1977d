#!/usr/bin/env bash
# The magnetic loop closers judged as place recognition (precision and recall against the truth,
# passes counted by direction), side by side on every recording: Aalto invensense trials 1-9 and
# Kok & Solin's walks read in place from ../shared/data/magnetic (skipped when absent), a long
# synthetic loop and a synthetic corridor walked back and forth. Each recording is imported with
# the drift model for seeds 1..N and run with each INI; a markdown table, a row per recording
# and INI (bench/bench_magnetic_recall.cpp says what each column counts).
# Usage: scripts/bench/magnetic_recall.sh [SEEDS] [INI ...]
#   (default: 10 seeds; magnetic_only.ini, the sequence matcher with GP correction, against
#   magnetic_window.ini, the window method; a few minutes)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
seeds=${1:-10}
shift || true
inis=("$@")
[ ${#inis[@]} -gt 0 ] || inis=(magnetic_only.ini magnetic_window.ini)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
pin=()
command -v taskset > /dev/null && pin=(taskset -c 0)
# (the optimizer logs its rejections on stdout: kept out of the table)
"${pin[@]}" "$root/build/bench/bench_magnetic_recall" "$root/../shared/data/magnetic" "$out" "$seeds" \
    "${inis[@]}" 2> /dev/null | grep -v "^\["
