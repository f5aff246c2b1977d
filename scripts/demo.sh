#!/usr/bin/env bash
# Set-up command 1: installs what is missing, builds Release and runs the main job on the
# bundled sample rawlog. Results go to out/demo/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"

out="$root/out/demo"
mkdir -p "$out"
sample="$root/rawlogs/sample_drive.rawlog.gz"
inspect="$root/build/apps/lodestone-inspect/lodestone-inspect"
"$inspect" summary "$sample" | tee "$out/summary.txt"
"$inspect" export "$sample" --sensor MAG_LEFT --out "$out/MAG_LEFT"
"$inspect" to-imu "$sample" "$out/sample_drive_imu.rawlog.gz"
echo
echo "demo: results in $out"
echo "  summary.txt                 the rawlog summary above"
echo "  MAG_LEFT/MAG_LEFT.csv       the left magnetometer series [uT]"
echo "  sample_drive_imu.rawlog.gz  the same rawlog for stock MRPT tools (RawLogViewer, rawlog-edit)"
