#!/usr/bin/env bash
# x_screenshot.sh [--dismiss DIALOG] [--click X,Y] OUT.xwd WINDOW SETTLE_S COMMAND [ARGS...]
# Starts COMMAND on a fresh 1280x800 Xvfb display (xvfb-run), waits up to 30 s for a top-level
# window whose name contains WINDOW, sizes it to the screen (there is no window manager to do
# it), closes a dialog named DIALOG with Escape (RawLogViewer's "Tip of the Day" is modal),
# clicks at X,Y, lets it draw SETTLE_S seconds, dumps the screen to OUT.xwd (xwd -root) and
# ends COMMAND. Prints "window: up" and "still running: yes|no".
# Exit: 0 screenshot taken with COMMAND still running; 3 no window appeared; 4 COMMAND had
# exited before the screenshot; 5 the screenshot failed; 2 usage.
set -uo pipefail
if [ "${1:-}" != "--inside" ]; then
    exec xvfb-run -a -s "-screen 0 1280x800x24" "$0" --inside "$@"
fi
shift
dismiss="" click=""
while [ $# -gt 0 ]; do
    case "$1" in
        --dismiss) dismiss=$2; shift 2 ;;
        --click) click=$2; shift 2 ;;
        *) break ;;
    esac
done
[ $# -ge 4 ] || { echo "usage: $0 [--dismiss DIALOG] [--click X,Y] OUT WINDOW SETTLE_S COMMAND..." >&2; exit 2; }
out=$1 name=$2 settle=$3
shift 3
"$@" >"$out.log" 2>&1 &
pid=$!

# Top-level window ids whose name contains $1.
windows_named() {
    xwininfo -root -children 2>/dev/null | grep -F "\"" | grep -F "$1" | awk '{print $1}'
}

seen=no
for _ in $(seq 1 60); do
    [ -n "$(windows_named "$name")" ] && { seen=yes; break; }
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.5
done
if [ "$seen" = yes ]; then
    echo "window: up"
    sleep 2  # the window's first layout
    for w in $(windows_named "$name"); do xdotool windowsize "$w" 1280 800 2>/dev/null; done
    if [ -n "$dismiss" ]; then
        for w in $(windows_named "$dismiss"); do
            xdotool windowfocus --sync "$w" key Escape 2>/dev/null
        done
    fi
    if [ -n "$click" ]; then
        sleep 1
        xdotool mousemove "${click%,*}" "${click#*,}" click 1
    fi
fi
sleep "$settle"
running=no
kill -0 "$pid" 2>/dev/null && running=yes
echo "still running: $running"
xwd -root -silent -out "$out"
shot=$?
kill "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
[ "$seen" = yes ] || exit 3
[ "$running" = yes ] || exit 4
[ $shot -eq 0 ] || exit 5
exit 0
