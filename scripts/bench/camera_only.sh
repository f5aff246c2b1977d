#!/usr/bin/env bash
# Camera-only SLAM: simulated scenarios recorded to disk with the RGB-D camera
# carried by the robot with its wheels, by the robot alone (lodestone-sim --camera-only: no
# encoders, wheel drop or magnetometers) and by hand (--handheld: 6-DoF, shaking, at 1.35 m) -
# colour as PNG files beside the rawlog, read back as a dataset's are. The camera-only
# recordings carry a gyro (--gyro: its own noise stream, so every other sample is as without
# it), and each is run four times with rgbd_only.ini: without the IMU (use_gyro, use_gravity
# false: the gaps' turns then measured by their frames' depth) and with it (the INI as it
# ships), each also with VO's edges alone (floor_level, step_motion_prior false: no floor as a
# landmark, no carrier's motion holding what VO left unmeasured - the earlier shipped INI).
# Beside them the robot with its wheels and visual_only.ini. One row per run: ATE, VO's gaps
# and how they were bridged, closures, the real-time factor; then median and worst over the
# seeds.
# Usage: [CARRIERS="wheels cam hand"] [JOBS=1] scripts/bench/camera_only.sh ["SEED..."] [SCENARIO.ini ...]
#        (default: seed 1; office and paper_loop, 640x480 at 30 Hz: about 1.5 hours a seed on
#        2 cores, and up to 13 GB of disk while a recording is in use; REC_DIR=DIR reads
#        DIR/NAME_{wheels,cam,hand}SEED.rawlog where they exist - what is missing is recorded
#        and removed after its runs, as without REC_DIR; JOBS=2 runs a recording's runs two at a
#        time: the real-time factor is then of two runs sharing the 2 cores)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
sim="$root/build/apps/lodestone-sim/lodestone-sim"
slam="$root/build/apps/lodestone-slam/lodestone-slam"
seeds=${1:-1}
shift || true
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
recordings=${REC_DIR:-$out}
scenarios=("$@")
[ ${#scenarios[@]} -gt 0 ] || scenarios=("$root/config_ini/scenarios/office.ini" "$root/config_ini/scenarios/paper_loop.ini")
base="$root/config_ini/slam/rgbd_only.ini"
source "$root/scripts/bench/ini_variant.bash"
variant rgbd_no_imu use_gyro=false use_gravity=false
variant rgbd_vo_edges_no_imu use_gyro=false use_gravity=false floor_level=false step_motion_prior=false
variant rgbd_vo_edges floor_level=false step_motion_prior=false
cp "$base" "$out/rgbd_only.ini"
cp "$root/config_ini/slam/visual_only.ini" "$out/visual_only.ini"
results="$out/results.txt"
: > "$results"
sharing="one run on 2 cores"
[[ ${JOBS:-1} -gt 1 ]] && sharing="$JOBS runs sharing 2 cores"
echo "| scenario | camera | seed | carrier | frames | ATE [m] | VO gaps: bridged by the gyro (of them by depth) / by the depth's turn / relocalized | segments | loop closures kept | real-time factor ($sharing) |"
echo "|---|---|---|---|---|---|---|---|---|---|"
max_jobs=${JOBS:-1}
carriers=${CARRIERS:-wheels cam hand}
# One run: its table row into $out/rows/INDEX, its ATE into $results (the summary).
run_one() {
    local index=$1 name=$2 cameraSpec=$3 seed=$4 rawlog=$5 carrier=$6 config=$7
    local run="$out/${name}_$index-$config"
    local log report ate rt closures gaps gyro depth turn bridged
    log=$("$slam" -r "$rawlog" --config "$out/$config.ini" \
        --ground-truth "${rawlog%.rawlog}.gt.tum" --out "$run" --quiet 2>&1 | grep -v "^\[")
    report="$run/report.json"
    ate=$(echo "$log" | grep -o "ATE RMSE [0-9.]*" | awk '{print $3}')
    rt=$(echo "$log" | grep -o "([0-9.]*x real time)" | tr -d '()' | awk '{print $1}')
    closures=$(echo "$log" | grep -o "[0-9]* loop closures ([0-9]* rejected)" | awk '{print $1 - substr($4, 2)}')
    gaps=$(field "$report" vo_gaps)
    gyro=$(field "$report" vo_gaps_bridged_by_gyro)
    depth=$(field "$report" vo_gaps_bridged_by_depth)
    turn=$(field "$report" vo_gaps_bridged_by_depth_turn)
    bridged="${gaps:--}: ${gyro:-0} (${depth:-0}) / ${turn:-0} / $(field "$report" vo_gaps_relocalized)"
    [[ $config == visual_only ]] && bridged="-"
    echo "| $name | $cameraSpec | $seed | $carrier | $(field "$report" rgbd_frames) | $ate | $bridged | $(field "$report" segments) | $closures | $rt |" > "$out/rows/$index"
    echo "$name|$carrier|$ate" > "$out/rows/$index.summary"
    rm -rf "$run"
}
mkdir -p "$out/rows"
for ini in "${scenarios[@]}"; do
    name=$(basename "$ini" .ini)
    # width x height @ rate from the scenario's [camera] section
    cameraSpec=$(awk '/^\[/{s=($0=="[camera]")} s && /^(width|height|rate) *=/{v[$1]=$3} END{printf "%sx%s@%s", v["width"], v["height"], v["rate"]}' "$ini")
    for seed in $seeds; do
        for tag in $carriers; do
            case $tag in
                wheels) flags=(); runs=("robot, wheels + VO:visual_only") ;;
                cam) flags=(--camera-only --gyro)
                     runs=("robot, camera only:rgbd_no_imu" "robot, camera only, VO's edges alone:rgbd_vo_edges_no_imu"
                           "robot, camera + gyro:rgbd_only" "robot, camera + gyro, VO's edges alone:rgbd_vo_edges") ;;
                hand) flags=(--handheld --gyro)
                      runs=("hand, camera only:rgbd_no_imu" "hand, camera only, VO's edges alone:rgbd_vo_edges_no_imu"
                            "hand, camera + gyro:rgbd_only" "hand, camera + gyro, VO's edges alone:rgbd_vo_edges") ;;
                *) echo "unknown carrier $tag (wheels, cam, hand)" >&2; exit 2 ;;
            esac
            rawlog="$recordings/${name}_$tag$seed.rawlog"
            recorded=false
            if [[ ! -f $rawlog ]]; then
                rawlog="$out/${name}_$tag$seed.rawlog"
                "$sim" -c "$ini" -o "$rawlog" -s "$seed" "${flags[@]}" > /dev/null
                recorded=true
            fi
            rm -f "$out"/rows/*
            for i in "${!runs[@]}"; do
                r=${runs[$i]}
                run_one "$i" "$name" "$cameraSpec" "$seed" "$rawlog" "${r%%:*}" "${r#*:}" &
                while [[ $(jobs -rp | wc -l) -ge $max_jobs ]]; do wait -n; done
            done
            wait
            for i in "${!runs[@]}"; do
                cat "$out/rows/$i"
                cat "$out/rows/$i.summary" >> "$results"
            done
            $recorded && rm -rf "$rawlog" "${rawlog%.rawlog}"{.gt.tum,.events.txt,_Images}
        done
    done
done
echo
echo "| scenario | carrier | ATE median / worst over seeds $seeds [m] |"
echo "|---|---|---|"
awk -F'|' '{k = $1 "|" $2; if (!(k in n)) order[++m] = k; v[k, ++n[k]] = $3}
    END {for (i = 1; i <= m; ++i) {k = order[i]; c = n[k];
            for (a = 1; a <= c; ++a) for (b = a + 1; b <= c; ++b) if (v[k, b] + 0 < v[k, a] + 0) {t = v[k, a]; v[k, a] = v[k, b]; v[k, b] = t}
            med = c % 2 ? v[k, (c + 1) / 2] : (v[k, c / 2] + v[k, c / 2 + 1]) / 2;
            split(k, p, "|"); printf "| %s | %s | %.4f / %s |\n", p[1], p[2], med, v[k, c]}}' "$results"
