#!/usr/bin/env bash
# Real time from disk (the target: camera-only at 640x480 >= 2x real time on 2 cores): recordings that
# exist (REC.rawlog with REC.gt.tum beside it, e.g. camera_only.sh's REC_DIR, or lodestone-sim
# -c config_ini/scenarios/paper_loop.ini -o REC.rawlog -s SEED --handheld --gyro), each run
# alone as a user runs it - the whole process, start to outputs written - one after another,
# nothing else should be running. One markdown row per recording: wall time, the real-time
# factor, CPU (user + system), peak RSS (/usr/bin/time), and per RGB-D frame the decode-ahead
# workers' reading and decoding, their preparing of the frame (features, depth cloud), and the
# frame loop's node decider (report.json); ATE.
# Usage: scripts/bench/realtime.sh [--config INI] [--decode-ahead N] REC.rawlog ...
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
config="$root/config_ini/slam/rgbd_only.ini"
ahead=()
while [ $# -gt 0 ]; do
    case "$1" in
        --config) config=$2; shift 2 ;;
        --decode-ahead) ahead=(--decode-ahead "$2"); shift 2 ;;
        *) break ;;
    esac
done
[ $# -gt 0 ] || { echo "usage: $0 [--config INI] [--decode-ahead N] REC.rawlog ..." >&2; exit 2; }
"$root/scripts/build.sh" > /dev/null
slam="$root/build/apps/lodestone-slam/lodestone-slam"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| recording | frames | data [s] | wall [s] | real-time factor | CPU [s] | peak RSS [MB] | read + decode ms / frame | prepare ms / frame | node decider ms / frame | ATE [m] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for rec in "$@"; do
    gt="${rec%.rawlog}.gt.tum"
    gt="${gt%.rawlog.gz}"
    truth=()
    [ -f "$gt" ] && truth=(--ground-truth "$gt")
    /usr/bin/time -f "%e %U %S %M" -o "$out/time.txt" "$slam" -r "$rec" --config "$config" \
        "${truth[@]}" "${ahead[@]}" --out "$out/run" --quiet > "$out/run.log" 2>&1
    read -r wall user sys rss < "$out/time.txt"
    python3 - "$out/run/report.json" "$rec" "$wall" "$user" "$sys" "$rss" <<'PY'
import json, os, sys
report, rec, wall, user, sys_s, rss = sys.argv[1:]
r = json.load(open(report))
t, e = r["timing"], r["engine"]
frames = e["counts"]["rgbd_frames"] or 1
per = lambda s: f"{1e3 * s / frames:.1f}"
ate = r.get("ate", {}).get("rmse_m")
print(f"| {os.path.basename(rec)} | {e['counts']['rgbd_frames']} | {t['data_s']:.1f} | {float(wall):.1f} "
      f"| {t['data_s'] / float(wall):.2f}x | {float(user) + float(sys_s):.0f} | {int(rss) / 1024:.0f} "
      f"| {per(t.get('worker_read_s', 0) + t.get('worker_decode_s', 0))} | {per(t.get('worker_prepare_s', 0))} "
      f"| {per(e['stage_seconds']['node_decider_s'])} | {ate if ate is None else f'{ate:.4f}'} |")
PY
done
