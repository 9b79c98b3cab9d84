#!/usr/bin/env bash
# Regenerates the de Bruijn tori stored as data (tilesets/data/window-KxL-C-RxS.json) with the
# solver, and writes the command into each file ("found_by"). Needs a build (scripts/build.sh).
# Usage: scripts/stored-window-tori.sh   (from any directory; the commands run in the repository)
#   2x3 and 3x2 binary windows on 8x8, 2x3 on 16x4, 2x2 over 3 symbols on 9x9: plain search
#   (the window model, scanline order, Luby restarts), each well under a second.
#   3x3 binary windows on 16x32: the row-difference lift over the stored 2x3 torus on 16x4
#   (B(i+1,j) - B(i,j) = A(i mod 16, j mod 4)): the search decides the top row, 36 nodes.
# Every file is checked by `tilekit check` (the independent validator) after it is written.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk=${TILEKIT_BIN:-$root/build/tilekit}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$root"
store() {  # NAME PACK-ARGS...
  local name=$1
  shift
  local cmd="tilekit pack --kind window $* --seed 0 --threads 1 --quiet"
  # shellcheck disable=SC2086
  "$tk" ${cmd#tilekit } --db "$tmp/scratch.sqlite" --out "$tmp/t.json" >/dev/null
  "$tk" check "$tmp/t.json" >/dev/null  # the independent validator
  {
    printf '{\n "found_by": "%s",\n' "$cmd"
    tail -n +2 "$tmp/t.json"
  } >"tilesets/data/window-$name.json"
  "$tk" check "tilesets/data/window-$name.json" >/dev/null  # the stored file itself
  echo "tilesets/data/window-$name.json <- $cmd"
}
store 2x3-2-8x8 --window 2x3 --colors 2 --size 8x8 --method search
store 3x2-2-8x8 --window 3x2 --colors 2 --size 8x8 --method search
store 2x3-2-16x4 --window 2x3 --colors 2 --size 16x4 --method search
store 2x2-3-9x9 --window 2x2 --colors 3 --size 9x9 --method search
store 3x3-2-16x32 --window 3x3 --colors 2 --size 16x32 --lift rows=tilesets/data/window-2x3-2-16x4.json
