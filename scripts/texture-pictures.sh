#!/usr/bin/env bash
# The README's texture pictures (docs/images/texture-*.png), each from a tilekit command: the
# corner tile set (C = 2, 64 px) synthesised from the fetched CC0 gravel texture, its atlas laid
# out by the packing from `atlas lookup`, a tilted render of the infinite virtual texture (16x
# anisotropic filtering), the same view with trilinear filtering, and with the hex and hpn baselines.
# The exemplar itself is never copied into the repository (scripts/fetch-textures.sh caches it).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"
img="$root/docs/images"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$root/scripts/fetch-textures.sh"
"$tk" texture tiles --exemplar gravel --kind corner --colors 2 --tile-px 64 --seed 1 --out "$work/tiles" --quiet
"$tk" texture atlas "$work/tiles" --out "$work/atlas.png" --no-db
view=(--size 640x360 --scale 1 --tilt 2 --quiet)
"$tk" texture render --atlas "$work/atlas.png" "${view[@]}" --out "$img/texture-gravel-surface.png"
"$tk" texture render --atlas "$work/atlas.png" "${view[@]}" --aniso 1 --out "$img/texture-gravel-surface-trilinear.png"
for m in hex hpn; do
  "$tk" texture render --method "$m" --exemplar gravel "${view[@]}" --out "$img/texture-gravel-surface-$m.png"
done
cp "$work/tiles/tileset.png" "$img/texture-gravel-corner-tiles.png"
cp "$work/atlas.png" "$img/texture-gravel-atlas.png"
echo "texture-pictures: $img/texture-gravel-{corner-tiles,atlas,surface,surface-trilinear,surface-hex,surface-hpn}.png (exemplar: ${TILEKIT_TEXTURES:-${XDG_CACHE_HOME:-$HOME/.cache}/tilekit/textures}/gravel.png)"
