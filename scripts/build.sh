#!/usr/bin/env bash
# Configures and builds Lodestone (Release) into build/, incrementally.
#   scripts/build.sh              Release build in build/
#   scripts/build.sh --sanitize   ASan+UBSan build (RelWithDebInfo) in build-sanitize/
#   scripts/build.sh --apps       only the apps and the MRPT plugin (target lodestone_apps), in
#                                 build/: what scripts/demo.sh runs; a later full build adds the
#                                 tests and benchmarks to the same tree
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir="$root/build"
extra=(-DCMAKE_BUILD_TYPE=Release)
target=()
case "${1:-}" in
    --sanitize)
        build_dir="$root/build-sanitize"
        extra=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DLODESTONE_SANITIZE=ON) ;;
    --apps) target=(--target lodestone_apps) ;;
    "") ;;
    *) echo "build.sh: unknown option $1 (--sanitize or --apps)" >&2; exit 2 ;;
esac
generator=()
if command -v ninja >/dev/null && [ ! -f "$build_dir/Makefile" ]; then generator=(-G Ninja); fi
mkdir -p "$build_dir"
cmake -S "$root" -B "$build_dir" "${generator[@]}" "${extra[@]}" > "$build_dir/configure.log" 2>&1 \
    || { cat "$build_dir/configure.log"; exit 1; }
cmake --build "$build_dir" --parallel "$(nproc)" "${target[@]}"
echo "build: $build_dir"
