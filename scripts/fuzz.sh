#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with clang, ASan and UBSan into build-fuzz/ and
# runs each for a while, from the committed seed and regression corpora. Prints a markdown
# table (executions, coverage, peak RSS, findings); exits 1 if any target found something.
#   scripts/fuzz.sh [--seconds N] [--jobs J] [TARGET ...]
#     --seconds N   time per target (default 600)
#     --jobs J      targets run at once (default: the number of cores)
#     --seed S      libFuzzer's random seed (default: from the clock); CI passes one
# Findings (the crashing input, its log) go to build-fuzz/findings/TARGET/; reproduce one
# with build-fuzz/tests/fuzz/TARGET FILE, or build/tests/fuzz/TARGET_replay FILE (gcc).
# A finding that is fixed is added to tests/fuzz/regression/TARGET/ (ctest replays it).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=600
jobs=$(nproc)
seed=0
targets=()
while [ $# -gt 0 ]; do
    case "$1" in
        --seconds) seconds=$2; shift 2 ;;
        --jobs) jobs=$2; shift 2 ;;
        --seed) seed=$2; shift 2 ;;
        -h|--help) sed -n 2,13p "$0"; exit 0 ;;
        -*) echo "fuzz.sh: unknown option '$1'" >&2; exit 2 ;;
        *) targets+=("$1"); shift ;;
    esac
done

"$root/scripts/install-deps.sh" --fuzz
build="$root/build-fuzz"
mkdir -p "$build"
generator=()
if command -v ninja >/dev/null && [ ! -f "$build/Makefile" ]; then generator=(-G Ninja); fi
CC=clang CXX=clang++ cmake -S "$root" -B "$build" "${generator[@]}" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLODESTONE_FUZZ=ON -DLODESTONE_SANITIZE=ON \
    -DLODESTONE_BUILD_TESTS=OFF > "$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" --target fuzz_all --parallel "$(nproc)"
[ ${#targets[@]} -gt 0 ] || mapfile -t targets < "$build/fuzz_targets.txt"

# One target: a working corpus seeded from the committed ones (ASan keeps 64 MB of freed memory
# in quarantine, not 256, leaving the limit to the inputs); libFuzzer's limits are the
# issue's: an input that takes > 10 s or > 1 GB RSS (or a single malloc > 1 GB) is a finding.
run_one() {
    local t=$1 work="$build/work/$1" findings="$build/findings/$1"
    mkdir -p "$work" "$findings"
    local dirs=("$work" "$root/tests/fuzz/corpus/$t")
    [ -d "$root/tests/fuzz/regression/$t" ] && dirs+=("$root/tests/fuzz/regression/$t")
    ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=0:quarantine_size_mb=64 UBSAN_OPTIONS=print_stacktrace=1 \
        "$build/tests/fuzz/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=1024 \
        -malloc_limit_mb=1024 -seed="$seed" -print_final_stats=1 -artifact_prefix="$findings/" \
        "${dirs[@]}" > "$findings/log.txt" 2>&1 || true
}
export -f run_one
export build root seconds seed
printf '%s\n' "${targets[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one {}'

echo
echo "| target | seconds | executions | execs/s | coverage (edges) | features | corpus | peak RSS (MB) | findings |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|"
status=0
for t in "${targets[@]}"; do
    log="$build/findings/$t/log.txt"
    stat() { { grep -m1 "^stat::$1:" "$log" || true; } | awk '{print $2}'; }
    last=$({ grep -E "^#[0-9]+.*cov: " "$log" || true; } | tail -1)
    cov=$(sed -n 's/.*cov: \([0-9]*\).*/\1/p' <<<"$last")
    ft=$(sed -n 's/.*ft: \([0-9]*\).*/\1/p' <<<"$last")
    corp=$(sed -n 's/.*corp: \([0-9]*\).*/\1/p' <<<"$last")
    found=$(find "$build/findings/$t" -maxdepth 1 -type f ! -name log.txt | wc -l)
    [ "$found" -eq 0 ] || status=1
    execs=$(stat number_of_executed_units)
    echo "| $t | $seconds | ${execs:-?} | $(stat average_exec_per_sec) | ${cov:-?} | ${ft:-?} | ${corp:-?} | $(stat peak_rss_mb) | $found |"
done
exit $status
