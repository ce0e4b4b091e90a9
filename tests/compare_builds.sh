#!/bin/bash
# bench/compare_builds.py (A/B timing of brume builds, docs/performance.md "How to measure"): two
# builds (the same binary twice, one with an empty BRUME_SPV_DIR) at a tiny size give a table with
# the wall and every pass of `brume bench`, each with a ratio and one per round; a missing binary,
# a single build, a bad option and a failing run are one sentence on stderr and exit 2. Timings are
# not asserted.
# Usage: compare_builds.sh BRUME_EXE SOURCE_DIR
set -uo pipefail
brume=$1 src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/spv"
cd "$src"
fails=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fails=$((fails + 1)); fi; }

python3 bench/compare_builds.py --width 64 --height 36 --quality low --frames 1 --rounds 2 \
    "A=$brume" "B=$brume@$work/spv" > "$work/out" 2> "$work/err"
rc=$?
cat "$work/out"
check "two builds exit 0" '[ $rc -eq 0 ]'
check "a line per round" '[ "$(grep -c "^round [12]/2" "$work/out")" -eq 2 ]'
for row in wall geometry voxelize light integrate composite; do
  # label, A's median, B's median, the ratio, then 2 per-round ratios
  check "row $row has medians, a ratio and 2 rounds" \
    "grep -Eq '^$row +[0-9.]+ \\| +[0-9.]+ +[0-9.]+  [0-9.]+ [0-9.]+\$' '$work/out'"
done

python3 bench/compare_builds.py "A=$work/none" "B=$brume" > "$work/out" 2> "$work/err"
rc=$?
check "a missing binary exits 2" '[ $rc -eq 2 ]'
check "with one sentence naming it" '[ "$(wc -l < "$work/err")" -eq 1 ] && grep -q "$work/none is not an executable file" "$work/err"'

python3 bench/compare_builds.py "A=$brume" > "$work/out" 2> "$work/err"
check "one build exits 2" '[ $? -eq 2 ] && [ "$(wc -l < "$work/err")" -eq 1 ]'

python3 bench/compare_builds.py --quality bogus "A=$brume" "B=$brume" > "$work/out" 2> "$work/err"
check "a bad option exits 2 with one sentence" '[ $? -eq 2 ] && [ "$(wc -l < "$work/err")" -eq 1 ] && grep -q "invalid choice" "$work/err"'

printf '{"camera": 3}\n' > "$work/bad.json"
python3 bench/compare_builds.py --scene "$work/bad.json" "A=$brume" "B=$brume" > "$work/out" 2> "$work/err"
check "a failing run exits 2 with brume's sentence" '[ $? -eq 2 ] && [ "$(wc -l < "$work/err")" -eq 1 ] && grep -q "failed in round 1" "$work/err"'
cat "$work/err"
[ $fails -eq 0 ]
