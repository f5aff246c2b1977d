#!/usr/bin/env bash
# The dense model (lodestone-slam --mesh), printed as markdown: each scenario recorded by the
# simulator to disk, run from disk without and with --mesh, the mesh judged against the
# simulated world (bench_mesh_accuracy: its vertices' distance to the nearest wall, floor or
# ceiling after the trajectory's rigid alignment to the truth; completeness: the share of the
# surface the camera saw within 3 m that has a vertex within 2 cm, and the share it shows twice),
# the wall time --mesh adds to the run and the peak memory of each.
# Usage: [CONFIG=slam.ini] [FLAGS="--handheld --gyro"] [VOLUME=blocks|open3d] [FUSION=after_run|while_running]
#        scripts/bench/mesh.sh [SEED] [SCENARIO.ini ...]
#        (default seed 1; office, paper_loop and corridor with slam.ini; FLAGS are lodestone-sim's
#        carrier flags, e.g. CONFIG=rgbd_only.ini FLAGS="--handheld --gyro" for the hand-held loop;
#        VOLUME the [dense] volume: ours, the default, or Open3D's; FUSION=while_running fuses
#        keyframes as the run makes them instead of after it; REC_DIR keeps the recordings there
#        and reuses them; the real 3DMatch frames follow where ../shared/data has them, unless NO_REAL=1)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
cmake --build "$root/build" --target bench_mesh_accuracy bench_mesh_real > /dev/null
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
if [[ -n ${VOLUME:-}${FUSION:-} ]]; then
    { cat "$config"; printf '\n[dense]\nvolume = %s\nfusion = %s\n' "${VOLUME:-blocks}" "${FUSION:-after_run}"; } > "$out/config.ini"
    config="$out/config.ini"
fi

echo "| scenario | carrier | keyframes fused | vertices | distance to the world: median / p95 / mean [m] | within 1 cm / 2 cm | seen surface within 2 cm / doubled | ATE [m] | run without --mesh [s] | --mesh adds [s] (share of the run) | fusing / meshing [s] | volume [MB] | peak memory without / with [MB] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for ini in "${scenarios[@]}"; do
    name=$(basename "$ini" .ini)
    rec="${REC_DIR:-$out}/${name}_s${seed}${FLAGS:+_$(echo "$FLAGS" | tr -d ' -')}"
    [[ -f $rec.rawlog ]] || "$sim" -c "$ini" -o "$rec.rawlog" -s "$seed" "${flags[@]}" > /dev/null
    source=(--rawlog "$rec.rawlog" --ground-truth "$rec.gt.tum" --config "$config" --quiet)
    /usr/bin/time -f "%e %M" -o "$out/without.time" "$slam" "${source[@]}" --out "$out/without" > /dev/null
    /usr/bin/time -f "%e %M" -o "$out/with.time" "$slam" "${source[@]}" --out "$out/with" --mesh > /dev/null
    read -r wallA rssA < "$out/without.time"
    read -r wallB rssB < "$out/with.time"
    handheld=()
    [[ " ${FLAGS:-} " == *" --handheld "* ]] && handheld=(--handheld)
    row=$("$accuracy" "$ini" "$out/with" "$rec.gt.tum" "${handheld[@]}" 2> /dev/null)
    IFS='|' read -r _ vertices median p95 mean w1 w2 ate complete doubled _ <<< "$row"
    python3 - "$out/with/report.json" "$wallA" "$wallB" "$rssA" "$rssB" "$name" "${FLAGS:-robot}" \
        "$vertices" "$median" "$p95" "$mean" "$w1" "$w2" "$ate" "$complete" "$doubled" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["mesh"]
wall, wallB, rssA, rssB = float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
name, carrier, vertices, median, p95, mean, w1, w2, ate, complete, doubled = [a.strip() for a in sys.argv[6:]]
# (after the run: fusing and meshing in the pass; while running: the worker's fusing, overlapping the run)
fuse = r.get("integrate_seconds", r.get("fuse_seconds", float("nan")))
print(f"| {name} | {carrier} | {r['frames_fused']} of {r['keyframes']} | {vertices} | {median} / {p95} / {mean} | "
      f"{w1} / {w2} | {complete} / {doubled} | {ate} | {wall:.1f} | {wallB - wall:.1f} ({(wallB - wall) / wall:.0%}) | {fuse:.2f} / {r['extract_seconds']:.2f} | {r.get('volume_mb', float('nan')):.0f} | {rssA / 1024:.0f} / {rssB / 1024:.0f} |")
PY
    rm -rf "$out/without" "$out/with"
done
data="$root/../shared/data/rgbd/3dmatch"
if [[ -d $data && -z ${NO_REAL:-} ]]; then
    echo
    echo "### Real Kinect frames (3DMatch seq-01, read in place, at the dataset's poses)"
    echo
    echo "| volume | frames | vertices | fusing a frame [ms] | meshing [s] | volume [MB] | resident memory added [MB] | a left-out frame's depth to the others' mesh: median / p95 [m] | within 1 cm |"
    echo "|---|---|---|---|---|---|---|---|---|"
    for volume in blocks open3d; do "$root/build/bench/bench_mesh_real" "$data" "$volume"; done
fi
