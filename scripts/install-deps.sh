#!/usr/bin/env bash
# Installs the Debian 12 packages Lodestone builds and runs with, if any is missing.
# Idempotent: does nothing (and needs no root) when everything is there.
#   scripts/install-deps.sh          what the build, the apps and the tests need
#   scripts/install-deps.sh --fuzz   and clang with its libFuzzer/sanitizer runtime (scripts/fuzz.sh)
set -euo pipefail

packages=(
    build-essential cmake ninja-build ccache pkg-config git
    libmrpt-dev mrpt-apps          # MRPT 2.5: obs, io, graphslam, hwdrivers; rawlog-edit for tests
    mrpt-common                    # MRPT's sample datasets: the tests compare inspect with rawlog-edit on them
    libopencv-dev libeigen3-dev libnanoflann-dev zlib1g-dev
    libdeflate-dev                 # colour PNG frames inflated in half zlib's time (libs/io)
    libjpeg62-turbo-dev            # libjpeg's error handler made to throw (libs/io/hooks)
    libceres-dev                   # pose-graph optimization (sparse, robust losses)
    libopen3d-dev                  # the dense model: TSDF fusion and marching cubes (libs/dense)
    nlohmann-json3-dev             # lodestone-eval relocation reads report.json
    libgtest-dev libgmock-dev
    libbenchmark-dev               # micro-benchmarks (bench/bench_matching)
    time                           # /usr/bin/time: wall time and peak RSS in scripts/bench/throughput.sh
    # GUI tests: stock RawLogViewer with our plugin on a virtual X display, and the
    # HTML report in headless Chromium.
    xvfb xauth x11-apps x11-utils xdotool  # Xvfb, xvfb-run; xwd screenshots; xwininfo; a click
    chromium fonts-dejavu-core             # the report page: images load, no console error
)

if [ "${1:-}" = "--fuzz" ]; then
    packages+=(clang libclang-rt-dev)  # libFuzzer, ASan and UBSan runtimes for clang
fi

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    echo "install-deps: all ${#packages[@]} packages present"
    exit 0
fi

echo "install-deps: installing ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
    sudo=()
elif command -v sudo >/dev/null; then
    sudo=(sudo)
else
    echo "install-deps: missing packages and neither root nor sudo: ${missing[*]}" >&2
    exit 1
fi
"${sudo[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
