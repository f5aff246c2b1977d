#!/usr/bin/env bash
# Remakes the small rawlogs committed in rawlogs/ (see rawlogs/README.md). Deterministic: the same
# code gives the same bytes.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" > /dev/null
cd "$root/rawlogs"
"$root/build/tests/make_sample_rawlog" sample_drive.rawlog.gz
"$root/build/apps/lodestone-sim/lodestone-sim" --config "$root/config_ini/scenarios/office.ini" \
    --camera 320x240@2 --embedded-images --out office_qvga.rawlog.gz
du -sh "$root/rawlogs"
