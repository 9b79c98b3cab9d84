#!/usr/bin/env bash
# Lists the functions of the libraries and the CLI longer than a bound, longest first, as a
# Markdown table (lines from the signature to the closing brace, lambdas inside included), with
# Universal Ctags. Usage: scripts/function-lengths.sh [MIN_LINES (default 80)] [ROOT]
set -euo pipefail
min=${1:-80}
root=${2:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root"
command -v ctags >/dev/null && ctags --version 2>/dev/null | grep -q 'Universal Ctags' ||
  { echo "function-lengths: needs Universal Ctags (apt-get install universal-ctags)" >&2; exit 2; }
folders=()
for d in */; do
  d=${d%/}
  case "$d" in build* | bench | tests | fuzz | shared) continue ;; esac
  [ -n "$(find "$d" -name '*.cpp' -o -name '*.hpp' | head -n 1)" ] && folders+=("$d")
done
echo "| function | lines | where |"
echo "|---|---|---|"
ctags --languages=C++ --kinds-C++=f --fields=+ne --extras=-q -o - -R "${folders[@]}" 2>/dev/null |
  awk -F'\t' -v min="$min" '{
    line = ""; end = ""
    for (i = 4; i <= NF; i++) {
      if ($i ~ /^line:/) line = substr($i, 6)
      if ($i ~ /^end:/) end = substr($i, 5)
    }
    if (line != "" && end != "" && end - line + 1 > min) printf "%d\t%s\t%s:%s\n", end - line + 1, $1, $2, line
  }' | sort -t$'\t' -k1,1nr -k3,3 | awk -F'\t' '{ printf "| `%s` | %d | %s |\n", $2, $1, $3 }'
