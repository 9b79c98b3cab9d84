#!/usr/bin/env bash
# The main job on the embedded default. Grows with the product (see README.md); each part is
# one step function below. Output goes under ./out/ (or $TILEKIT_OUT).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"
out=${TILEKIT_OUT:-./out}

# Step: a 3-colour corner tiling by the direct stochastic algorithm (thesis sec. 3.3.1),
# validated, written as a tiling file and drawn as SVG and PNG.
demo_corner_tiling() {
  mkdir -p "$out"
  local base="$out/corner-tiling-3"
  "$tk" tile --set complete-corner-3 --algo direct --size 16x16 --seed 1 --out "$base.json"
  "$tk" check "$base.json" --set complete-corner-3 >/dev/null
  "$tk" tile --set complete-corner-3 --algo direct --size 16x16 --seed 1 --out "$base.svg" >/dev/null
  "$tk" tile --set complete-corner-3 --algo direct --size 16x16 --seed 1 --out "$base.png" >/dev/null
  echo "main job: 3-colour corner tiling (direct, 16x16, seed 1) written to:"
  echo "  $base.json (tiling file, checked by \`tilekit check\`)"
  echo "  $base.svg"
  echo "  $base.png"
}

demo_corner_tiling
