#!/usr/bin/env bash
# Camera-only SLAM (issue #14): simulated scenarios recorded with the RGB-D camera alone -
# carried by the robot (lodestone-sim --camera-only: no encoders, wheel drop or magnetometers)
# and carried by hand (--handheld: 6-DoF, shaking, at 1.35 m) - colour as PNG files beside the
# rawlog, read from disk as a dataset's are, run with rgbd_only.ini (nodes from VO alone, 6-DoF
# graph); beside them the robot with its wheels and visual_only.ini. Prints a markdown table.
# Usage: scripts/bench/camera_only.sh [SCENARIO.ini ...]   (default: office, paper_loop)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
sim="$root/build/apps/lodestone-sim/lodestone-sim"
slam="$root/build/apps/lodestone-slam/lodestone-slam"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
scenarios=("$@")
[ ${#scenarios[@]} -gt 0 ] || scenarios=("$root/config_ini/scenarios/office.ini" "$root/config_ini/scenarios/paper_loop.ini")
field() { { grep -o "\"$2\": [0-9.e+-]*" "$1" || true; } | head -1 | awk '{print $2}'; }
echo "| scenario | camera | carrier | frames | ATE [m] | VO gaps / segments | loop closures kept | real-time factor (one run on 2 cores) |"
echo "|---|---|---|---|---|---|---|---|"
for ini in "${scenarios[@]}"; do
    name=$(basename "$ini" .ini)
    # width x height @ rate from the scenario's [camera] section
    cameraSpec=$(awk '/^\[/{s=($0=="[camera]")} s && /^(width|height|rate) *=/{v[$1]=$3} END{printf "%sx%s@%s", v["width"], v["height"], v["rate"]}' "$ini")
    for carrier in "robot, wheels + VO (visual_only.ini)" "robot, camera only (rgbd_only.ini)" "hand (rgbd_only.ini)"; do
        case "$carrier" in
            hand*) flags=(--handheld); config=rgbd_only.ini; tag=hand ;;
            *camera*) flags=(--camera-only); config=rgbd_only.ini; tag=cam ;;
            *) flags=(); config=visual_only.ini; tag=wheels ;;
        esac
        "$sim" -c "$ini" -o "$out/${name}_$tag.rawlog" "${flags[@]}" > /dev/null
        run=$("$slam" -r "$out/${name}_$tag.rawlog" --config "$root/config_ini/slam/$config" \
            --ground-truth "$out/${name}_$tag.gt.tum" --out "$out/${name}_$tag" --quiet 2>&1 | grep -v "^\[")
        report="$out/${name}_$tag/report.json"
        ate=$(echo "$run" | grep -o "ATE RMSE [0-9.]*" | awk '{print $3}')
        rt=$(echo "$run" | grep -o "([0-9.]*x real time)" | tr -d '()' | awk '{print $1}')
        closures=$(echo "$run" | grep -o "[0-9]* loop closures ([0-9]* rejected)" | awk '{print $1 - substr($4, 2)}')
        gaps=$(field "$report" vo_gaps)
        echo "| $name | $cameraSpec | $carrier | $(field "$report" rgbd_frames) | $ate | ${gaps:--} / $(field "$report" segments) | $closures | $rt |"
        rm -rf "$out/${name}_$tag"* 
    done
done
