#!/usr/bin/env bash
# What the 3D view costs, printed as markdown:
#  - lodestone-view's first picture of an hour's saved map (bench_view_map: 35 000 nodes),
#    off-screen (--screenshot), median of three;
#  - offline runs from disk (the robot recorded by lodestone-sim, slam.ini) with and without
#    lodestone-slam --view on an Xvfb display: the real-time factor of each and their ratio;
#  - live: scripts/bench/live.sh without and with VIEW=1 (lag behind the newest observation,
#    RGB-D frames skipped).
# Usage: [PARTS="map offline live"] scripts/bench/view.sh [SCENARIO ...]
#        (default office and paper_loop; 640x480 recordings take up to 7 GB while in use)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
cmake --build "$root/build" --target bench_view_map > /dev/null
view="$root/build/apps/lodestone-view/lodestone-view"
slam="$root/build/apps/lodestone-slam/lodestone-slam"
sim="$root/build/apps/lodestone-sim/lodestone-sim"
parts=${PARTS:-"map offline live"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
scenarios=("$@")
[[ ${#scenarios[@]} -gt 0 ]] || scenarios=("$root/config_ini/scenarios/office.ini" "$root/config_ini/scenarios/paper_loop.ini")
command -v xvfb-run > /dev/null || { echo "xvfb-run is needed (scripts/install-deps.sh installs xvfb)" >&2; exit 1; }

if [[ $parts == *map* ]]; then
    "$root/build/bench/bench_view_map" "$out/map" 35000 > /dev/null
    times=()
    for _ in 1 2 3; do
        t0=$(date +%s.%N)
        "$view" "$out/map" --screenshot "$out/map.png" > /dev/null
        times+=("$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN{print b - a}')")
    done
    median=$(printf "%s\n" "${times[@]}" | sort -n | sed -n 2p)
    echo "| saved map | nodes | first picture, off-screen 1280x960 [s] (median of 3) |"
    echo "|---|---|---|"
    printf "| bench_view_map | 35000 | %.2f |\n\n" "$median"
fi

if [[ $parts == *offline* ]]; then
    echo "| scenario | seed | real-time factor without / with --view | ratio | outputs identical |"
    echo "|---|---|---|---|---|"
    for ini in "${scenarios[@]}"; do
        name=$(basename "$ini" .ini)
        "$sim" -c "$ini" -o "$out/$name.rawlog" -s 1 > /dev/null
        rt() { grep -o "([0-9.]*x real time)" "$1" | tr -d '()x' | awk '{print $1}'; }
        "$slam" --rawlog "$out/$name.rawlog" --config "$root/config_ini/slam/slam.ini" --out "$out/without" --quiet > "$out/without.txt" 2>&1
        xvfb-run -a -s "-screen 0 1280x1024x24" "$slam" --rawlog "$out/$name.rawlog" --config "$root/config_ini/slam/slam.ini" \
            --out "$out/with" --quiet --view > "$out/with.txt" 2>&1
        a=$(rt "$out/without.txt") b=$(rt "$out/with.txt")
        same=yes
        for f in trajectory.tum graph.graph closures.csv; do cmp -s "$out/without/$f" "$out/with/$f" || same=no; done
        printf "| %s | 1 | %.2fx / %.2fx | %.2f | %s |\n" "$name" "$a" "$b" "$(awk -v a="$a" -v b="$b" 'BEGIN{print b / a}')" "$same"
        rm -rf "$out/without" "$out/with" "$out/$name"*
    done
    echo
fi

if [[ $parts == *live* ]]; then
    echo "Live, without the view:"
    echo
    "$root/scripts/bench/live.sh" | grep "^|"
    echo
    echo "Live, with --view on Xvfb:"
    echo
    VIEW=1 "$root/scripts/bench/live.sh" | grep "^|"
fi
