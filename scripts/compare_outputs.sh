#!/usr/bin/env bash
# The proof of a change that must not change behaviour (a refactoring): builds REF (a git
# revision) in a worktree beside this checkout, builds the working tree, runs the same jobs with
# both and compares what they write - trajectories, graphs, closure logs, node tables, maps, the
# simulator's truths and rawlogs, imported rawlogs, the evaluations' figures. Wall-clock figures
# (report.json's "timing", stage and solve seconds and every *_ms_* key, nodes.csv's engine_ms,
# the summary line's speed) and the output folder's own path are taken out first; pictures are
# compared byte for byte too (the simulator's frames, field_map.png, the charts). Prints a
# markdown table and exits 1 if anything differs.
#
# Jobs: the demo's two runs (the bundled rawlog, office simulated on the fly); corridor_kidnap,
# paper_kidnap (slam.ini) and corridor_shuttle (the window closer) recorded at 320x240 / 15 Hz
# and run from disk, judged by lodestone-eval; a hand-held camera-only paper_loop; Kok's walks
# and Aalto trials 1 and 9 imported (seed 1), run with both magnetic closers and judged, and
# lodestone-magfit on each (skipped when ../shared/data is absent); lodestone-eval's ATE / RPE of
# the bundled run. About 6 minutes a build on two cores.
#
# Usage: scripts/compare_outputs.sh [--compare-only] [REF]   (default HEAD: the working tree's
# uncommitted change). Outputs stay in build-compare/{ref,new}-out/ for a closer look;
# --compare-only compares the outputs already there again (no build, no run).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
compare_only=0
if [ "${1:-}" = "--compare-only" ]; then compare_only=1; shift; fi
ref=${1:-HEAD}
sha=$(git -C "$root" rev-parse --verify "$ref^{commit}")
cmp_dir="$root/build-compare"
worktree="$cmp_dir/ref"
data="$root/../shared/data/magnetic"
mkdir -p "$cmp_dir"

# --- Both builds (ccache shares objects between them: paths relative to each tree) -------------
export CCACHE_BASEDIR="$cmp_dir/.."
if [ $compare_only -eq 1 ]; then
    :
elif [ ! -d "$worktree/.git" ] && [ ! -f "$worktree/.git" ]; then
    git -C "$root" worktree add --detach "$worktree" "$sha" > /dev/null
else
    git -C "$worktree" checkout --detach --quiet "$sha"
fi
if [ $compare_only -eq 0 ]; then
    echo "building $ref ($sha) in $worktree/build ..." >&2
    "$worktree/scripts/build.sh" > "$cmp_dir/ref-build.log" 2>&1 ||
        { tail -20 "$cmp_dir/ref-build.log"; exit 1; }
    echo "building the working tree ..." >&2
    "$root/scripts/build.sh" > "$cmp_dir/new-build.log" 2>&1 ||
        { tail -20 "$cmp_dir/new-build.log"; exit 1; }
fi

app() {  # BUILD_DIR NAME: the app's executable wherever the build put it
    local found
    found=$(find "$1/apps" -type f -name "$2" -perm -u+x | head -1)
    [ -n "$found" ] || { echo "compare_outputs.sh: no $2 in $1/apps" >&2; exit 1; }
    echo "$found"
}

# --- The jobs, run with one build into OUT; inputs always from the working tree --------------
run_jobs() {
    local build=$1 out=$2
    local slam sim imp ev insp fit tmp="$out/tmp"
    local ini="$root/config_ini/slam" scenarios="$root/config_ini/scenarios"
    slam=$(app "$build" lodestone-slam)
    sim=$(app "$build" lodestone-sim)
    imp=$(app "$build" lodestone-import)
    ev=$(app "$build" lodestone-eval)
    insp=$(app "$build" lodestone-inspect)
    fit=$(app "$build" lodestone-magfit)
    rm -rf "$out"
    mkdir -p "$out" "$tmp"
    "$root/scripts/bench/window_inis.sh" "$tmp" > /dev/null
    local sample="$root/rawlogs/office_qvga.rawlog.gz"
    job() { echo "  $1" >&2; }

    job bundled
    "$insp" summary "$sample" > "$out/summary.txt"
    "$slam" -q --rawlog "$sample" --ground-truth "${sample%.rawlog.gz}.gt.tum" \
        --config "$ini/slam.ini" --out "$out/bundled" > "$out/bundled.stdout"
    "$ev" "$out/bundled/trajectory.tum" "${sample%.rawlog.gz}.gt.tum" > "$out/bundled.eval.txt"
    job office
    "$slam" -q --sim "$scenarios/office.ini" --config "$ini/slam.ini" --out "$out/office" \
        > "$out/office.stdout"
    # Longer scenarios are recorded at 320x240 / 15 Hz and run from disk (the user's path).
    local scenario
    for scenario in corridor_kidnap:slam.ini paper_kidnap:slam.ini \
        corridor_shuttle:tmp/slam_window.ini; do
        local name=${scenario%%:*} cfg=${scenario#*:}
        case $cfg in tmp/*) cfg="$out/$cfg" ;; *) cfg="$ini/$cfg" ;; esac
        job "$name"
        "$sim" -c "$scenarios/$name.ini" --camera 320x240@15 -o "$out/$name.rawlog.gz" > /dev/null
        "$slam" -q --rawlog "$out/$name.rawlog.gz" --config "$cfg" \
            --ground-truth "$out/$name.gt.tum" --out "$out/$name" > "$out/$name.stdout"
        "$ev" closures "$out/$name" -g "$out/$name.gt.tum" > "$out/$name.closures.txt"
        case $name in
            *kidnap) "$ev" relocation "$out/$name" -g "$out/$name.gt.tum" \
                         -e "$out/$name.events.txt" > "$out/$name.relocation.txt" ;;
        esac
    done
    job handheld
    "$sim" -c "$scenarios/paper_loop_qvga.ini" --handheld -o "$out/handheld.rawlog" > /dev/null
    "$slam" -q --rawlog "$out/handheld.rawlog" --config "$ini/rgbd_only.ini" \
        --ground-truth "$out/handheld.gt.tum" --out "$out/handheld" > "$out/handheld.stdout"
    if [ -d "$data" ]; then
        local name
        for rec in kok/eight.csv kok/square.csv aalto1 aalto9; do
            name=$(basename "$rec" .csv)
            job "$name"
            case $rec in
                kok/*) "$imp" kok "$data/$rec" "$out/$name.rawlog" --seed 1 > /dev/null ;;
                aalto*) "$imp" aalto "$data/aalto/invensense" "${rec#aalto}" "$out/$name.rawlog" \
                            --seed 1 > /dev/null ;;
            esac
            for cfg in magnetic_only magnetic_window; do
                "$slam" -q --rawlog "$out/$name.rawlog" --config "$ini/$cfg.ini" \
                    --ground-truth "$out/$name.gt.tum" --out "$out/$name-$cfg" \
                    > "$out/$name-$cfg.stdout"
                "$ev" closures "$out/$name-$cfg" -g "$out/$name.gt.tum" \
                    > "$out/$name-$cfg.closures.txt"
            done
            "$fit" "$out/$name.rawlog" --config "$ini/magnetic_only.ini" > "$out/$name.magfit.txt"
        done
    else
        echo "  (the magnetic recordings are absent: $data; their jobs skipped)" >&2
    fi
}

# Prints FILE (under DIR) as compared: what depends on the wall clock or on DIR taken out.
normalized() {
    case $1 in
        *.gz) zcat "$1" ;;
        */nodes.csv) cut -d, -f1-4 "$1" ;;
        */report.json)
            python3 -c 'import json, re, sys
wall = {"timing", "stage_seconds", "full_seconds", "local_seconds", "background_wait_seconds"}
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items()
                if k != "input" and k not in wall and not re.search(r"(^|_)ms(_|$)", k)}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x.replace(sys.argv[2], "OUT") if isinstance(x, str) else x
print(json.dumps(strip(json.load(open(sys.argv[1]))), indent=1, sort_keys=True))' "$1" "$2" ;;
        *.stdout) sed -E "s/ in [0-9.]+ s \([0-9.]+x real time\)//; s/^\[[0-9:.]+\|/[/; s|$2|OUT|g" "$1" ;;
        *) sed "s|$2|OUT|g" "$1" ;;
    esac
}

if [ $compare_only -eq 0 ]; then
    echo "running the jobs with $ref ..." >&2
    run_jobs "$worktree/build" "$cmp_dir/ref-out"
    echo "running the jobs with the working tree ..." >&2
    run_jobs "$root/build" "$cmp_dir/new-out"
fi

echo "| output | files compared | differing |"
echo "|---|---|---|"
status=0
declare -A total differ
while IFS= read -r f; do
    rel=${f#"$cmp_dir/ref-out/"}
    group=${rel%%/*}
    group=${group%%.*}
    total[$group]=$(( ${total[$group]:-0} + 1 ))
    other="$cmp_dir/new-out/$rel"
    if [ ! -f "$other" ] ||
        ! cmp -s <(normalized "$f" "$cmp_dir/ref-out") <(normalized "$other" "$cmp_dir/new-out"); then
        differ[$group]="${differ[$group]:-}${differ[$group]:+, }$rel"
        status=1
    fi
done < <(find "$cmp_dir/ref-out" -type f | sort)
# Files only the new build wrote are a change too.
while IFS= read -r f; do
    rel=${f#"$cmp_dir/new-out/"}
    if [ ! -f "$cmp_dir/ref-out/$rel" ]; then
        group=${rel%%/*}
        group=${group%%.*}
        differ[$group]="${differ[$group]:-}${differ[$group]:+, }$rel (new)"
        status=1
    fi
done < <(find "$cmp_dir/new-out" -type f | sort)
for group in $(printf '%s\n' "${!total[@]}" | sort); do
    echo "| $group | ${total[$group]} | ${differ[$group]:-none} |"
done
[ $status -eq 0 ] && echo && echo "identical: $ref and the working tree" ||
    { echo; echo "DIFFERENT: $ref and the working tree"; }
exit $status
