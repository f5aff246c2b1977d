#!/usr/bin/env bash
# lodestone-inspect report as a user runs it: the bundled office sample and the
# simulated paper_loop_qvga (about 1 GB of rawlog and images, made by
# scripts/make_benchmark_rawlogs.sh if missing), each alone and with --slam on a lodestone-slam
# run of it (made here if missing, slam.ini; with the ground truth beside the rawlog). Timed
# as whole processes (/usr/bin/time: wall, peak RSS). Prints a markdown table. Target:
# paper_loop_qvga under a minute, memory flat (the same peak RSS as the small sample).
# Usage: scripts/bench/report.sh [--build DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build="$root/build"
[ "${1:-}" = "--build" ] && build=$2
inspect="$build/apps/lodestone-inspect/lodestone-inspect"
slam="$build/apps/lodestone-slam/lodestone-slam"
out="$root/out/bench_report"
mkdir -p "$out"

big="$root/out/rawlogs/paper_loop_qvga.rawlog.gz"
[ -f "$big" ] || "$root/scripts/make_benchmark_rawlogs.sh" paper_loop_qvga > /dev/null

# rawlog|name
inputs=("$root/rawlogs/office_qvga.rawlog.gz|office_qvga (bundled)" "$big|paper_loop_qvga")

on_disk() {  # the rawlog and its external images folder, if any
    local r=$1 images="${1%.rawlog.gz}_Images"
    du -cb "$r" $( [ -d "$images" ] && echo "$images" ) | tail -1 | cut -f1
}

echo "| rawlog | on disk | entries | --slam | wall [s] | peak RSS [MB] | charts | thumbnails |"
echo "|---|---|---|---|---|---|---|---|"
for item in "${inputs[@]}"; do
    rawlog=${item%%|*} name=${item#*|}
    key=$(basename "${rawlog%.rawlog.gz}")
    run="$out/${key}_slam"
    if [ ! -f "$run/report.json" ]; then
        "$slam" --rawlog "$rawlog" --config "$root/config_ini/slam/slam.ini" --quiet --out "$run" > /dev/null
    fi
    bytes=$(on_disk "$rawlog")
    for with_slam in no yes; do
        args=("$rawlog" --out "$out/${key}_report_$with_slam" -q)
        [ "$with_slam" = yes ] && args+=(--slam "$run")
        gt="${rawlog%.rawlog.gz}.gt.tum"
        [ "$with_slam" = yes ] && [ -f "$gt" ] && args+=(--ground-truth "$gt")
        rm -rf "$out/${key}_report_$with_slam"
        /usr/bin/time -f "%e %M" -o "$out/time.txt" "$inspect" report "${args[@]}" > "$out/stdout.txt"
        read -r wall rss < <(tail -1 "$out/time.txt")
        # "N entries, C charts, T thumbnails -> ..."
        read -r entries _ charts _ thumbs _ < "$out/stdout.txt"
        printf "| %s | %.0f MB | %s | %s | %.2f | %.0f | %s | %s |\n" "$name" \
            "$(awk -v b="$bytes" 'BEGIN{print b/1e6}')" "$entries" "$with_slam" "$wall" \
            "$(awk -v k="$rss" 'BEGIN{print k/1024}')" "$charts" "$thumbs"
    done
done
echo
echo "reports in $out"
