#!/usr/bin/env bash
# Camera-only SLAM (issues #14, #30): simulated scenarios recorded to disk with the RGB-D camera
# carried by the robot with its wheels, by the robot alone (lodestone-sim --camera-only: no
# encoders, wheel drop or magnetometers) and by hand (--handheld: 6-DoF, shaking, at 1.35 m) -
# colour as PNG files beside the rawlog, read back as a dataset's are. The camera-only
# recordings carry a gyro (--gyro: its own noise stream, so every other sample is as without
# it), and each is run four times with rgbd_only.ini: without the IMU (use_gyro, use_gravity
# false: the gaps' turns then measured by their frames' depth) and with it (the INI as it
# ships), each also as a level carrier on one floor (carrier_tilt_sigma_deg = 5 where no
# accelerometer gives the up, carrier_height_sigma = 0.05: opt-in; it helps the hand-held
# loop and, measured, not the robot's camera).
# Beside them the robot with its wheels and visual_only.ini. One row per run: ATE, VO's gaps
# and how they were bridged, closures, the real-time factor; then median and worst over the
# seeds.
# Usage: scripts/bench/camera_only.sh ["SEED..."] [SCENARIO.ini ...]
#        (default: seed 1; office and paper_loop, 640x480 at 30 Hz: about 1.5 hours a seed on
#        2 cores, and up to 13 GB of disk while a recording is in use; REC_DIR=DIR reads
#        DIR/NAME_{wheels,cam,hand}SEED.rawlog where they exist and keeps what it records there)
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
variant rgbd_level_no_imu use_gyro=false use_gravity=false carrier_tilt_sigma_deg=5 carrier_height_sigma=0.05
variant rgbd_floor carrier_height_sigma=0.05
cp "$base" "$out/rgbd_only.ini"
cp "$root/config_ini/slam/visual_only.ini" "$out/visual_only.ini"
results="$out/results.txt"
: > "$results"
echo "| scenario | camera | seed | carrier | frames | ATE [m] | VO gaps: bridged by the gyro (of them by depth) / by the depth's turn / relocalized | segments | loop closures kept | real-time factor (one run on 2 cores) |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for ini in "${scenarios[@]}"; do
    name=$(basename "$ini" .ini)
    # width x height @ rate from the scenario's [camera] section
    cameraSpec=$(awk '/^\[/{s=($0=="[camera]")} s && /^(width|height|rate) *=/{v[$1]=$3} END{printf "%sx%s@%s", v["width"], v["height"], v["rate"]}' "$ini")
    for seed in $seeds; do
        for tag in wheels cam hand; do
            case $tag in
                wheels) flags=(); runs=("robot, wheels + VO:visual_only") ;;
                cam) flags=(--camera-only --gyro)
                     runs=("robot, camera only:rgbd_no_imu" "robot, camera only, level on one floor:rgbd_level_no_imu"
                           "robot, camera + gyro:rgbd_only" "robot, camera + gyro, one floor:rgbd_floor") ;;
                hand) flags=(--handheld --gyro)
                      runs=("hand, camera only:rgbd_no_imu" "hand, camera only, level on one floor:rgbd_level_no_imu"
                            "hand, camera + gyro:rgbd_only" "hand, camera + gyro, one floor:rgbd_floor") ;;
            esac
            rawlog="$recordings/${name}_$tag$seed.rawlog"
            [[ -f $rawlog ]] || "$sim" -c "$ini" -o "$rawlog" -s "$seed" "${flags[@]}" > /dev/null
            for r in "${runs[@]}"; do
                carrier=${r%%:*} config=${r#*:}
                run="$out/${name}_$tag$seed-$config"
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
                echo "| $name | $cameraSpec | $seed | $carrier | $(field "$report" rgbd_frames) | $ate | $bridged | $(field "$report" segments) | $closures | $rt |"
                echo "$name|$carrier|$ate" >> "$results"
                rm -rf "$run"
            done
            [[ -n ${REC_DIR:-} ]] || rm -rf "$rawlog" "${rawlog%.rawlog}"{.gt.tum,.events.txt,_Images}
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
