#!/usr/bin/env bash
# Kidnap recovery benchmark, printed as markdown: each kidnap scenario is run
# through lodestone-slam with slam.ini on the simulator, then judged against the simulator's
# ground truth and kidnap events:
#  - `lodestone-eval relocation`: per kidnap relocated or not, time and odometry travel from the
#    put-down to the verified relocation, pose error there (the map aligned on the nodes mapped
#    before the first lift), wrong (> 0.5 m or 10 deg); the map's damage (ATE of the pre-lift
#    nodes at the lift and at the end) and the whole run's ATE;
#  - `lodestone-eval closures`: each loop closer's proposals (before the relocalizer and the
#    optimizer judge them): right within 0.5 m, recall of revisits, recall at 100 % precision.
# Then one summary line per run.
#
# Usage: scripts/bench/kidnap.sh [--qvga] [--variants N] [--jobs J] [--no-wheel-drop]
#                                [--config SLAM.ini] [SCENARIO.ini ...]
#   default scenario: config_ini/scenarios/paper_kidnap.ini (830 s of 640x480 data: about ten minutes)
#   --qvga           the camera at 320x240 / 15 Hz (about three times faster)
#   --variants N     also N variants of each scenario: other simulator seeds, put-downs drawn
#                    at random on the loop (kidnap_variant.awk; corridor scenarios only on its
#                    long plain sides), lift times moved by up to 15 s - the held-out kind
#   --jobs J         runs at once (each pinned to a core of its own when taskset exists)
#   --no-wheel-drop  no wheel-drop sensor: the kidnap detectors of [kidnap_detection] instead
#   --config INI     the SLAM configuration (default config_ini/slam/slam.ini; scripts/bench/
#                    window_inis.sh writes slam.ini with one magnetic closer, either)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
qvga=0 variants=0 jobs=1 nowheel=0 config="$root/config_ini/slam/slam.ini"
scenarios=()
while [ $# -gt 0 ]; do
    case "$1" in
        --qvga) qvga=1 ;;
        --variants) variants=$2; shift ;;
        --jobs) jobs=$2; shift ;;
        --no-wheel-drop) nowheel=1 ;;
        --config) config=$(cd "$(dirname "$2")" && pwd)/$(basename "$2"); shift ;;
        -*) echo "kidnap.sh: unknown option $1" >&2; exit 2 ;;
        *) scenarios+=("$1") ;;
    esac
    shift
done
[ ${#scenarios[@]} -gt 0 ] || scenarios=("$root/config_ini/scenarios/paper_kidnap.ini")
"$root/scripts/build.sh" > /dev/null
slam="$root/build/apps/lodestone-slam/lodestone-slam"
evaluate="$root/build/apps/lodestone-eval/lodestone-eval"
out="${LODESTONE_BENCH_OUT:-$root/out/bench_kidnap}"
mkdir -p "$out"

if [ $nowheel = 1 ]; then
    base=$config
    config="$out/slam_no_wheel_drop.ini"
    sed -e 's/^kidnap_wheel_drop *=.*/kidnap_wheel_drop = false/' \
        -e '/^\[kidnap_detection\]/,/^\[/{s/^motion *=.*/motion = true/;s/^magnetic *=.*/magnetic = true/}' \
        "$base" > "$config"
    grep -q '^kidnap_wheel_drop = false' "$config" ||
        { echo "kidnap.sh: slam.ini has no kidnap_wheel_drop line to switch off" >&2; exit 1; }
fi

# The runs: NAME<tab>INI, variants written beside the outputs.
runs=()
for s in "${scenarios[@]}"; do
    name=$(basename "$s" .ini)
    ini="$out/$name.ini"
    cp "$s" "$ini"
    runs+=("$name	$ini")
    for v in $(seq 1 "$variants"); do
        minleg=0
        case "$name" in corridor*) minleg=10 ;; esac
        awk -v variant="$v" -v min_leg="$minleg" -f "$root/scripts/bench/kidnap_variant.awk" "$s" \
            > "$out/${name}_v$v.ini"
        runs+=("${name}_v$v	$out/${name}_v$v.ini")
    done
done
if [ $qvga = 1 ]; then
    for r in "${runs[@]}"; do
        sed -i -e 's/^width *= *640/width = 320/' -e 's/^height *= *480/height = 240/' \
            -e 's/^rate *= *30 *$/rate = 15/' "${r#*	}"
    done
fi

run_one() {  # NAME INI CORE
    local dir="$out/$1" start
    start=$(date +%s)
    local pin=()
    command -v taskset > /dev/null && pin=(taskset -c "$3")
    if ! "${pin[@]}" "$slam" --sim "$2" --config "$config" --out "$dir" --quiet > "$dir.log" 2>&1; then
        echo "lodestone-slam failed on $2 (see $dir.log)" > "$dir.failed"
        return
    fi
    echo $(( $(date +%s) - start )) > "$dir.wall"
    "$evaluate" relocation "$dir" > "$dir.relocation.md" 2>&1 || true
    "$evaluate" closures "$dir" > "$dir.closures.md" 2>&1 || true
}

cores=$(nproc)
i=0
for r in "${runs[@]}"; do
    rm -f "$out/${r%%	*}.failed" "$out/${r%%	*}.wall"
    run_one "${r%%	*}" "${r#*	}" $(( i % cores )) &
    i=$((i + 1))
    if [ $(( i % jobs )) = 0 ]; then wait; fi
done
wait

failed=0
for r in "${runs[@]}"; do
    name=${r%%	*}
    if [ -f "$out/$name.failed" ]; then cat "$out/$name.failed" >&2; failed=1; continue; fi
    echo "### $name ($(basename "$config"), $([ $qvga = 1 ] && echo 320x240 || echo 640x480), wall $(cat "$out/$name.wall") s)"
    echo
    cat "$out/$name.relocation.md"
    echo
    cat "$out/$name.closures.md"
    echo
done

echo "### Summary"
echo
echo "| run | relocated | wrong | false detections | mean / max m to relocate | mean / max s | map ATE change m | whole-run ATE m |"
echo "|---|---|---|---|---|---|---|---|"
for r in "${runs[@]}"; do
    name=${r%%	*}
    [ -f "$out/$name.failed" ] && continue
    awk -v run="$name" '
        /^relocated / { rel = $2 " of " $4; wrong = $6; fd = $9; sub(/,/, "", rel); sub(/,/, "", wrong) }
        /^put-down to relocation/ { s = $5 " / " $8; m = $10 " / " $15; gsub(/[(),]/, "", s); gsub(/[(),]/, "", m) }
        /^map before the first lift/ { ch = $16 }
        /^whole run/ { ate = $4 }
        END { printf "| %s | %s | %s | %s | %s | %s | %s | %s |\n", run, rel, wrong, fd, m, s, ch, ate }
    ' "$out/$name.relocation.md"
done
exit $failed
