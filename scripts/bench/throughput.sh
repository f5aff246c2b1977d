#!/usr/bin/env bash
# Offline SLAM throughput from a rawlog on disk (issue #15): each scenario recorded by
# lodestone-sim at its INI's camera (640x480 @ 30 Hz; colour as PNG files beside the rawlog,
# as a user's recording is), then `lodestone-slam --rawlog ... --config CONFIG` timed as a user
# runs it - the whole process, start to outputs written - on both cores and pinned to one
# (taskset -c 0). Prints a markdown table: wall time, real-time factor, the engine's frame time
# (report.json), peak RSS (/usr/bin/time), ATE.
# Usage: scripts/bench/throughput.sh [--config INI] [--recordings DIR] [--slam BINARY] [SCENARIO.ini ...]
#   --config      SLAM INI (default config_ini/slam.ini)
#   --recordings  keep the recorded rawlogs in DIR and reuse them when there (they are large:
#                 paper_loop is 7 GB with its images)
#   --slam        another lodestone-slam (e.g. a build of an earlier commit, for "before")
#   --image-format png|jpg|jpg:Q   colour files as lodestone-sim writes them (default png)
#   --gzip        record NAME.rawlog.gz (depth deflated) instead of NAME.rawlog
#   default scenarios: office and paper_loop
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
config="$root/config_ini/slam.ini"
recordings=""
simArgs=()
ext=rawlog
slam="$root/build/apps/lodestone-slam/lodestone-slam"
while [ $# -gt 0 ]; do
    case "$1" in
        --config) config=$2; shift 2 ;;
        --recordings) recordings=$2; shift 2 ;;
        --slam) slam=$2; shift 2 ;;
        --image-format) simArgs+=(--image-format "$2"); shift 2 ;;
        --gzip) ext=rawlog.gz; shift ;;
        *) break ;;
    esac
done
"$root/scripts/build.sh" > /dev/null
sim="$root/build/apps/lodestone-sim/lodestone-sim"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
rec=${recordings:-$out}
mkdir -p "$rec"
scenarios=("$@")
[ ${#scenarios[@]} -gt 0 ] || scenarios=("$root/config_ini/office.ini" "$root/config_ini/paper_loop.ini")
json() { python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }
echo "| scenario | config | cores | frames | data [s] | wall [s] | real-time factor | frame ms mean / p99 | peak RSS [MB] | ATE [m] |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for ini in "${scenarios[@]}"; do
    name=$(basename "$ini" .ini)
    [ -f "$rec/$name.$ext" ] || "$sim" -c "$ini" -o "$rec/$name.$ext" "${simArgs[@]}" > /dev/null
    for cores in 2 1; do
        pin=()
        [ "$cores" = 1 ] && pin=(taskset -c 0)
        /usr/bin/time -f "%e %M" -o "$out/time.txt" "${pin[@]}" "$slam" -r "$rec/$name.$ext" \
            --config "$config" --ground-truth "$rec/$name.gt.tum" --out "$out/run" --quiet \
            > "$out/run.log" 2>&1
        read -r wall rss < "$out/time.txt"
        report="$out/run/report.json"
        data=$(json "$report" "round(r['timing']['data_s'], 1)")
        frames=$(grep -o "[0-9]* frames" "$out/run.log" | head -1 | awk '{print $1}')
        frame=$(json "$report" "'%.1f / %.1f' % (r['timing']['frame_ms']['mean'], r['timing']['frame_ms']['p99'])")
        ate=$(grep -o "ATE RMSE [0-9.]*" "$out/run.log" | awk '{print $3}')
        rtf=$(python3 -c "print('%.2fx' % ($data / $wall))")
        echo "| $name | $(basename "$config") | $cores | $frames | $data | $wall | $rtf | $frame | $((rss / 1024)) | $ate |"
        rm -rf "$out/run"
    done
    [ -n "$recordings" ] || rm -rf "$out/$name"*
done
