#!/usr/bin/env bash
# Set-up command 1: installs what is missing, builds Release and runs the main job on embedded
# defaults: inspects the bundled rawlog, then simulates the office scenario. Results go to
# out/demo/. (When offline SLAM lands, the main job becomes lodestone-slam on a scenario.)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"

out="$root/out/demo"
rm -rf "$out"
mkdir -p "$out"
inspect="$root/build/apps/lodestone-inspect/lodestone-inspect"
sim="$root/build/apps/lodestone-sim/lodestone-sim"
sample="$root/rawlogs/office_qvga.rawlog.gz"

"$inspect" summary "$sample" | tee "$out/summary.txt"
"$inspect" export "$sample" --sensor MAG_LEFT --out "$out/MAG_LEFT" > /dev/null
"$sim" --config "$root/config_ini/office.ini" --camera 320x240@15 \
    --out "$out/office.rawlog.gz" --plot "$out/office.png"
"$inspect" to-imu "$out/office.rawlog.gz" "$out/office_imu.rawlog.gz" > /dev/null
echo
echo "demo: results in $out"
echo "  summary.txt            summary of the bundled rawlog rawlogs/office_qvga.rawlog.gz"
echo "  MAG_LEFT/MAG_LEFT.csv  its left magnetometer series [uT]"
echo "  office.rawlog.gz       a fresh simulated run of config_ini/office.ini (QVGA, 15 Hz),"
echo "                         with office.gt.tum (ground truth) and office_Images/"
echo "  office.png             the scenario: floor plan, path, magnetic field magnitude"
echo "  office_imu.rawlog.gz   the same run for stock MRPT tools (RawLogViewer, rawlog-edit)"
