#!/usr/bin/env bash
# The dense model (lodestone-slam --mesh), printed as markdown: each scenario recorded by the
# simulator to disk, run from disk without and with --mesh, the mesh judged against the
# simulated world (bench_mesh_accuracy: its vertices' distance to the nearest wall, floor or
# ceiling after the trajectory's rigid alignment to the truth; completeness: the share of the
# surface the camera saw within 3 m that has a vertex within 2 cm), the mesh pass's wall time
# against the run's and the peak memory of each.
# Usage: [CONFIG=slam.ini] [FLAGS="--handheld --gyro"] scripts/bench/mesh.sh [SEED] [SCENARIO.ini ...]
#        (default seed 1; office, paper_loop and corridor with slam.ini; FLAGS are lodestone-sim's
#        carrier flags, e.g. CONFIG=rgbd_only.ini FLAGS="--handheld --gyro" for the hand-held loop)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
cmake --build "$root/build" --target bench_mesh_accuracy > /dev/null
slam="$root/build/apps/lodestone-slam/lodestone-slam"
sim="$root/build/apps/lodestone-sim/lodestone-sim"
accuracy="$root/build/bench/bench_mesh_accuracy"
config="$root/config_ini/slam/${CONFIG:-slam.ini}"
seed=${1:-1}
shift || true
scenarios=("$@")
[[ ${#scenarios[@]} -gt 0 ]] || scenarios=("$root/config_ini/scenarios/office.ini" "$root/config_ini/scenarios/paper_loop.ini"
                                          "$root/config_ini/scenarios/corridor.ini")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
read -r -a flags <<< "${FLAGS:-}"

echo "| scenario | carrier | keyframes fused | vertices | distance to the world: median / p95 / mean [m] | within 1 cm / 2 cm | seen surface within 2 cm | ATE [m] | run without --mesh [s] | mesh pass [s] (share of the run) | peak memory without / with [MB] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for ini in "${scenarios[@]}"; do
    name=$(basename "$ini" .ini)
    "$sim" -c "$ini" -o "$out/$name.rawlog" -s "$seed" "${flags[@]}" > /dev/null
    source=(--rawlog "$out/$name.rawlog" --ground-truth "$out/$name.gt.tum" --config "$config" --quiet)
    /usr/bin/time -f "%e %M" -o "$out/without.time" "$slam" "${source[@]}" --out "$out/without" > /dev/null
    /usr/bin/time -f "%e %M" -o "$out/with.time" "$slam" "${source[@]}" --out "$out/with" --mesh > /dev/null
    read -r wallA rssA < "$out/without.time"
    read -r _ rssB < "$out/with.time"
    row=$("$accuracy" "$ini" "$out/with" "$out/$name.gt.tum" 2> /dev/null)
    IFS='|' read -r _ vertices median p95 mean w1 w2 ate complete _ <<< "$row"
    python3 - "$out/with/report.json" "$wallA" "$rssA" "$rssB" "$name" "${FLAGS:-robot}" \
        "$vertices" "$median" "$p95" "$mean" "$w1" "$w2" "$ate" "$complete" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["mesh"]
wall, rssA, rssB = float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
name, carrier, vertices, median, p95, mean, w1, w2, ate, complete = [a.strip() for a in sys.argv[5:]]
print(f"| {name} | {carrier} | {r['frames_fused']} of {r['keyframes']} | {vertices} | {median} / {p95} / {mean} | "
      f"{w1} / {w2} | {complete} | {ate} | {wall:.1f} | {r['seconds']:.1f} ({r['seconds'] / wall:.0%}) | {rssA / 1024:.0f} / {rssB / 1024:.0f} |")
PY
    rm -rf "$out/without" "$out/with" "$out/$name"*
done
