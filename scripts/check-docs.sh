#!/usr/bin/env bash
# The doc check: the docs say what the tree holds. Fails (exit 1, one line per problem) when
#   (a) a source file of a library folder (a top-level folder whose CMakeLists.txt makes a
#       library, or cli/) is not named in that folder's README.md: its name, its path from the
#       folder, or a pattern that covers it (`progress.*` or `progress.hpp/.cpp` names both files);
#   (b) a file a doc names does not exist. The docs are every *.md file of the tree (README.md,
#       BENCHMARKS.md, docs/**, the folder READMEs). Checked: markdown links to local files
#       (relative to the doc, as a reader's browser resolves them), and, in `code spans`, code
#       blocks and prose, paths that start with a top-level folder of the tree (`solver/solve.cpp`,
#       `scripts/x.sh`) or bare file names with a source or script extension (`cell_model.*`,
#       `run.sh`), relative to the repository root or to the doc's folder; `*` globs must match
#       a file. Not checked: URLs, absolute and home paths, build trees (build/, build-asan/...),
#       placeholders (an upper-case stem or folder such as `F.json`, `DIR/labels/`) and the short
#       list of generated outputs below;
#   (c) README.md is over 250 lines, or its first code block is not the two commands
#       `bash scripts/run.sh` and `bash scripts/test.sh` (CI runs the second);
#   (d) BENCHMARKS.md carries an issue, branch or commit stamp (history stays in git).
# Usage: scripts/check-docs.sh [ROOT] (default: this repository). tests/scripts/check-docs-test.sh
# runs it on a copy of the tree with one deliberate violation of each kind.
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root"

problems=0
fail() {
  echo "check-docs: $*" >&2
  problems=$((problems + 1))
}

# Generated outputs the docs name as examples of what a command writes (not files of the tree).
generated=(
  atlas.h atlas.glsl         # texture atlas's header and shader, beside its PNG
  submit.sh                  # cluster submit's script in the run directory
  TilekitConfig.cmake        # cmake --install's package file
  build_paths.cpp            # written by the build (tests/CMakeLists.txt)
)

# Top-level folders of the tree (not build trees, hidden or ignored folders, nor shared/).
top=()
for d in */; do
  d=${d%/}
  case "$d" in build* | shared | Testing) continue ;; esac
  if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git check-ignore -q "$d/" 2>/dev/null && continue
  fi
  top+=("$d")
done
is_top() {
  local d
  for d in "${top[@]}"; do [ "$d" = "$1" ] && return 0; done
  return 1
}

# ---- (a) every source file of a library folder is named in its README.
source_pattern='.*\.(cpp|hpp|h|c|cc|glsl|vert|frag|js)$'
for d in "${top[@]}"; do
  [ -f "$d/CMakeLists.txt" ] || continue
  grep -qE 'add_library|tilekit_library\(|add_executable\(tilekit ' "$d/CMakeLists.txt" || continue
  case "$d" in bench | tests | fuzz | examples) continue ;; esac
  readme="$d/README.md"
  if [ ! -f "$readme" ]; then
    fail "$d/: a library folder without a README.md"
    continue
  fi
  # the name or its path inside the folder, stem.* or stem.hpp/.cpp, with no letter, digit or
  # _ on either side (so that input.hpp is not named by json_input.hpp)
  while IFS= read -r f; do
    fail "$readme: does not name $f (a source file of the folder)"
  done < <(find "$d" -type f -regextype posix-extended -regex "$source_pattern" | sort |
    awk -v d="$d" -v readme="$readme" '
      BEGIN { while ((getline line < readme) > 0) text = text "\n" line; text = text "\n" }
      function esc(w) { gsub(/[][.*^$\/+?(){}|\\]/, "\\\\&", w); return w }
      function named(w) { return text ~ ("[^A-Za-z0-9_]" esc(w) "([^A-Za-z0-9_]|$)") }
      {
        rel = substr($0, length(d) + 2); name = rel; sub(/.*\//, "", name)
        stem = name; sub(/\.[^.]*$/, "", stem)
        if (!(named(rel) || named(name) || named(stem ".*") || named(stem ".hpp/.cpp"))) print
      }')
done

# ---- (b) every file a doc names exists.
# awk reads a doc and prints what to look for, one per line: LINE<TAB>KIND<TAB>PATH, KIND
# `link` (relative to the doc only) or `name` (relative to the root or the doc's folder).
candidates() {
  awk -v top=" ${top[*]} " -v generated=" ${generated[*]} " '
    function placeholder(p,    n, i, part) {
      n = split(p, part, "/")
      for (i = 1; i <= n; i++) {
        sub(/\..*$/, "", part[i])
        if (part[i] ~ /^[A-Z][A-Z0-9_]*$/ && part[i] !~ /^(README|BENCHMARKS|TESTING|ARCHITECTURE)$/) return 1
        if (part[i] ~ /[-_][A-Z]$/) return 1          # packing-corner-C.json, shard-I.ckpt
      }
      return 0
    }
    function consider(kind, p,    first) {
      sub(/^.*=/, "", p)                            # --out=F, rows=FILE
      gsub(/^[("'"'"'<\[]+/, "", p)
      gsub(/[]),.;:"'"'"'>!?]+$/, "", p)
      sub(/:[0-9]+(:[0-9]+)?$/, "", p)              # file:12
      sub(/^\.\//, "", p)
      if (p == "" || p ~ /:\/\// || p ~ /^[\/~$-]/ || p ~ /^build(-[^\/]*)?\// || p ~ /[{<]|\.\./) return
      if (p !~ /^[A-Za-z0-9_.*\/+-]+$/) return
      if (index(p, "/")) {
        first = p; sub(/\/.*$/, "", first)
        if (index(top, " " first " ") == 0 || p == first "/") return
        if (p ~ /\/s$/) return                     # a rate: points/s
        if (kind == "prose" && p !~ /(\.[A-Za-z0-9*]+|\/)$/) return   # tiling/packing: words
      } else {
        # a bare name: files with a source, script or doc extension, and stem.* patterns
        if (kind != "code" || p !~ /\.(cpp|hpp|h|sh|md|glsl|js|py|cmake|\*)$/) return
        if (p ~ /^[A-Z][A-Za-z0-9]*\.\*$/) return   # a ctest pattern: LayerCheck.*
      }
      if (index(generated, " " p " ") || placeholder(p)) return
      printf "%d\tname\t%s\n", FNR, p
    }
    function words(kind, s,    n, i, w) {
      n = split(s, w, /[ \t|]+/)
      for (i = 1; i <= n; i++) if (w[i] != "") consider(kind, w[i])
    }
    /^[ \t]*```/ { fence = !fence; next }
    fence { words("code", $0); next }
    {
      line = $0
      rest = line
      while (match(rest, /\]\([^) \t]+\)/)) {       # [text](target), ![alt](target)
        t = substr(rest, RSTART + 2, RLENGTH - 3)
        sub(/#.*$/, "", t)
        if (t != "" && t !~ /^[a-z]+:/) printf "%d\tlink\t%s\n", FNR, t
        rest = substr(rest, RSTART + RLENGTH)
      }
      gsub(/\]\([^) \t]+\)/, "]", line)
      out = ""
      while (match(line, /`[^`]+`/)) {              # code spans
        words("code", substr(line, RSTART + 1, RLENGTH - 2))
        out = out substr(line, 1, RSTART - 1) " "
        line = substr(line, RSTART + RLENGTH)
      }
      words("prose", out line)
    }' "$1"
}

exists() {  # exists PATH: a file or folder, or a glob that matches one
  local p=$1 m
  if [[ "$p" == *'*'* ]]; then
    for m in $p; do [ -e "$m" ] && return 0; done
    return 1
  fi
  [ -e "$p" ]
}

docs=()
while IFS= read -r f; do docs+=("$f"); done < <(
  find . \( -path './build*' -o -path './shared' -o -path './.*' -o -path './Testing' -o -path './out' \) -prune \
    -o -type f -name '*.md' -print | sed 's|^\./||' | sort)
for doc in "${docs[@]}"; do
  dir=$(dirname "$doc")
  while IFS=$'\t' read -r line kind p; do
    if [ "$kind" = link ]; then
      exists "$dir/$p" || fail "$doc:$line: links to $p, which does not exist (relative to $dir/)"
    else
      exists "$p" || exists "$dir/$p" || fail "$doc:$line: names $p, which does not exist"
    fi
  done < <(candidates "$doc")
done

# ---- (c) README.md: at most 250 lines, and it opens with the two commands.
if [ -f README.md ]; then
  n=$(wc -l <README.md)
  [ "$n" -le 250 ] || fail "README.md: $n lines, more than 250 (move the depth to docs/guide/)"
  block=$(awk '/^```/ { if (open) exit; open = 1; next } open' README.md)
  first_text=$(awk '!/^(# .*|)$/ { print; exit }' README.md)
  if [ "$first_text" != '```' ] ||
    [ "$(sed -n 1p <<<"$block" | awk '{print $1, $2}')" != 'bash scripts/run.sh' ] ||
    [ "$(sed -n 2p <<<"$block" | awk '{print $1, $2}')" != 'bash scripts/test.sh' ] ||
    [ "$(wc -l <<<"$block")" != 2 ]; then
    fail "README.md: must open (after its title) with the code block of the two commands 'bash scripts/run.sh' and 'bash scripts/test.sh'"
  fi
else
  fail "README.md: missing"
fi

# ---- (d) BENCHMARKS.md: no issue, branch or commit stamps.
if [ -f BENCHMARKS.md ]; then
  while IFS=: read -r line text; do
    fail "BENCHMARKS.md:$line: an issue, branch or commit stamp: $text"
  done < <(grep -niE '\bissues?\b|#[0-9]|\bbranch(es)?\b|\bcommits?\b|\bstop [0-9]' BENCHMARKS.md || true)
  # a commit hash: a word of 7 to 40 hex digits with both a digit and a letter in it
  while IFS=: read -r line word; do
    word=$(tr -dc '0-9a-f' <<<"$word")
    [[ "$word" =~ ^[0-9]+e[0-9]+$ ]] && continue   # 5.42e1068: a number
    if [[ "$word" =~ [0-9] && "$word" =~ [a-f] ]]; then fail "BENCHMARKS.md:$line: a commit hash: $word"; fi
  done < <(grep -noE '(^|[^A-Za-z0-9_])[0-9a-f]{7,40}([^A-Za-z0-9_]|$)' BENCHMARKS.md || true)
fi

if ((problems)); then
  echo "check-docs: FAILED, $problems problem(s)" >&2
  exit 1
fi
echo "check-docs: ok (${#docs[@]} docs, every library source file listed, every named file present)"
