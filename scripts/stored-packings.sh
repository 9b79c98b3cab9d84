#!/usr/bin/env bash
# Regenerates the packings stored as data (tilesets/data/packing-<kind>-<C>.json) with the
# solver, and writes the command into each file. Needs a build (scripts/build.sh).
# Usage: scripts/stored-packings.sh [C...]   (default: 2)
#   C=4: TILEKIT_PACK_EXTRA="--impose t=0,8:pi=1,0,3,2" scripts/stored-packings.sh 4
#        (DESIGN.md's imposed automorphism; 474 s on one thread of this 2-core machine under load)
#   TILEKIT_PACK_EXTRA  extra `pack` options, recorded in the file too (e.g. an imposed
#                       automorphism for C=4 once `pack` takes one)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk=${TILEKIT_BIN:-$root/build/tilekit}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for c in "${@:-2}"; do
  cmd="tilekit pack --kind corner --colors $c --method search --seed 1 --threads 1 --quiet${TILEKIT_PACK_EXTRA:+ $TILEKIT_PACK_EXTRA}"
  # shellcheck disable=SC2086
  "$tk" ${cmd#tilekit } --db "$tmp/scratch.sqlite" --out "$tmp/p.json" >/dev/null
  "$tk" check "$tmp/p.json" >/dev/null  # the independent validator
  {
    printf '{\n "found_by": "%s",\n' "$cmd"
    tail -n +2 "$tmp/p.json"
  } >"$root/tilesets/data/packing-corner-$c.json"
  echo "tilesets/data/packing-corner-$c.json <- $cmd"
done
