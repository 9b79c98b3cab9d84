#!/usr/bin/env bash
# Regenerates the packings stored as data (tilesets/data/packing-<kind>-<C>.json) with the
# solver, and writes the command into each file. Needs a build (scripts/build.sh).
# Usage: scripts/stored-packings.sh [C...]   (default: 2)
#   C=4: TILEKIT_PACK_EXTRA="--impose t=0,8:pi=1,0,3,2" scripts/stored-packings.sh 4
#        (an imposed automorphism, solver/impose_group.hpp; 474 s on one thread of this 2-core
#        machine under load)
#   C=8: TILEKIT_PACK_EXTRA="--lift 4 --formulation sat" scripts/stored-packings.sh 8
#        (binary colour-quotient lift of the stored C=4 packing, CNF solved by cadical; seconds)
#   C=16: TILEKIT_PACK_SEED=0 TILEKIT_PACK_EXTRA="--lift 8 --formulation cell" scripts/stored-packings.sh 16
#        (binary lift of the stored C=8 packing by the engine's cell model, most constrained first,
#        natural value order: no backtracking, under a second)
#   C=32: TILEKIT_PACK_SEED=0 TILEKIT_PACK_EXTRA="--lift 16 --formulation cell" scripts/stored-packings.sh 32
#        (the same over the stored C=16 packing: 1M cells, about 5 s; 1 MB of pegs, 126 KB gzipped)
#   TILEKIT_PACK_EXTRA  extra `pack` options, recorded in the file too
#   TILEKIT_PACK_SEED   --seed (default 1; 0 keeps the natural value order of the first dive)
# From C=8 on the file holds the compact peg form (`tilekit check --pegs-out`), one digit per
# lattice point, instead of the tile indices.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk=${TILEKIT_BIN:-$root/build/tilekit}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for c in "${@:-2}"; do
  cmd="tilekit pack --kind corner --colors $c --method search --seed ${TILEKIT_PACK_SEED:-1} --threads 1 --quiet${TILEKIT_PACK_EXTRA:+ $TILEKIT_PACK_EXTRA}"
  # shellcheck disable=SC2086
  "$tk" ${cmd#tilekit } --db "$tmp/scratch.sqlite" --out "$tmp/p.json" >/dev/null
  "$tk" check "$tmp/p.json" --pegs-out "$tmp/pegs.json" >/dev/null  # the independent validator
  src="$tmp/p.json"
  [ "$c" -ge 8 ] && src="$tmp/pegs.json"
  {
    printf '{\n "found_by": "%s",\n' "$cmd"
    tail -n +2 "$src"
  } >"$root/tilesets/data/packing-corner-$c.json"
  "$tk" check "$root/tilesets/data/packing-corner-$c.json" >/dev/null  # the stored file itself
  echo "tilesets/data/packing-corner-$c.json <- $cmd"
done
