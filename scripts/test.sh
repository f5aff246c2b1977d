#!/usr/bin/env bash
# Set-up command 2: installs what is missing, builds Release and runs the whole test suite.
#   scripts/test.sh [--sanitize]   (--sanitize: the same suite under ASan+UBSan)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh" "$@"
build_dir="$root/build"
[ "${1:-}" = "--sanitize" ] && build_dir="$root/build-sanitize"
cd "$build_dir"
ctest --output-on-failure --parallel "$(nproc)" --timeout 600
