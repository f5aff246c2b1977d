#!/usr/bin/env bash
# What chooses VO's keyframes: corridor_floor.ini carried by hand (lodestone-sim
# --handheld --gyro, 640x480 at 30 Hz, recorded to disk), its texture only on the floor 3-5 m
# ahead, where VO's steps are noisiest. rgbd_only.ini run frame by frame against the truth
# (bench/bench_depth_alignment.cpp) four ways: features only or features and depth as one
# (joined), each with its keyframes chosen by the frame's measured motion or by what was known
# before it (keyframe_by). Per run: the length error of every step, by how it was found, and of
# the keyframe chain - the steps VO's motion is chained through (each step's estimate along
# its true direction against its true length, summed; with its standard error).
# Usage: scripts/bench/keyframe_chain.sh ["SEED..."]   (default 1; about 20 minutes a seed on
#        2 cores and 3 GB of disk while its recording is in use; REC_DIR=DIR reads
#        DIR/corridor_floorSEED.rawlog where it exists and keeps what it records there)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
sim="$root/build/apps/lodestone-sim/lodestone-sim"
bench="$root/build/bench/bench_depth_alignment"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
base="$root/config_ini/slam/rgbd_only.ini"
source "$root/scripts/bench/ini_variant.bash"
variant features-measured depth_alignment=false keyframe_by=measured
variant features-predicted depth_alignment=false keyframe_by=predicted
variant joined-measured depth_alignment=true depth_with_features=true keyframe_by=measured
variant joined-predicted depth_alignment=true depth_with_features=true keyframe_by=predicted
echo "| seed, VO, keyframes by | found by | steps | translation error median / RMS [mm] | rotation RMS [deg] | length error [%] |"
echo "|---|---|---|---|---|---|"
for seed in ${1:-1}; do
    rec="${REC_DIR:-$out}/corridor_floor$seed.rawlog"
    [[ -f $rec ]] || "$sim" -c "$root/config_ini/scenarios/corridor_floor.ini" -o "$rec" -s "$seed" --handheld --gyro > /dev/null
    for v in features-measured features-predicted joined-measured joined-predicted; do
        "$bench" "$rec" "${rec%.rawlog}.gt.tum" "$out/$v.ini" "$seed, $v" 2> /dev/null |
            grep -E "ORB|keyframe chain" | awk -F' [|] ' '{printf "| %s | %s | %s | %s | %s | %s |\n", substr($1, 3), $2, $3, $4, $5, $6}'
    done
    [[ -n ${REC_DIR:-} ]] || rm -rf "$rec" "${rec%.rawlog}"{.gt.tum,.events.txt,_Images}
done
