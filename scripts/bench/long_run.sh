#!/usr/bin/env bash
# A one-hour run: paper_kidnap.ini driven for LAPS laps (default 28: about 3 600 s
# of data; its five kidnaps stay in laps 4-5), simulated at 640x480 / 30 Hz into lodestone-slam
# with slam.ini. Prints a markdown table: data and wall time, peak RSS (/usr/bin/time), nodes,
# ATE, and the engine's mean time per node in each tenth of the run (flat: no growth with the
# graph).
# Usage: scripts/bench/long_run.sh [--laps N] [--camera WxH@HZ] [--config INI] [--keep DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
laps=28
camera=""
config="$root/config_ini/slam/slam.ini"
keep=""
while [ $# -gt 0 ]; do
    case "$1" in
        --laps) laps=$2; shift 2 ;;
        --camera) camera=$2; shift 2 ;;
        --config) config=$2; shift 2 ;;
        --keep) keep=$2; shift 2 ;;
        *) echo "usage: $0 [--laps N] [--camera WxH@HZ] [--config INI] [--keep DIR]" >&2; exit 2 ;;
    esac
done
"$root/scripts/build.sh" > /dev/null
out=${keep:-$(mktemp -d)}
mkdir -p "$out"
[ -n "$keep" ] || trap 'rm -rf "$out"' EXIT
ini="$out/long_run.ini"
sed -e "s/^name *=.*/name       = long_run/" -e "s/^laps *=.*/laps      = $laps/" \
    "$root/config_ini/scenarios/paper_kidnap.ini" > "$ini"
if [ -n "$camera" ]; then
    w=${camera%%x*}; rest=${camera#*x}; h=${rest%%@*}; hz=${rest#*@}
    sed -i -e "/^\[camera\]/,/^\[/ s/^width *=.*/width      = $w/" \
        -e "/^\[camera\]/,/^\[/ s/^height *=.*/height     = $h/" \
        -e "/^\[camera\]/,/^\[/ s/^rate *=.*/rate       = $hz/" "$ini"
fi
/usr/bin/time -f "%e %M" -o "$out/time.txt" "$root/build/apps/lodestone-slam/lodestone-slam" \
    --sim "$ini" --config "$config" --out "$out/run" --quiet > "$out/run.log" 2>&1 || {
    cat "$out/run.log" >&2
    exit 1
}
read -r wall rss < "$out/time.txt"
python3 - "$out/run/report.json" "$wall" "$rss" "$laps" "${camera:-640x480@30}" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
wall, rss, laps, camera = float(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5]
t = r["timing"]
deciles = " / ".join("%.1f" % d for d in t["node_ms_by_decile"])
print("| laps | camera | data [s] | wall [s] | peak RSS [MB] | nodes | loop closures | relocations | ATE [m] | node ms mean / p99 / max | node ms by decile |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
c = r["engine"]["counts"]
print("| %s | %s | %.0f | %.0f | %d | %d | %d | %d | %.4f | %.1f / %.1f / %.0f | %s |" % (
    laps, camera, t["data_s"], wall, rss // 1024, c["nodes"], c["loop_closures"], c["relocations"],
    r.get("ate", {}).get("rmse_m", float("nan")),
    t["node_ms"]["mean"], t["node_ms"]["p99"], t["node_ms"]["max"], deciles))
PY
