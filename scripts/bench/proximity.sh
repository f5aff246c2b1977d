#!/usr/bin/env bash
# Local closures between keyframes that see the same place (ProximityERD), printed as markdown:
# every scenario and seed run with a SLAM INI as it ships and with ProximityERD added to its
# [CompositeERD] children (nothing else changed), judged against the simulator's truth.
#   - robot: lodestone-slam --sim SCENARIO with slam.ini (the wheels, VO, depth, magnetic);
#   - hand:  recorded hand-held with a gyro (lodestone-sim --handheld --gyro), run from disk
#            with rgbd_only.ini (the camera alone);
#   - camera: recorded by the robot without its wheels (--camera-only --gyro), from disk with
#            rgbd_only.ini.
# IMU="with without" also runs hand and camera without the gyro (use_gyro, use_gravity false).
# Per run: ATE without / with, the proximity links (candidates, aligned by the features, the
# depth joined, refused by the odometry's gate, proposed), the optimizer's refusals, the links'
# error against the truth (median / max, lodestone-eval closures: where a link puts the later
# node), the share inside their own 99.73 % region, and the real-time factor without / with.
# Usage: [CARRIERS="robot hand camera"] [IMU="with without"] [REC_DIR=DIR]
#        scripts/bench/proximity.sh ["SEED..."] [SCENARIO.ini ...]
#        (default: seeds "1 2 3", CARRIERS="robot hand", IMU=with; robot: office and
#        paper_loop_qvga, about a minute a run; hand: linger.ini, about three minutes a seed to
#        record and run; camera: paper_loop.ini. A 640x480 loop takes 7 GB and about 20 minutes
#        a seed: REC_DIR=DIR reads DIR/NAME_{hand,camera}SEED.rawlog where it exists, and what
#        is missing is recorded and removed after its runs)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
slam="$root/build/apps/lodestone-slam/lodestone-slam"
sim="$root/build/apps/lodestone-sim/lodestone-sim"
evaluate="$root/build/apps/lodestone-eval/lodestone-eval"
seeds=${1:-"1 2 3"}
shift || true
carriers=${CARRIERS:-"robot hand"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$root/scripts/bench/ini_variant.bash"

# $1 the INI as it ships -> $out/NAME.ini with ProximityERD among its loop closers
with_proximity() {
    local name
    name=$(basename "$1" .ini)
    sed 's/^children *= */&ProximityERD /' "$1" > "$out/${name}_proximity.ini"
    grep -q "^children *= *ProximityERD " "$out/${name}_proximity.ini" ||
        { echo "no [CompositeERD] children in $1" >&2; exit 1; }
    echo "$out/${name}_proximity.ini"
}

# $1 run folder: "ATE|RT" of its report
ate_rt() {
    echo "$(field "$1/report.json" rmse_m)|$(field "$1/report.json" real_time_factor)"
}

# $1 label, $2 seed, $3 run without, $4 run with, $5 the ground truth
row() {
    local without with links evalRow err inside
    IFS='|' read -r ateA rtA <<< "$(ate_rt "$3")"
    IFS='|' read -r ateB rtB <<< "$(ate_rt "$4")"
    local r="$4/report.json"
    # the ProximityERD child's stats (the first after its class name)
    links=$(python3 -c "
import json, sys
d = json.load(open('$r'))
for c in d['engine']['edge_decider'].get('children', []):
    if c['class'] == 'ProximityERD':
        s = c['stats']
        print(f\"{s['candidates']} / {s['aligned']} / {s['depth_joined']} / {s['refused_by_gate']} / {s['accepted']}\")
")
    evalRow=$("$evaluate" closures "$4" -g "$5" --radius 0.05 2> /dev/null | grep '^| ProximityERD ' || true)
    if [[ -n $evalRow ]]; then
        err=$(echo "$evalRow" | awk -F'|' '{gsub(/ /, "", $7); print $7}')
        kept=$(echo "$evalRow" | awk -F'|' '{gsub(/^ +| +$/, "", $8); print $8}')
        inside=$(echo "$evalRow" | awk -F'|' '{gsub(/^ +| +$/, "", $(NF-1)); print $(NF-1)}')
    else
        err=-; kept=-; inside=-
    fi
    printf "| %s | %s | %.4f / %.4f | %s | %s | %s | %s | %.2fx / %.2fx |\n" "$1" "$2" "$ateA" "$ateB" \
        "$links" "$kept" "$err" "$inside" "$rtA" "$rtB"
}

echo "| run | seed | ATE without / with [m] | links: candidates / aligned / depth joined / refused by the gate / proposed | kept by the optimizer (of them > 5 cm off) | link error median / max [m] | inside their own 99.73 % | real-time factor without / with |"
echo "|---|---|---|---|---|---|---|---|"
for carrier in $carriers; do
    case $carrier in
        robot) scenarios=("$@"); [[ ${#scenarios[@]} -gt 0 ]] ||
                   scenarios=("$root/config_ini/scenarios/office.ini" "$root/config_ini/scenarios/paper_loop_qvga.ini")
               base="$root/config_ini/slam/slam.ini" ;;
        hand) scenarios=("$@"); [[ ${#scenarios[@]} -gt 0 ]] || scenarios=("$root/config_ini/scenarios/linger.ini")
              base="$root/config_ini/slam/rgbd_only.ini" ;;
        camera) scenarios=("$@"); [[ ${#scenarios[@]} -gt 0 ]] || scenarios=("$root/config_ini/scenarios/paper_loop.ini")
                base="$root/config_ini/slam/rgbd_only.ini" ;;
        *) echo "unknown carrier $carrier (robot, hand, camera)" >&2; exit 2 ;;
    esac
    configs=("$base")
    if [[ $carrier != robot ]]; then
        configs=()
        for imu in ${IMU:-with}; do
            case $imu in
                with) configs+=("$base") ;;
                without) variant rgbd_no_imu use_gyro=false use_gravity=false
                         configs+=("$out/rgbd_no_imu.ini") ;;
                *) echo "unknown IMU $imu (with, without)" >&2; exit 2 ;;
            esac
        done
    fi
    for ini in "${scenarios[@]}"; do
        name=$(basename "$ini" .ini)
        for seed in $seeds; do
            recorded=""
            case $carrier in
                robot)
                    sed "s/^seed *=.*/seed = $seed/" "$ini" > "$out/$name.ini"
                    source=(--sim "$out/$name.ini")
                    gt="$out/with/ground_truth.tum" ;;
                hand | camera)
                    flags=(--handheld --gyro)
                    [[ $carrier == camera ]] && flags=(--camera-only --gyro)
                    rawlog="${REC_DIR:-$out}/${name}_$carrier$seed.rawlog"
                    if [[ ! -f $rawlog ]]; then
                        rawlog="$out/${name}_$carrier$seed.rawlog"
                        "$sim" -c "$ini" -o "$rawlog" -s "$seed" "${flags[@]}" > /dev/null
                        recorded="${rawlog%.rawlog}"
                    fi
                    source=(--rawlog "$rawlog" --ground-truth "${rawlog%.rawlog}.gt.tum")
                    gt="${rawlog%.rawlog}.gt.tum" ;;
            esac
            for config in "${configs[@]}"; do
                proximity=$(with_proximity "$config")
                "$slam" "${source[@]}" --config "$config" --out "$out/without" --quiet > /dev/null
                "$slam" "${source[@]}" --config "$proximity" --out "$out/with" --quiet > /dev/null
                row "$carrier, $name, $(basename "$config")" "$seed" "$out/without" "$out/with" "$gt"
                rm -rf "$out/without" "$out/with"
            done
            [[ -z $recorded ]] || rm -rf "$recorded"*
        done
    done
done
