#!/bin/bash
# Drives brume-editor with the real mouse and keyboard (xdotool, inside xvfb-run), as a user would:
# click the fog box in the middle of the view to select it, drag the gizmo's X handle, Ctrl+S,
# Ctrl+Z, Ctrl+S. Usage: editor_xdotool.sh EDITOR SCENE.json RECORD.txt SAVED_AFTER_DRAG.json
# Every step waits for the editor's --record log (or the saved file) to show that the input
# arrived, never for a fixed time, so a slow machine only makes it slower.
set -u
editor=$1 scene=$2 record=$3 afterDrag=$4
: > "$record"
"$editor" "$scene" --width 1000 --height 450 --quality low --validation --record "$record" &
pid=$!
trap 'kill $pid 2>/dev/null' EXIT

# waitfor PATTERN COUNT: until the record holds COUNT lines matching PATTERN (60 s at most).
waitfor() {
    for _ in $(seq 600); do
        [ "$(grep -c -- "$1" "$record")" -ge "$2" ] && return 0
        kill -0 $pid 2>/dev/null || { echo "the editor exited early"; exit 1; }
        sleep 0.1
    done
    echo "timed out waiting for $2 x '$1' in the record:"; cat "$record"; exit 1
}
# waitchange FILE STAMP: until FILE is another file (saves are atomic: a new inode) than STAMP.
waitchange() {
    for _ in $(seq 600); do
        [ "$(stat -c %i.%Y.%s "$1" 2>/dev/null)" != "$2" ] && return 0
        sleep 0.1
    done
    echo "timed out waiting for $1 to be saved"; exit 1
}

win=$(xdotool search --sync --onlyvisible --name brume | head -1)
[ -n "$win" ] || { echo "no editor window"; exit 1; }
xdotool windowfocus "$win" 2>/dev/null
# The box sits at the view's centre (500, 225): a click that does not move picks it.
xdotool mousemove --window "$win" 500 225 click 1
waitfor '^pick ' 1
# Its X handle runs right from the centre, a fifth of the view height (90 px) long.
xdotool mousemove --window "$win" 560 225 mousedown 1
waitfor '^begin' 2
for x in 580 600 620 640; do
    xdotool mousemove --window "$win" $x 226
    waitfor '^set volumes\[0\].transform.translation' 1
done
sleep 0.5  # the last moves: a drag is continuous, so how many sets is not the point
xdotool mouseup 1
waitfor '^end' 2
# chord KEY PATTERN COUNT: Ctrl+KEY held until the record shows its action, so a slow frame cannot
# miss a press and release that came between two frames.
chord() {
    xdotool keydown ctrl keydown "$1"
    waitfor "$2" "$3"
    xdotool keyup "$1"
    sleep 0.2
    xdotool keyup ctrl
}
stamp=$(stat -c %i.%Y.%s "$scene")
chord s '^save' 1
waitchange "$scene" "$stamp"
cp "$scene" "$afterDrag"
chord z '^undo' 1
stamp=$(stat -c %i.%Y.%s "$scene")
chord s '^save' 2
waitchange "$scene" "$stamp"
exit 0
