#!/bin/sh
# Editor benchmark (issue 11): a scripted drag of a volume, a camera orbit, a drag of a light out of
# the view's reach, a drag of a volume out of it (without the fallbacks, a pipeline compile mid-drag:
# see each run's slowest frame) and volumes hidden, shown and deleted (without the stand-ins, a compile on
# the frames after each: see "compiled") in brume-editor,
# 1280x720, the default scene at its preset (high), UI shown, under Xvfb; each run prints the median
# and p95 frame wall time per kind of frame (coarse while interacting, rest, ui) and the per-pass
# median GPU ms (brume-editor --bench).
#
#   bench/editor_bench.sh [ROUNDS] [EDITOR...]
#
# With several editors (e.g. an older build), runs alternate A B A B in each round so that a busy
# machine affects both alike. Defaults: 1 round, build/app/brume-editor.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
rounds=${1:-1}
[ $# -gt 0 ] && shift
[ $# -eq 0 ] && set -- "$here/build/app/brume-editor"
command -v xvfb-run > /dev/null || { echo "error: xvfb-run is missing (apt-get install xvfb xauth)." >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
round=1
while [ "$round" -le "$rounds" ]; do
    for script in editor_drag editor_orbit editor_light_drag editor_volume_out editor_hide; do
        for exe in "$@"; do
            echo "== round $round, $script, $exe"
            # XDG_CONFIG_HOME: keep the run off the user's recent-files list.
            XDG_CONFIG_HOME="$tmp" xvfb-run -a -s '-screen 0 1280x720x24' "$exe" \
                "$here/assets/scenes/default.json" --width 1280 --height 720 --bench \
                --script "$here/bench/$script.txt" --discard-recovery | grep -v '^frames:'
        done
    done
    round=$((round + 1))
done
