#!/usr/bin/env bash
# The terrain pictures of docs/guide/terrain.md (docs/images/terrain-*.png), each from a tilekit
# command on the fetched real textures (scripts/fetch-textures.sh; never copied into the repository):
#   terrain-2-sheet.png   the packed sheet of the C = 2 terrain set (grass, oa-dirt; 16 tiles of 64 px);
#   terrain-2-wrapped.png that sheet repeated 2x2 as a Tiled map, rendered by Tiled's tmxrasterizer:
#                         the sheet's own borders wrap seamlessly;
#   terrain-3-sheet.png   the packed sheet of the C = 3 set (grass, oa-dirt, gravel; 81 tiles of 48 px);
#   terrain-3-map.png     a 384x384 flat render of that set's atlas (the direct stochastic tiling);
#   terrain-3-straight.png the same view of the baseline, `--seams straight` (terrain boundaries on the
#                         tiles' middle lines, same seed).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"
img="$root/docs/images"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$root/scripts/fetch-textures.sh"
"$tk" texture terrain --terrain grass=grass --terrain dirt=oa-dirt --seed 1 --out "$work/c2" --tiled "$work/c2-tiled" --quiet
cp "$work/c2/sheet.png" "$img/terrain-2-sheet.png"
# the sheet 2x2 as a Tiled map: tile ids (r mod 4) * 4 + (c mod 4), gids from 1
{
  echo '<?xml version="1.0" encoding="UTF-8"?>'
  echo '<map version="1.8" orientation="orthogonal" renderorder="right-down" width="8" height="8" tilewidth="64" tileheight="64" infinite="0" nextlayerid="2" nextobjectid="1">'
  echo ' <tileset firstgid="1" source="terrain-grass-dirt.tsx"/>'
  echo ' <layer id="1" name="sheet" width="8" height="8">'
  echo '  <data encoding="csv">'
  for r in 0 1 2 3 4 5 6 7; do
    row=""
    for c in 0 1 2 3 4 5 6 7; do row+="$(((r % 4) * 4 + c % 4 + 1)),"; done
    [ "$r" = 7 ] && row=${row%,}
    echo "$row"
  done
  echo '</data>'
  echo ' </layer>'
  echo '</map>'
} > "$work/c2-tiled/wrap.tmx"
QT_QPA_PLATFORM=offscreen tmxrasterizer "$work/c2-tiled/wrap.tmx" "$img/terrain-2-wrapped.png"
for seams in graph-cut straight; do
  "$tk" texture terrain --terrain grass=grass --terrain dirt=oa-dirt --terrain gravel=gravel --seed 1 --seams "$seams" \
    --tile-px 48 --out "$work/c3-$seams" --quiet
  "$tk" texture atlas "$work/c3-$seams" --out "$work/c3-$seams-atlas/atlas.png" --quiet
done
cp "$work/c3-graph-cut/sheet.png" "$img/terrain-3-sheet.png"
"$tk" texture render --atlas "$work/c3-graph-cut-atlas/atlas.png" --size 384x384 --seed 2 --out "$img/terrain-3-map.png" --quiet
"$tk" texture render --atlas "$work/c3-straight-atlas/atlas.png" --size 384x384 --seed 2 --out "$img/terrain-3-straight.png" --quiet
echo "terrain-pictures: $img/terrain-{2-sheet,2-wrapped,3-sheet,3-map,3-straight}.png"
