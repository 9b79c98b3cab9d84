#!/usr/bin/env bash
# scripts/check-layers.sh on a copy of the tree (sources and READMEs): it passes on the tree as
# it is, and fails, naming the problem, on one include outside a README's "May include" line,
# on a cycle, and on a README without the line. Prints "N passed, M failed"; exit 1 on a failure.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0
copy_tree() {
  rm -rf "$tmp/tree" && mkdir "$tmp/tree"
  # the files git tracks or would track (not build trees, nor outputs it ignores such as out/)
  (cd "$root" && git ls-files -z --cached --others --exclude-standard -- '*.cpp' '*.hpp' '*.h' '*README.md' |
    xargs -0 cp --parents -t "$tmp/tree")
}
# expect RC PATTERN: the check on the copy exits RC and its output matches PATTERN.
expect() {
  local rc=$1 pattern=$2 name=$3 out got
  out=$(bash "$root/scripts/check-layers.sh" "$tmp/tree" 2>&1)
  got=$?
  if [ "$got" = "$rc" ] && grep -qE -- "$pattern" <<<"$out"; then
    passed=$((passed + 1))
    echo "ok: $name"
  else
    failed=$((failed + 1))
    echo "FAIL: $name (exit $got, wanted $rc and /$pattern/):"
    echo "$out"
  fi
}

copy_tree
expect 0 '^check-layers: ok' "the tree as it is passes"

# tilesets/ may include only base/: one include of the engine is named with file and line.
file="$tmp/tree/tilesets/tile.hpp"
printf '#include "solver/problem.hpp"\n' >>"$file"
n=$(wc -l <"$file")
expect 1 "tilesets/tile.hpp:$n: includes solver/problem.hpp, but tilesets/README.md may include only: base" \
  "an include outside the 'May include' line fails"

# The same include allowed by the README, and solver/ including tilesets/ as it does: a cycle.
sed -i 's/^May include: `base\/`\./May include: `solver\/`, `base\/`./' "$tmp/tree/tilesets/README.md"
expect 1 "a cycle among the folders' includes: .*(solver|tilesets)" "an include cycle fails"
expect 1 "a cycle among the folders' README 'May include' lines" "a cycle between README lines fails"

copy_tree
sed -i '/^May include:/d' "$tmp/tree/image/README.md"
expect 1 "image/README.md: needs exactly one line starting 'May include:'" "a README without the line fails"

copy_tree
sed -i 's/^May include: .*/May include: `base\/`, `nowhere\/`./' "$tmp/tree/tiling/README.md"
expect 1 'tiling/README.md: .May include. names `nowhere/`' "a README naming no folder fails"

echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
