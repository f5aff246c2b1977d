#!/usr/bin/env bash
# VO's gaps bridged by the gyro: a simulated scenario recorded to disk with an IMU
# (--gyro), on the robot with the camera alone and carried by hand, for each seed; run from
# rgbd_only.ini two ways - the gyro's rotation with the fading velocity's translation (fading),
# and the same corrected by the gap frames' depth (bridge_by_depth: odometry::DepthBridge). One
# table: the ATE of each run, its gaps and how they were bridged, and the edges across gaps of a
# second or more against the truth (scripts/bench/gap_edges.py); then median and worst by seed.
# Usage: scripts/bench/gap_bridges.sh ["SEED..."] [SCENARIO.ini]
#        (default seeds "1 2 3" of paper_loop.ini, 640x480 at 30 Hz: about 25 minutes a seed on
#        2 cores, and 25 GB of disk while a seed runs; REC_DIR=DIR reads DIR/{cam,hand}SEED.rawlog
#        where they exist instead of recording them, and keeps what it records there)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
sim="$root/build/apps/lodestone-sim/lodestone-sim"
slam="$root/build/apps/lodestone-slam/lodestone-slam"
seeds=${1:-1 2 3}
scenario=${2:-$root/config_ini/scenarios/paper_loop.ini}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
recordings=${REC_DIR:-$out}
base="$root/config_ini/slam/rgbd_only.ini"
source "$root/scripts/bench/ini_variant.bash"
variants=(fading depth)
variant fading bridge_by_depth=false
variant depth bridge_by_depth=true
echo "| carrier | seed | gap bridge | ATE [m] | VO gaps | bridged by the gyro | of them corrected by depth | relocalized | gap edges >= 1 s against the truth [m] |"
echo "|---|---|---|---|---|---|---|---|---|"
results="$out/results.txt"
: > "$results"
for carrier in camera hand; do
    case $carrier in
        camera) flags=(--camera-only --gyro) tag=cam ;;
        hand) flags=(--handheld --gyro) tag=hand ;;
    esac
    for seed in $seeds; do
        rawlog="$recordings/$tag$seed.rawlog"
        [[ -f $rawlog ]] || "$sim" -c "$scenario" -o "$rawlog" -s "$seed" "${flags[@]}" > /dev/null
        for v in "${variants[@]}"; do
            run="$out/$carrier-$seed-$v"
            ate=$("$slam" --rawlog "$rawlog" --ground-truth "${rawlog%.rawlog}.gt.tum" \
                --config "$out/$v.ini" --out "$run" --quiet | grep -o "ATE RMSE [0-9.]*" | awk '{print $3}')
            edges=$("$root/scripts/bench/gap_edges.py" "$run" "${rawlog%.rawlog}.gt.tum" 1.0)
            echo "| $carrier | $seed | $v | $ate | $(field "$run/report.json" vo_gaps) |" \
                "$(field "$run/report.json" vo_gaps_bridged_by_gyro) |" \
                "$(d=$(field "$run/report.json" vo_gaps_bridged_by_depth); echo "${d:--}") |" \
                "$(field "$run/report.json" vo_gaps_relocalized) | $edges |"
            echo "$carrier $v $ate" >> "$results"
        done
        [[ -n ${REC_DIR:-} ]] || rm -rf "$rawlog" "${rawlog%.rawlog}_Images"
    done
done
echo
echo "| carrier | gap bridge | ATE median / worst over seeds $seeds [m] |"
echo "|---|---|---|"
for carrier in camera hand; do
    for v in "${variants[@]}"; do
        awk -v c="$carrier" -v v="$v" '$1 == c && $2 == v {print $3}' "$results" | sort -g |
            awk -v c="$carrier" -v v="$v" '{a[NR] = $1}
                END {m = NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2;
                     printf "| %s | %s | %.4f / %.4f |\n", c, v, m, a[NR]}'
    done
done
