#!/usr/bin/env bash
# The main job on the embedded default. Grows with the product (see README.md).
# Gets a corner packing for an atlas (database hit, else a construction, else a search),
# checks it with the independent validator, stores it in the per-user results database,
# writes the atlas lookup (JSON, C header, GLSL) and the atlas picture, synthesises texture tiles
# from a real texture (CC0 grass), lays them out as an atlas and renders a surface with them (CPU,
# and GLSL through headless EGL where it can), renders the same view with trilinear filtering and
# with the hex and hpn baselines, writes the live preview page (and captures one view of it in a
# headless browser where chromium is installed), and says where everything went and how to query it.
#   TILEKIT_MAIN_COLORS  colours of the corner packing (default 6 = 2 x 3: stored x closed form)
#   TILEKIT_MAIN_OUT     output folder (default: out/main-job in the repository)
#   TILEKIT_DB           results database (default: the per-user data directory)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"

C=${TILEKIT_MAIN_COLORS:-6}
out=${TILEKIT_MAIN_OUT:-$root/out/main-job}
mkdir -p "$out"

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

echo "== 0. a tiling to look at"
demo_corner_tiling
db=$("$tk" db stats --json | sed -n 's/.*"db":"\([^"]*\)".*/\1/p')
packing="$out/packing-corner-$C.json"
echo
echo "== 1. corner packing over $C colours (database, else construction, else search)"
if ! "$tk" atlas lookup --kind corner --colors "$C" --db "$db" --out "$packing"; then
  echo "no stored or constructible packing: searching (stored in $db by pack)"
  "$tk" pack --kind corner --colors "$C" --method search --db "$db" --time-limit "${TILEKIT_MAIN_SEARCH_SECONDS:-600}" \
    --out "$packing"
  "$tk" atlas lookup --kind corner --colors "$C" --db "$db" --out "$packing"
fi
echo
echo "== 2. independent validator"
"$tk" check "$packing"
echo
echo "== 3. store it in the results database"
source=$(grep -o '"source":"[a-z]*"' "$packing" | cut -d'"' -f4)
how=$(grep -o '"how":"[^"]*"' "$packing" | cut -d'"' -f4)
echo "the packing came from: $source ($how)"
"$tk" db add "$packing" --method "$source" --db "$db"
id=$("$tk" db list --kind corner --colors "$C" --limit 0 --json --db "$db" |
  grep -o "\"id\":[0-9]*" | tail -1 | cut -d: -f2)
echo
echo "== 4. atlas lookup tables and picture"
"$tk" atlas lookup --kind corner --colors "$C" --db "$db" --format c --out "$out/atlas-corner-$C.h"
"$tk" atlas lookup --kind corner --colors "$C" --db "$db" --format glsl --out "$out/atlas-corner-$C.glsl"
"$tk" atlas build --kind corner --colors "$C" --db "$db" --tile-size 24 --out "$out/atlas-corner-$C.png"
echo
echo "== 5. the results database"
"$tk" db stats --db "$db"
echo
echo "== 6. texture tiles from a real texture, their atlas and a rendered surface"
"$root/scripts/fetch-textures.sh"
tex=$out/texture-grass
# C = 4 with thin shared bands: the setting that hides the grid best on irregular textures
# (grid repetition 0.025 against 0.065 for C = 3, 128 px, default bands; BENCHMARKS.md).
"$tk" texture tiles --exemplar grass --kind corner --colors 4 --tile-px 64 --thin-bands --out "$tex/tiles" --quiet
"$tk" texture atlas "$tex/tiles" --out "$tex/atlas.png" --db "$db"
view=(--size 1600x900 --scale 1 --tilt 3 --quiet)
"$tk" texture render --atlas "$tex/atlas.png" "${view[@]}" --out "$tex/surface.png"
if "$tk" texture render --atlas "$tex/atlas.png" "${view[@]}" --compare --out "$tex/surface-glsl.png"; then
  glsl="$tex/surface-glsl.png (GLSL sampler, headless EGL)"
else
  glsl="skipped (no EGL context here; see the message above)"
fi
echo
echo "== 7. the same view: trilinear instead of 16x anisotropic, and the baselines hex and hpn"
"$tk" texture render --atlas "$tex/atlas.png" "${view[@]}" --aniso 1 --out "$tex/surface-trilinear.png"
for m in hex hpn; do
  "$tk" texture render --method "$m" --exemplar grass "${view[@]}" --out "$tex/surface-$m.png"
done
echo
echo "== 8. the live preview page (WebGL2, the same GLSL), and one view of it in a headless browser"
"$tk" texture preview --atlas "$tex/atlas.png" --exemplar grass --out "$tex/preview.html"
if "$root/scripts/capture-preview.sh" "$tex/preview.html" 'u=0&v=0&scale=1&seed=1&tilt=3' 800x450 \
  "$tex/preview-capture.png"; then
  capture="$tex/preview-capture.png (chromium headless, SwiftShader WebGL2)"
else
  capture="skipped (no chromium here; scripts/setup.sh installs it)"
fi
cat <<EOF

Where everything went:
  packing (tiling JSON)   $packing
  C header / GLSL         $out/atlas-corner-$C.h, $out/atlas-corner-$C.glsl
  atlas picture           $out/atlas-corner-$C.png
  results database        $db (solution $id)
  texture tiles (grass)   $tex/tiles/tileset.png (256 corner tiles, C = 4, thesis 5.3)
  texture atlas + mips    $tex/atlas.png, $tex/atlas.mip1.png ..., $tex/atlas.glsl (sampler)
  rendered surface        $tex/surface.png (CPU reference, 16x anisotropic filtering)
  the same through GLSL   $glsl
  comparison, same view   $tex/surface-trilinear.png (tiles, trilinear filtering)
                          $tex/surface-hex.png (hex tiling, Mikkelsen 2022, from the exemplar)
                          $tex/surface-hpn.png (histogram-preserving blending, Heitz & Neyret 2018)
  live preview page       $tex/preview.html (open it in a browser: drag, wheel, tilt, methods)
  a view of the page      $capture
How to query it:
  $tk db list --db '$db'
  $tk db show $id --db '$db' --json
  $tk db export --format csv --db '$db'
  sqlite3 '$db' "SELECT id, kind, colors, rows, cols, method, validated FROM solutions"
EOF
