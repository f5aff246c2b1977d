#!/usr/bin/env bash
# Configures and builds Lodestone (Release) into build/, incrementally.
#   scripts/build.sh              Release build in build/
#   scripts/build.sh --sanitize   ASan+UBSan build (RelWithDebInfo) in build-sanitize/
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir="$root/build"
extra=(-DCMAKE_BUILD_TYPE=Release)
if [ "${1:-}" = "--sanitize" ]; then
    build_dir="$root/build-sanitize"
    extra=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DLODESTONE_SANITIZE=ON)
fi
generator=()
if command -v ninja >/dev/null && [ ! -f "$build_dir/Makefile" ]; then generator=(-G Ninja); fi
mkdir -p "$build_dir"
cmake -S "$root" -B "$build_dir" "${generator[@]}" "${extra[@]}" > "$build_dir/configure.log" 2>&1 \
    || { cat "$build_dir/configure.log"; exit 1; }
cmake --build "$build_dir" --parallel "$(nproc)"
echo "build: $build_dir"
