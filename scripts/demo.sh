#!/usr/bin/env bash
# Set-up command 1: installs what is missing, builds Release - the apps and the MRPT plugin only,
# not the tests and benchmarks (scripts/test.sh builds those into the same tree) - and runs the
# main job, lodestone-slam, on embedded defaults:
#   1. the bundled rawlog rawlogs/office_qvga.rawlog.gz, against its ground truth;
#   2. the office scenario simulated on the fly (640x480 at 30 Hz), against the simulator's truth.
# Prints the ATE of each and where the outputs are (out/demo/).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh" --apps

out="$root/out/demo"
rm -rf "$out"
mkdir -p "$out"
slam="$root/build/apps/lodestone-slam/lodestone-slam"
inspect="$root/build/apps/lodestone-inspect/lodestone-inspect"
sample="$root/rawlogs/office_qvga.rawlog.gz"

"$inspect" summary "$sample" > "$out/summary.txt"
echo "== lodestone-slam on the bundled rawlog $sample"
"$slam" --rawlog "$sample" --ground-truth "${sample%.rawlog.gz}.gt.tum" \
    --config "$root/config_ini/slam/slam.ini" --out "$out/bundled"
echo
echo "== lodestone-inspect report of the bundled rawlog and that run"
"$inspect" report "$sample" --out "$out/report" --slam "$out/bundled" \
    --ground-truth "${sample%.rawlog.gz}.gt.tum" -q
echo
echo "== lodestone-slam on the office scenario, simulated on the fly"
"$slam" --sim "$root/config_ini/scenarios/office.ini" --config "$root/config_ini/slam/slam.ini" \
    --out "$out/office"
echo
echo "== lodestone-view: the office run in 3D, off-screen"
"$root/build/apps/lodestone-view/lodestone-view" "$out/office" --screenshot "$out/office/view3d.png"
echo
echo "demo: results in $out"
echo "  bundled/, office/  trajectory.tum (every node), graph.graph (MRPT), map.ply (keyframe"
echo "                     clouds), report.json (counts, timings, ATE), graph.png, trajectory.png,"
echo "                     field_map.png (|B| on the optimized trajectory), nodes.csv"
echo "  office/view3d.png  the office run in 3D (lodestone-view DIR opens it in MRPT's window)"
echo "  report/index.html  the visual report of the bundled rawlog and its SLAM run"
echo "  office/ground_truth.tum  the simulator's truth"
echo "  summary.txt        lodestone-inspect summary of the bundled rawlog"
