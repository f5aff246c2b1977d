#!/usr/bin/env bash
# Offline SLAM throughput from a rawlog on disk: each scenario recorded by
# lodestone-sim at its INI's camera (640x480 @ 30 Hz; colour as PNG files beside the rawlog,
# as a user's recording is), then `lodestone-slam --rawlog ... --config CONFIG` timed as a user
# runs it - the whole process, start to outputs written - on both cores and pinned to one
# (taskset -c 0). Prints two markdown tables: wall time, real-time factor, the engine's frame
# time (report.json), peak RSS (/usr/bin/time), ATE; then each run's time per RGB-D frame by
# stage (report.json): read and decode (the decode-ahead workers, summed over them; "-" where
# the build did not report them), ORB, matching, RANSAC (VO), the rest of the node decider
# (fusion, keyframes, graph), the loop closers, the solves, and the frame loop's wait for data.
# Usage: scripts/bench/throughput.sh [--config INI] [--recordings DIR] [--slam BINARY] [SCENARIO.ini ...]
#   --config      SLAM INI (default config_ini/slam/slam.ini)
#   --recordings  keep the recorded rawlogs in DIR and reuse them when there (they are large:
#                 paper_loop is 7 GB with its images)
#   --slam        another lodestone-slam (e.g. a build of an earlier commit, for "before")
#   --image-format png|jpg|jpg:Q   colour files as lodestone-sim writes them (default png)
#   --gzip        record NAME.rawlog.gz (depth deflated) instead of NAME.rawlog
#   default scenarios: office and paper_loop
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
config="$root/config_ini/slam/slam.ini"
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
[ ${#scenarios[@]} -gt 0 ] || scenarios=("$root/config_ini/scenarios/office.ini" "$root/config_ini/scenarios/paper_loop.ini")
json() { python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }
stages="$out/stages.md"
: > "$stages"
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
        python3 - "$report" "$name" "$cores" >> "$stages" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
t, e = r["timing"], r["engine"]
st = e["node_decider"]["stats"]
frames = max(1, st.get("rgbd_frames", 1))
vo = st.get("vo_ms_per_frame", {})
ms = lambda s: "%.2f" % (1e3 * s / frames) if s is not None else "-"
voSum = sum(vo.get(k, 0) for k in ("orb", "matching", "ransac"))
nrdRest = 1e3 * e["stage_seconds"]["node_decider_s"] / frames - voSum
cells = [ms(t.get("worker_read_s")), ms(t.get("worker_decode_s"))]
cells += ["%.2f" % vo[k] if k in vo else "-" for k in ("orb", "matching", "ransac")]
cells += ["%.2f" % nrdRest, ms(e["stage_seconds"]["edge_decider_s"]),
          ms(e["stage_seconds"]["optimizer_s"]), ms(t["source_s"])]
print("| %s | %s | %s |" % (sys.argv[2], sys.argv[3], " | ".join(cells)))
PY
        rm -rf "$out/run"
    done
    [ -n "$recordings" ] || rm -rf "$out/$name"*
done
echo
echo "Per RGB-D frame [ms]: read and decode on the workers (their CPU time), the rest in the frame"
echo "loop (wall time: on one core it includes the turns the workers took):"
echo
echo "| scenario | cores | read | decode | ORB | matching | RANSAC | node decider, rest | loop closers | solves | frame loop waiting for data |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
cat "$stages"
