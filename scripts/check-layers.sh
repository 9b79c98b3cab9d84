#!/usr/bin/env bash
# The layer check: every top-level folder that holds C++ sources has a README.md with one line
#   May include: `a/`, `b/`.            (the project folders its files may #include)
#   May include: nothing in the project.
#   May include: every library.         (cli/, bench/, tests/: the top of the graph)
# This script fails (exit 1, one line per problem) on an #include of a project folder that the
# line does not name, on a folder whose README lacks the line, and on any cycle, both among the
# folders' actual includes and among the README lines themselves. Includes inside a folder are
# free. It also fails on a string literal in a library (every folder but the top of the graph:
# cli/, tests/, bench/, fuzz/, examples/, scripts/) that names a command-line flag ("--shard ..."):
# libraries name the fields of their requests (base/error.hpp's RequestError) and the CLI words
# them as flags. Comments may mention flags; scripts/flag-literals.pl reads the literals.
# Usage: scripts/check-layers.sh [ROOT] (default: this repository); tests/scripts/
# check-layers-test.sh runs it on a copy of the tree with one bad include, one flag literal, ...
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=${1:-$(cd "$here/.." && pwd)}
cd "$root"

sources() { find "$1" \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \) -type f; }

# Project folders: top-level folders with C++ sources (build trees, hidden folders and folders git
# ignores aside: the main job writes C headers into out/).
folders=()
for d in */; do
  d=${d%/}
  case "$d" in build* | shared) continue ;; esac
  git check-ignore -q "$d/" 2>/dev/null && continue
  [ -n "$(sources "$d" | head -n 1)" ] && folders+=("$d")
done
is_folder() {
  local f
  for f in "${folders[@]}"; do [ "$f" = "$1" ] && return 0; done
  return 1
}

problems=0
fail() {
  echo "check-layers: $*" >&2
  problems=$((problems + 1))
}

declare -A allowed declared_edges actual_edges
for d in "${folders[@]}"; do
  lines=$(grep -c '^May include:' "$d/README.md" 2>/dev/null || true)
  if [ "${lines:-0}" != 1 ]; then
    fail "$d/README.md: needs exactly one line starting 'May include:' (found ${lines:-no file})"
    continue
  fi
  line=$(grep '^May include:' "$d/README.md")
  names=$(grep -oE '`[a-z_]+/`' <<<"$line" | tr -d '`/' || true)
  if grep -q 'every library' <<<"$line"; then
    allowed[$d]=" ${folders[*]} "
  elif [ -n "$names" ]; then
    allowed[$d]=" $(tr '\n' ' ' <<<"$names")"
    for n in $names; do
      is_folder "$n" || fail "$d/README.md: 'May include' names \`$n/\`, which is not a project folder"
      [ "$n" != "$d" ] && declared_edges["$d $n"]=1
    done
  elif grep -q 'nothing in the project' <<<"$line"; then
    allowed[$d]=" "
  else
    fail "$d/README.md: cannot read its 'May include' line: $line"
  fi
done

# Every #include "folder/..." (or <folder/...> of a project folder) against the line.
for d in "${folders[@]}"; do
  [ -n "${allowed[$d]+x}" ] || continue
  while IFS=: read -r file lineno target; do
    top=${target%%/*}
    [ "$top" = "$target" ] && continue  # "file.hpp": the folder's own
    is_folder "$top" || continue        # <fmt/format.h>, <sys/...>: not the project's
    [ "$top" = "$d" ] && continue
    actual_edges["$d $top"]=1
    case "${allowed[$d]}" in
      *" $top "*) ;;
      *) fail "$file:$lineno: includes $target, but $d/README.md may include only:${allowed[$d]}" ;;
    esac
  done < <(sources "$d" | sort | xargs grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"][^>"]+[>"]' /dev/null |
    sed -E 's/^([^:]+):([0-9]+):.*#[[:space:]]*include[[:space:]]*[<"]([^>"]+)[>"].*/\1:\2:\3/')
done

# Flag names in the libraries' string literals: the top of the graph (the CLI, tests, benchmarks,
# fuzzers, examples) may name flags; a library names its request's fields instead.
for d in "${folders[@]}"; do
  case "$d" in cli | tests | bench | fuzz | examples | scripts) continue ;; esac
  while IFS= read -r hit; do
    fail "$hit: a library's string literal names a command-line flag (name the request field, \`field\`, in a RequestError: base/error.hpp)"
  done < <(sources "$d" | sort | xargs perl "$here/flag-literals.pl")
done

# Cycles: tsort names the folders on a loop.
check_cycles() {
  local what=$1
  shift
  local out
  out=$(printf '%s\n' "$@" | tsort 2>&1 >/dev/null || true)
  if [ -n "$out" ]; then
    fail "a cycle among the $what: $(grep -v 'input contains a loop' <<<"$out" | sed 's/^tsort: //' | tr '\n' ' ')"
  fi
}
check_cycles "folders' README 'May include' lines" "${!declared_edges[@]}"
check_cycles "folders' includes" "${!actual_edges[@]}"

if ((problems)); then
  echo "check-layers: FAILED, $problems problem(s) in ${#folders[@]} folders" >&2
  exit 1
fi
echo "check-layers: ok (${#folders[@]} folders, ${#actual_edges[@]} include arrows between them, no cycle, no flag literal in a library)"
