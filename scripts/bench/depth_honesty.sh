#!/usr/bin/env bash
# Depth alignment's covariance against the simulated Kinect's noise: pairs of
# frames along the robot's path of a scenario, each rendered DRAWS times with fresh noise and
# aligned as VO aligns them, alone and joined with a simulated feature measurement; NEES per
# pinned direction, and how much of the error repeats every draw (bench/bench_depth_honesty.cpp).
# Usage: scripts/bench/depth_honesty.sh [SCENARIO.ini] [PAIRS] [DRAWS]
#        (default paper_loop.ini, 60 pairs, 6 draws: about 6 minutes on one core)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" > /dev/null
"$root/build/bench/bench_depth_honesty" "${1:-$root/config_ini/scenarios/paper_loop.ini}" "${2:-60}" "${3:-6}"
