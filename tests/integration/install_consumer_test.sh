#!/usr/bin/env bash
# Installs the current build into a scratch prefix, then configures, builds and runs a consumer
# project against it. Usage: install_consumer_test.sh CMAKE BUILD_DIR CONSUMER_SOURCE_DIR
set -euo pipefail
cmake_bin=$1 build_dir=$2 consumer_src=$3
scratch=$(mktemp -d "${TMPDIR:-/tmp}/lodestone-install.XXXXXX")
trap 'rm -rf "$scratch"' EXIT

"$cmake_bin" --install "$build_dir" --prefix "$scratch/prefix" > "$scratch/install.log"
test -x "$scratch/prefix/bin/lodestone-inspect"
test -f "$scratch/prefix/include/lodestone/obs/CObservationMagnetometer.h"
test -f "$scratch/prefix/lib/cmake/lodestone/lodestoneConfig.cmake"

"$cmake_bin" -S "$consumer_src" -B "$scratch/build" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$scratch/prefix" > "$scratch/configure.log"
"$cmake_bin" --build "$scratch/build" > "$scratch/build.log"
"$scratch/build/lodestone_consumer"
# The installed app runs from the prefix (RPATH to the installed libraries).
"$scratch/prefix/bin/lodestone-inspect" --help > /dev/null
