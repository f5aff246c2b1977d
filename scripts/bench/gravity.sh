#!/usr/bin/env bash
# The accelerometer's up as a prior on each node's roll and pitch: a simulated
# scenario recorded to disk with an IMU (--gyro: its rate gyro and accelerometer), on the robot
# with the camera alone and carried by hand, for each seed; run from rgbd_only.ini four ways -
# VO's edges with and without their translation-rotation correlations (edge_cross_covariance),
# each without and with the measured ups (use_gravity). One table: the ATE of each run, the
# nodes given an up, and the worst over the seeds.
# Usage: scripts/bench/gravity.sh [SEEDS] [SCENARIO.ini]
#        (default 1 seed of paper_loop.ini, 640x480 at 30 Hz: about 40 minutes a seed on 2 cores)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
sim="$root/build/apps/lodestone-sim/lodestone-sim"
slam="$root/build/apps/lodestone-slam/lodestone-slam"
seeds=${1:-1}
scenario=${2:-$root/config_ini/scenarios/paper_loop.ini}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
base="$root/config_ini/slam/rgbd_only.ini"
source "$root/scripts/bench/ini_variant.bash"
variants=(cross cross+gravity block block+gravity)
variant cross edge_cross_covariance=true use_gravity=false
variant cross+gravity edge_cross_covariance=true use_gravity=true
variant block edge_cross_covariance=false use_gravity=false
variant block+gravity edge_cross_covariance=false use_gravity=true
echo "| carrier | seed | VO edges | measured ups | nodes given an up | ATE [m] |"
echo "|---|---|---|---|---|---|"
results="$out/results.txt"
: > "$results"
for carrier in camera hand; do
    case $carrier in
        camera) flags=(--camera-only --gyro) ;;
        hand) flags=(--handheld --gyro) ;;
    esac
    for seed in $(seq 1 "$seeds"); do
        rawlog="$out/$carrier-$seed.rawlog"
        "$sim" -c "$scenario" -o "$rawlog" -s "$seed" "${flags[@]}" > /dev/null
        for v in "${variants[@]}"; do
            run="$out/$carrier-$seed-$v"
            ate=$("$slam" --rawlog "$rawlog" --ground-truth "${rawlog%.rawlog}.gt.tum" \
                --config "$out/$v.ini" --out "$run" --quiet | grep -o "ATE RMSE [0-9.]*" | awk '{print $3}')
            ups=$(field "$run/report.json" nodes_with_measured_up)
            edges=${v%%+*}
            [[ $v == *gravity ]] && g=yes || g=no
            echo "| $carrier | $seed | $edges | $g | ${ups:--} | $ate |"
            echo "$carrier $v $ate" >> "$results"
        done
        rm -rf "$rawlog" "${rawlog%.rawlog}_Images"
    done
done
echo
echo "| carrier | VO edges | measured ups | ATE median / worst over $seeds seed(s) [m] |"
echo "|---|---|---|---|"
for carrier in camera hand; do
    for v in "${variants[@]}"; do
        [[ $v == *gravity ]] && g=yes || g=no
        awk -v c="$carrier" -v v="$v" '$1 == c && $2 == v {print $3}' "$results" | sort -g |
            awk -v c="$carrier" -v e="${v%%+*}" -v g="$g" '{a[NR] = $1}
                END {m = NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2;
                     printf "| %s | %s | %s | %.4f / %.4f |\n", c, e, g, m, a[NR]}'
    done
done
