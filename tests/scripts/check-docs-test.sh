#!/usr/bin/env bash
# scripts/check-docs.sh on a copy of the tree (every file git tracks or would track): it passes on
# the tree as it is, and fails, naming the problem, on a source file its folder README does not
# name, on a doc naming a file that does not exist (a path and a link), on a README.md over 250
# lines or not opening with the two commands, and on a commit or issue stamp in BENCHMARKS.md.
# Prints "N passed, M failed"; exit 1 on a failure.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$root/tests/scripts/expect_check.sh"
# the files git tracks or would track (not build trees, nor outputs it ignores such as out/),
# copied once; each case starts from a fresh copy of that
(cd "$root" && git ls-files -z --cached --others --exclude-standard | while IFS= read -r -d '' f; do
  [ -e "$f" ] && printf '%s\0' "$f"
done | xargs -0 cp --parents -t "$(mkdir -p "$tmp/pristine" && echo "$tmp/pristine")")
copy_tree() {
  rm -rf "$tmp/tree" && cp -a "$tmp/pristine" "$tmp/tree"
}
# expect RC PATTERN NAME: check-docs.sh on the copy exits RC and its output matches PATTERN.
expect() { expect_check "$root/scripts/check-docs.sh" "$@"; }

copy_tree
expect 0 '^check-docs: ok' "the tree as it is passes"

# A new source file in tiling/ that tiling/README.md does not name.
printf '// a file nobody listed\n' >"$tmp/tree/tiling/unlisted_kernel.cpp"
expect 1 'tiling/README.md: does not name tiling/unlisted_kernel.cpp' "a source file missing from its folder README fails"
rm "$tmp/tree/tiling/unlisted_kernel.cpp"

# A README row that names the file by stem.* covers it; one that names only the .hpp does not.
printf '// listed by its stem\n' >"$tmp/tree/tiling/lattice_hash_extra.cpp"
printf '\n| `lattice_hash_extra.*` | listed |\n' >>"$tmp/tree/tiling/README.md"
expect 0 '^check-docs: ok' "a stem.* row names the file"

copy_tree
# A doc naming a file that is not there, as a path and as a link.
printf '\nSee `solver/no_such_model.hpp`.\n' >>"$tmp/tree/docs/ARCHITECTURE.md"
expect 1 'docs/ARCHITECTURE.md:[0-9]+: names solver/no_such_model.hpp, which does not exist' "a named file that does not exist fails"
copy_tree
printf '\n[the gone page](gone.md)\n' >>"$tmp/tree/docs/guide/README.md"
expect 1 'docs/guide/README.md:[0-9]+: links to gone.md' "a link to a missing file fails"
copy_tree
# Placeholders, URLs and build outputs are not files of the tree.
printf '\n`tilekit pack --out F.json`, `DIR/labels/`, https://example.org/x.md, `build/tilekit`\n' >>"$tmp/tree/docs/guide/README.md"
expect 0 '^check-docs: ok' "placeholders, URLs and build paths pass"

copy_tree
for i in $(seq 1 260); do echo "line $i"; done >>"$tmp/tree/README.md"
expect 1 'README.md: [0-9]+ lines, more than 250' "a README over 250 lines fails"
copy_tree
sed -i '0,/bash scripts\/test.sh/s//bash scripts\/tests.sh/' "$tmp/tree/README.md"
expect 1 "README.md: must open .* 'bash scripts/test.sh'" "a README whose opening block lacks the test command fails"
copy_tree
sed -i '1a\
\
Some words before the commands.' "$tmp/tree/README.md"
expect 1 "README.md: must open" "a README with text before the two commands fails"

copy_tree
printf '\n| a figure | 1.0 s | measured at commit 1a2b3c4d |\n' >>"$tmp/tree/BENCHMARKS.md"
expect 1 'BENCHMARKS.md:[0-9]+: a commit hash: 1a2b3c4d' "a commit hash in BENCHMARKS.md fails"
copy_tree
printf '\nMeasured on branch `texture-goals` for issue 12.\n' >>"$tmp/tree/BENCHMARKS.md"
expect 1 'BENCHMARKS.md:[0-9]+: an issue, branch or commit stamp' "a branch or issue stamp in BENCHMARKS.md fails"

finish_checks
