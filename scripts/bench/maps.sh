#!/usr/bin/env bash
# Maps that outlive a run (bench/bench_maps.cpp): a scenario mapped once with --map-out (its
# laps, seed 1, recorded to a rawlog and run from disk), then six one-lap runs in the same
# building started in that map with --map-in (localize): other seeds, another corner, driven the
# other way. Per run: relocated, travel to the first relocation, its error, the ATE of the
# run's nodes in the map's frame (no re-alignment), how far the map's nodes moved. One table
# per SLAM INI; then a map extended through a room it never saw, and localized in there.
# Usage: scripts/bench/maps.sh [SCENARIO.ini] [SLAM.ini ...]
#   (default: paper_loop.ini at 320x240 / 15 Hz with slam.ini, and slam.ini with the GP
#    magnetic closer alone (scripts/bench/window_inis.sh): a few minutes each)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
scenario=${1:-$root/config_ini/scenarios/paper_loop.ini}
shift || true
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
inis=("$@")
if [ ${#inis[@]} -eq 0 ]; then
    "$root/scripts/bench/window_inis.sh" "$out" > /dev/null
    inis=("$root/config_ini/slam/slam.ini" "$out/slam_gp.ini")
fi
for ini in "${inis[@]}"; do
    echo
    echo "#### $(basename "$scenario") at 320x240 / 15 Hz, $(basename "$ini")"
    echo
    mkdir -p "$out/$(basename "$ini" .ini)"
    # (the optimizer logs its rejections on stdout: kept out of the table)
    "$root/build/bench/bench_maps" "$out/$(basename "$ini" .ini)" "$scenario" "$ini" 320x240@15 |
        grep -v "^\["
done
# Extend: paper_kidnap_unmapped.ini's building (the loop and a room beside it that the map never
# saw), mapped on the loop; one run extends the map along a route through the room, another
# localizes in the extended map starting in the room.
echo
echo "#### paper_kidnap_unmapped.ini at 320x240 / 15 Hz, slam.ini: extend through the room, then localize there"
echo
mkdir -p "$out/extend"
"$root/build/bench/bench_maps" "$out/extend" "$root/config_ini/scenarios/paper_kidnap_unmapped.ini" \
    "$root/config_ini/slam/slam.ini" 320x240@15 \
    --extend "1 1 7.5 1 7.5 6 10.5 6 11.5 4 11.5 8 10.5 6.3 7.5 6.3 7.5 12 1 12" 3 | grep -v "^\["
