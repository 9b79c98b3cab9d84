#!/usr/bin/env bash
# The README's texture pictures (docs/images/texture-*.png), each from a tilekit command:
#   texture-gravel-{corner-tiles,atlas}.png  the corner tile set (C = 2, 64 px) from the fetched
#       CC0 gravel texture and its atlas laid out by the packing from `atlas lookup` (16 tiles, to
#       be seen one by one);
#   texture-gravel-surface.png  a tilted render of the infinite virtual texture of the C = 4 corner
#       tiles with thin bands (256 tiles; 16x anisotropic filtering): C = 2's 16 tiles recur often
#       enough to show as rows of the same stones toward the horizon;
#   texture-gravel-surface-{trilinear,hex,hpn}.png  the same view with trilinear filtering, and with
#       the hex and hpn baselines;
#   texture-grid-{grass,gravel,oa-dirt,gimp-stone33}.png  flat 256x256 renders of corner tiles
#       (C = 4, 64 px, --thin-bands) of four real textures, the grid hidden;
#   texture-grid-{brick,oa-brick}.png  the same of the two brick walls (default bands: a periodic
#       exemplar keeps them);
#   texture-grid-labels.png  the samples of the grass view, one colour each (the shared bands along
#       the borders, the corner squares, a centre patch per tile);
#   texture-grid-spectrum.png  `texture analyze --plot` of a 1024x1024 grass render.
#   texture-heldout-{ufo-brick,ufo-tile,ufo-wood,ufo-dirt,re-brick1,re-brick2,re-tile1,re-wood1}-
#       {tiles,hex,hpn,naive}.png  (--held-out: only these) flat 256x256 renders of held-out
#       textures (scripts/fetch-textures.sh --held-out), side by side: corner tiles (C = 4, UFO's
#       at 64 px, Red Eclipse's at the default tile size, --thin-bands, which a periodic exemplar ignores),
#       hex tiling, histogram-preserving blending and the naive mosaic of random 64-px crops
#       (build/bench_texture_quality's, so that needs the benchmarks built).
# The exemplars are never copied into the repository (scripts/fetch-textures.sh caches them).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"
img="$root/docs/images"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ "${1:-}" = --held-out ]; then
  "$root/scripts/fetch-textures.sh" --held-out
  cache=${TILEKIT_TEXTURES:-${XDG_CACHE_HOME:-$HOME/.cache}/tilekit/textures}
  # NAME and tile size: UFO's at 64 px, Red Eclipse's at the default (--tile-px auto)
  while read -r t px; do
    ex=$cache/$t.png
    [ -s "$ex" ] || ex=$cache/$t.jpg
    "$tk" texture tiles --exemplar "$ex" --tileable --kind corner --colors 4 --tile-px "$px" --seed 1 --thin-bands \
      --out "$work/$t/tiles" --quiet
    "$tk" texture atlas "$work/$t/tiles" --out "$work/$t/atlas.png" --no-db
    "$tk" texture render --atlas "$work/$t/atlas.png" --size 256x256 --out "$img/texture-heldout-$t-tiles.png" --quiet
    for m in hex hpn; do
      "$tk" texture render --method "$m" --exemplar "$ex" --size 256x256 --quiet --out "$img/texture-heldout-$t-$m.png"
    done
    "$root/build/bench_texture_quality" --textures "$t" --kinds corner --colors 2 --size 256 --threads 2 \
      --out "$work" >/dev/null
    cp "$work/$t-naive.png" "$img/texture-heldout-$t-naive.png"
  done <<'LIST'
ufo-brick 64
ufo-tile 64
ufo-wood 64
ufo-dirt 64
re-brick1 auto
re-brick2 auto
re-tile1 auto
re-wood1 auto
LIST
  echo "texture-pictures: $img/texture-heldout-*.png"
  exit 0
fi
"$root/scripts/fetch-textures.sh"
"$tk" texture tiles --exemplar gravel --kind corner --colors 2 --tile-px 64 --seed 1 --wide-bands --out "$work/tiles" --quiet
"$tk" texture atlas "$work/tiles" --out "$work/atlas.png" --no-db
view=(--size 640x360 --scale 1 --tilt 2 --quiet)
cp "$work/tiles/tileset.png" "$img/texture-gravel-corner-tiles.png"
cp "$work/atlas.png" "$img/texture-gravel-atlas.png"
for t in grass gravel oa-dirt gimp-stone33; do
  mkdir -p "$work/$t" "$work/$t-labels"
  "$tk" texture tiles --exemplar "$t" --kind corner --colors 4 --tile-px 64 --seed 1 --thin-bands --out "$work/$t/tiles" --quiet
  "$tk" texture atlas "$work/$t/tiles" --out "$work/$t/atlas.png" --no-db
  "$tk" texture render --atlas "$work/$t/atlas.png" --size 256x256 --out "$img/texture-grid-$t.png" --quiet
done
for t in brick oa-brick; do
  mkdir -p "$work/$t"
  "$tk" texture tiles --exemplar "$t" --kind corner --colors 4 --tile-px 64 --seed 1 --out "$work/$t/tiles" --quiet
  "$tk" texture atlas "$work/$t/tiles" --out "$work/$t/atlas.png" --no-db
  "$tk" texture render --atlas "$work/$t/atlas.png" --size 256x256 --out "$img/texture-grid-$t.png" --quiet
done
"$tk" texture render --atlas "$work/gravel/atlas.png" "${view[@]}" --out "$img/texture-gravel-surface.png"
"$tk" texture render --atlas "$work/gravel/atlas.png" "${view[@]}" --aniso 1 --out "$img/texture-gravel-surface-trilinear.png"
for m in hex hpn; do
  "$tk" texture render --method "$m" --exemplar gravel "${view[@]}" --out "$img/texture-gravel-surface-$m.png"
done
"$tk" texture atlas "$work/grass/tiles/labels" --out "$work/grass-labels/atlas.png" --no-db
"$tk" texture render --atlas "$work/grass-labels/atlas.png" --size 256x256 --out "$img/texture-grid-labels.png" --quiet
"$tk" texture render --atlas "$work/grass/atlas.png" --size 1024x1024 --out "$work/grass-1024.png" --quiet
"$tk" texture analyze "$work/grass-1024.png" --tile-px 64 --exemplar grass --plot "$img/texture-grid-spectrum.png"
echo "texture-pictures: $img/texture-gravel-{corner-tiles,atlas,surface,surface-trilinear,surface-hex,surface-hpn}.png, $img/texture-grid-*.png"
