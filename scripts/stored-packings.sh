#!/usr/bin/env bash
# Regenerates the packings stored as data (tilesets/data/packing-<kind>-<C>.json) with the
# solver, and writes the command into each file. Needs a build (scripts/build.sh).
# Usage: scripts/stored-packings.sh [C...]   (default: 2; 4 once the search finds one quickly)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for c in "${@:-2}"; do
  cmd="tilekit pack --kind corner --colors $c --method search --seed 1 --threads 1 --quiet"
  # shellcheck disable=SC2086
  "$tk" ${cmd#tilekit } --db "$tmp/scratch.sqlite" --out "$tmp/p.json" >/dev/null
  "$tk" check "$tmp/p.json" >/dev/null  # the independent validator
  {
    printf '{\n "found_by": "%s",\n' "$cmd"
    tail -n +2 "$tmp/p.json"
  } >"$root/tilesets/data/packing-corner-$c.json"
  echo "tilesets/data/packing-corner-$c.json <- $cmd"
done
