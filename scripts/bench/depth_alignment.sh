#!/usr/bin/env bash
# Depth alignment where VO's features fail: a simulated scenario recorded to disk
# carried by hand (--handheld) and on the robot with the camera alone (--camera-only), each
# without and with a simulated gyro (--gyro: its own noise stream, the camera's frames the
# same). Without: run five ways from rgbd_only.ini - features only; depth alignment where the
# features fail, accepting a motion that pins 5 of 6 directions (a corridor, a wall and the
# floor) or 4; and both with features and depth solved as one where both align (joined5). With
# the gyro (use_gyro): not used (joined5-nogyro); its rotation only starting the depth alignment
# (-nobridge); also bridging VO's gaps (joined5+gyro: as shipped); its rotation and the depth
# solved as one through the gaps, counting where the depth pins 4 or 3 (-depth4, -depth3). Two
# tables:
#   1. every VO step against the truth (bench/bench_depth_alignment.cpp): how it was found, its
#      translation error (median / RMS), rotation error, its length error (the estimate along the
#      true direction against the true length, summed: VO's steps short or long), the error along the directions its
#      covariance calls pinned and along the rest, and the NEES per pinned direction (1: honest);
#   2. the SLAM run: ATE; the ATE of each VO segment aligned on its own, pooled (lodestone-eval
#      segments): the odometry's own accuracy, apart from where the segments were placed; VO
#      gaps (count, seconds, longest), segments, real-time factor.
# Usage: [CARRIERS="hand+gyro camera+gyro"] scripts/bench/depth_alignment.sh [SCENARIO.ini]
#        (default paper_loop_qvga.ini and all four carriers: about 40 minutes; paper_loop.ini is
#        640x480 at 30 Hz and takes hours)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
sim="$root/build/apps/lodestone-sim/lodestone-sim"
slam="$root/build/apps/lodestone-slam/lodestone-slam"
bench="$root/build/bench/bench_depth_alignment"
scenario=${1:-$root/config_ini/scenarios/paper_loop_qvga.ini}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
base="$root/config_ini/slam/rgbd_only.ini"
source "$root/scripts/bench/ini_variant.bash"
variant features depth_alignment=false
variant depth5 depth_alignment=true depth_with_features=false depth_min_observed=5
variant depth4 depth_alignment=true depth_with_features=false depth_min_observed=4
variant joined5 depth_alignment=true depth_with_features=true depth_min_observed=5
variant joined4 depth_alignment=true depth_with_features=true depth_min_observed=4
variant joined5-nogyro depth_alignment=true depth_with_features=true depth_min_observed=5 use_gyro=false
variant joined5+gyro depth_alignment=true depth_with_features=true depth_min_observed=5 use_gyro=true
variant joined4+gyro depth_alignment=true depth_with_features=true depth_min_observed=4 use_gyro=true
variant joined5+gyro-nobridge depth_alignment=true depth_with_features=true depth_min_observed=5 use_gyro=true gyro_bridge_max_seconds=0
variant joined5+gyro-depth4 depth_alignment=true depth_with_features=true depth_min_observed=5 use_gyro=true gyro_depth_min_observed=4
variant joined5+gyro-depth3 depth_alignment=true depth_with_features=true depth_min_observed=5 use_gyro=true gyro_depth_min_observed=3
segmentAte() {  # RUN_DIR GT: each VO segment aligned on its own, pooled (lodestone-eval segments)
    "$root/build/apps/lodestone-eval/lodestone-eval" segments "$1" --ground-truth "$2" |
        grep -o "on its own: ATE RMSE [0-9.]*" | awk '{printf "%.3f", $NF}'
}
gaps() {  # REPORT KEY: count, seconds, longest of report.json's list KEY (vo_gap_seconds, ...)
    tr -d '\n ' < "$1" | grep -o "\"$2\":\\[[^]]*\\]" | sed 's/.*\[//; s/\]//' |
        awk -F, '{n = 0; s = 0; m = 0; for (i = 1; i <= NF; ++i) if ($i != "") {n++; s += $i; if ($i > m) m = $i}
                  printf "%d | %.1f | %.1f", n, s, m}'
}
unbridged() {  # REPORT: gaps that opened a segment (count, longest [s])
    gaps "$1" vo_unbridged_gap_seconds | awk -F' [|] ' '{printf "%d (%.1f)", $1, $3}'
}
steps="$out/steps.md"
runs="$out/runs.md"
: > "$steps"
: > "$runs"
for carrier in ${CARRIERS:-hand camera hand+gyro camera+gyro}; do
    variants=(features depth5 depth4 joined5 joined4)
    case $carrier in
        hand) flags=(--handheld) ;;
        camera) flags=(--camera-only) ;;
        # The same hand with a gyro (its own noise stream: the camera's frames are the same).
        hand+gyro) flags=(--handheld --gyro)
            variants=(joined5-nogyro joined5+gyro-nobridge joined5+gyro joined4+gyro joined5+gyro-depth4 joined5+gyro-depth3) ;;
        camera+gyro) flags=(--camera-only --gyro); variants=(joined5-nogyro joined5+gyro joined5+gyro-depth4) ;;
    esac
    "$sim" -c "$scenario" -o "$out/$carrier.rawlog" "${flags[@]}" > /dev/null
    for v in "${variants[@]}"; do
        # (the steps bench runs VO alone, without the node decider that feeds it the gyro)
        [[ $carrier == *+gyro ]] ||
            "$bench" "$out/$carrier.rawlog" "$out/$carrier.gt.tum" "$out/$v.ini" "$carrier, $v" >> "$steps" 2> /dev/null
        log=$("$slam" -r "$out/$carrier.rawlog" --config "$out/$v.ini" --ground-truth "$out/$carrier.gt.tum" \
            --out "$out/run" --quiet 2>&1 | grep -v "^\[")
        ate=$(echo "$log" | grep -o "ATE RMSE [0-9.]*" | awk '{print $3}')
        rt=$(echo "$log" | grep -o "([0-9.]*x real time)" | tr -d '()' | awk '{print $1}')
        echo "| $carrier | $v | $ate | $(segmentAte "$out/run" "$out/$carrier.gt.tum") | $(gaps "$out/run/report.json" vo_gap_seconds) | $(unbridged "$out/run/report.json") | $(field "$out/run/report.json" segments) | $rt |" >> "$runs"
        rm -rf "$out/run"
    done
done
if [ -s "$steps" ]; then  # (none when only the gyro carriers ran: VO alone has no gyro)
    echo "#### Every VO step against the truth ($(basename "$scenario"), read from disk)"
    echo
    echo "| carrier, INI | found by | steps | translation error median / RMS [mm] | rotation RMS [deg] | length error [%] | along pinned directions RMS [mm] | along loose directions RMS [mm] | NEES per pinned direction |"
    echo "|---|---|---|---|---|---|---|---|---|"
    cat "$steps"
    echo
fi
echo "#### SLAM (lodestone-slam, rgbd_only.ini and the variants)"
echo
echo "| carrier | VO | ATE [m] | ATE of each VO segment on its own, pooled [m] | VO gaps | gap seconds | longest gap [s] | gaps left unbridged (longest [s]) | segments | real-time factor |"
echo "|---|---|---|---|---|---|---|---|---|---|"
cat "$runs"
