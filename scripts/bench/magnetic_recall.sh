#!/usr/bin/env bash
# The magnetic loop closers judged as place recognition (precision and recall against the truth,
# passes counted by direction), side by side on every recording: Aalto invensense trials 1-9 and
# Kok & Solin's walks read in place from ../shared/data/magnetic (skipped when absent), a long
# synthetic loop and a synthetic corridor walked back and forth. Each recording is imported with
# the drift model for seeds 1..N and run with each INI; a markdown table, a row per recording
# and INI (bench/bench_magnetic_recall.cpp says what each column counts).
# Usage: scripts/bench/magnetic_recall.sh [SEEDS] [INI ...]   (SIM_SEEDS=N: corridor_shuttle seeds, 3; 0: none)
#   VARIANTS="quiet:0.5 quiet:0.3 gauss normalized:45 rate:50 noise:0.3": each recording also
#   made harder (datasets/MagneticRecordingVariants.h), a table each; ONLY=NAME: the recordings whose name
#   holds NAME ("kok", "synthetic", "aalto 3"); JUDGE=M: passes and right closures within M
#   metres (0.5); ANOMALY_SCALE=A: the simulated corridor in a quieter building
#   ([magnetic_field] anomaly_scale).
#   (default: 10 seeds; magnetic_gp.ini, the sequence matcher with GP correction, against
#   magnetic_window.ini, the window method, and magnetic_only.ini, both; about ten minutes)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
seeds=${1:-10}
shift || true
inis=("$@")
[ ${#inis[@]} -gt 0 ] || inis=(magnetic_gp.ini magnetic_window.ini magnetic_only.ini)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
pin=()
command -v taskset > /dev/null && pin=(taskset -c 0)
# (the optimizer logs its rejections on stdout: kept out of the table)
only=()
[ -z "${ONLY:-}" ] || only=(--only "$ONLY")
for variant in original ${VARIANTS:-}; do
    printf "\n#### variant: %s\n\n" "$variant"
    "${pin[@]}" "$root/build/bench/bench_magnetic_recall" "$root/../shared/data/magnetic" "$out" \
        "$seeds" "${inis[@]}" "${only[@]}" --variant "$variant" --judge-radius "${JUDGE:-0.5}" \
        2> /dev/null | grep -v "^\["
done

# A simulated robot (two magnetometers 0.12 m either side of its centre line, wheels, RGB-D at
# 320x240 / 15 Hz) driving corridor_shuttle.ini's plain corridor back and forth, each seed
# simulated to disk and run with slam.ini's magnetic closers one at a time (MagneticGpERD, then
# MagneticWindowERD: scripts/bench/window_inis.sh) and with slam.ini itself (both);
# lodestone-eval closures counts the passes by direction.
sim_seeds=${SIM_SEEDS:-3}
[ "$sim_seeds" -gt 0 ] || exit 0
sim="$root/build/apps/lodestone-sim/lodestone-sim"
slam="$root/build/apps/lodestone-slam/lodestone-slam"
evaluate="$root/build/apps/lodestone-eval/lodestone-eval"
"$root/scripts/bench/window_inis.sh" "$out"
scenario="$root/config_ini/scenarios/corridor_shuttle.ini"
if [ -n "${ANOMALY_SCALE:-}" ]; then
    sed "s/^anomaly_scale *=.*/anomaly_scale = $ANOMALY_SCALE/" "$scenario" > "$out/corridor_shuttle.ini"
    scenario="$out/corridor_shuttle.ini"
fi
echo
echo "#### corridor_shuttle.ini (simulated robot, two magnetometers; seeds 1-$sim_seeds; anomaly_scale ${ANOMALY_SCALE:-1})"
echo
echo "| seed | INI: magnetic closer | its closures: right / wrong | same direction: passes, recall | opposite direction: passes, recall | ATE [m] |"
echo "|---|---|---|---|---|---|"
for seed in $(seq 1 "$sim_seeds"); do
    "$sim" -c "$scenario" --camera 320x240@15 -s "$seed" \
        -o "$out/shuttle_$seed.rawlog" > /dev/null
    for ini in "$out/slam_gp.ini" "$out/slam_window.ini" "$root/config_ini/slam/slam.ini"; do
        name=$(basename "$ini")
        run="$out/shuttle_${seed}_$name"
        ate=$("$slam" --rawlog "$out/shuttle_$seed.rawlog" --ground-truth "$out/shuttle_$seed.gt.tum" \
            --config "$ini" --out "$run" 2> /dev/null | sed -n 's/^ATE RMSE \([0-9.]*\) m.*/\1/p')
        "$evaluate" closures "$run" --ground-truth "$out/shuttle_$seed.gt.tum" |
            awk -F'|' -v seed="$seed" -v ini="$name" -v ate="$ate" '/^Recall funnel/ { exit }
                /^\| Magnetic/ {
                split($13, same, ","); split($14, opp, ",");
                gsub(/ /, "", $2);
                printf "| %s | %s: %s | %d / %d | %d passes, %.2f | %d passes, %.2f | %s |\n",
                    seed, ini, $2, $4, $5, same[1], same[2], opp[1], opp[2], ate }'
    done
    rm -rf "$out"/shuttle_"$seed"*
done
