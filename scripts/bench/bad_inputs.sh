#!/usr/bin/env bash
# Damaged rawlogs through the apps a user points at them: every input of the fuzz
# regression corpora (tests/fuzz/regression: the first fuzzing's findings rebuilt, and every input the fuzz
# targets found) plus damaged copies of the bundled sample made here, each through
# lodestone-inspect summary, lodestone-slam and lodestone-magfit, timed as whole processes
# (/usr/bin/time: wall, peak RSS). Prints a markdown table: exit code, wall time, peak RSS and
# the error line; then the worst time and RSS. Target: a clean error (exit 1, the
# file named) in < 1 s and < 200 MB.
# Usage: scripts/bench/bad_inputs.sh [--build DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build="$root/build"
[ "${1:-}" = "--build" ] && build=$2
inspect="$build/apps/lodestone-inspect/lodestone-inspect"
slam="$build/apps/lodestone-slam/lodestone-slam"
magfit="$build/apps/lodestone-magfit/lodestone-magfit"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

inputs=()
for f in "$root"/tests/fuzz/regression/fuzz_rawlog/*; do inputs+=("$f"); done
# The gzip target's inputs: a first byte, then the file (odd) or what to compress (even).
for f in "$root"/tests/fuzz/regression/fuzz_rawlog_gz/*; do
    name=$(basename "$f")
    if [ $(( $(head -c1 "$f" | od -An -tu1) % 2 )) -eq 1 ]; then
        tail -c +2 "$f" > "$work/$name.rawlog.gz"
    else
        tail -c +2 "$f" | gzip -c > "$work/$name.rawlog.gz"
    fi
    inputs+=("$work/$name.rawlog.gz")
done
# Damaged copies of the bundled sample (a real recording's size): cut, garbage appended.
sample="$root/rawlogs/sample_drive.rawlog.gz"
gzip -dc "$sample" > "$work/sample.rawlog"
size=$(stat -c %s "$work/sample.rawlog")
head -c $((size / 2)) "$work/sample.rawlog" > "$work/sample_cut_in_half.rawlog"
{ cat "$sample"; echo "garbage after the gzip data"; } > "$work/sample_garbage_after.rawlog.gz"
head -c $(( $(stat -c %s "$sample") / 2 )) "$sample" > "$work/sample_gzip_cut_in_half.rawlog.gz"
inputs+=("$work/sample_cut_in_half.rawlog" "$work/sample_garbage_after.rawlog.gz" "$work/sample_gzip_cut_in_half.rawlog.gz")

echo "| input | bytes | app | exit | wall (s) | peak RSS (MB) | message |"
echo "|---|---:|---|---:|---:|---:|---|"
worst_s=0; worst_mb=0; unclean=0
for f in "${inputs[@]}"; do
    for app in inspect slam magfit; do
        case $app in
            inspect) cmd=("$inspect" summary "$f") ;;
            slam) cmd=("$slam" --rawlog "$f" --config "$root/config_ini/slam/slam.ini" --quiet --out "$work/out") ;;
            magfit) cmd=("$magfit" "$f") ;;
        esac
        set +e
        /usr/bin/time -f "%e %M" -o "$work/time" timeout 60 "${cmd[@]}" > "$work/log" 2>&1
        rc=$?
        set -e
        read -r secs kb < <(tail -1 "$work/time") || { secs=60; kb=0; }
        mb=$((kb / 1024))
        msg=$(grep -m1 -F "$(basename "$f")" "$work/log" | sed "s|$work/||g; s|$root/||g; s/|/\\\\|/g" | cut -c1-200 || true)
        # Clean: exit 1 and the file named (a run that read everything exits 0 or 1 on its own).
        named=0; grep -q "$(basename "$f")" "$work/log" && named=1
        if [ "$rc" -gt 1 ] || { [ "$rc" -eq 1 ] && [ $named -eq 0 ]; }; then unclean=$((unclean + 1)); fi
        awk -v a="$secs" -v b="$worst_s" 'BEGIN { exit !(a > b) }' && worst_s=$secs
        [ "$mb" -gt "$worst_mb" ] && worst_mb=$mb
        echo "| $(basename "$f") | $(stat -c %s "$f") | $app | $rc | $secs | $mb | ${msg:-(read to the end)} |"
    done
done
echo
echo "worst: ${worst_s} s, ${worst_mb} MB; runs not ending cleanly (exit > 1, or exit 1 without the file named): $unclean"
