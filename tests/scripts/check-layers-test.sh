#!/usr/bin/env bash
# scripts/check-layers.sh on a copy of the tree (sources and READMEs): it passes on the tree as
# it is, and fails, naming the problem, on one include outside a README's "May include" line,
# on a cycle, on a README without the line, and on a library string literal that names a
# command-line flag (not on one in a comment, in cli/ or in tests/). Usage: check-layers-test.sh
# [includes|flags] (default: both groups). Prints "N passed, M failed"; exit 1 on a failure.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$root/tests/scripts/expect_check.sh"
copy_tree() {
  rm -rf "$tmp/tree" && mkdir "$tmp/tree"
  # the files git tracks or would track (not build trees, nor outputs it ignores such as out/)
  (cd "$root" && git ls-files -z --cached --others --exclude-standard -- '*.cpp' '*.hpp' '*.h' '*README.md' |
    xargs -0 cp --parents -t "$tmp/tree")
}
# expect RC PATTERN NAME: check-layers.sh on the copy exits RC and its output matches PATTERN.
expect() { expect_check "$root/scripts/check-layers.sh" "$@"; }

group=${1:-all}
copy_tree
expect 0 '^check-layers: ok' "the tree as it is passes"

if [ "$group" != flags ]; then

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
fi

if [ "$group" != includes ]; then

# A flag in a library's string literal fails, named with file and line; the same text in a
# comment, in another program's flag marked as such, and in the CLI and the tests passes.
copy_tree
file="$tmp/tree/solver/solve.cpp"
printf '// A comment may say --shard I/N.\nconst char* kOther = "--seed=1";  // cadical'"'"'s: not a tilekit flag\n' >>"$file"
printf 'const char* kFlag = "--shard I/N";\n' >>"$tmp/tree/cli/main.cpp"
printf 'const char* kFlag = "--shard I/N";\n' >>"$tmp/tree/tests/cli/test_pack.cpp"
expect 0 '^check-layers: ok' "flags in comments, marked literals, the CLI and the tests pass"
printf 'void f() { throw InputError("--shard must be I/N"); }\n' >>"$file"
n=$(wc -l <"$file")
expect 1 "solver/solve.cpp:$n: \"--shard must be I/N\": a library's string literal names a command-line flag" \
  "a flag in a library's string literal fails"
copy_tree
printf 'const char* kHelp = R"(use a smaller\n--tile-px)";\n' >"$tmp/tree/solver/raw_flag.cpp"
expect 1 "solver/raw_flag.cpp:2: .*names a command-line flag" "a flag on the second line of a raw string fails"
copy_tree
printf 'constexpr long kBig = 1'"'"'000'"'"'000;\nconst char* kFlag = "x --colors";\n' >"$tmp/tree/base/separator_flag.hpp"
expect 1 "base/separator_flag.hpp:2: \"x --colors\"" "a flag after a digit separator fails"
fi

finish_checks
