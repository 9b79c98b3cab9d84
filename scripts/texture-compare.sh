#!/usr/bin/env bash
# Renders every method (tiles, hex, hpn) on every texture, for the comparison table of tile-based
# texture mapping against hex tiling (Mikkelsen 2022) and histogram-preserving blending (Heitz &
# Neyret 2018): corner tiles C=4 of 64 px, flat 1024x1024 renders at scale 1 (what the measures
# read) and a tilted 1024x576 view (what people look at), all from one seed.
# Per texture and method it measures what needs no analysis: texture fetches per pixel, GLSL
# M fragments/s on llvmpipe (LP_NUM_THREADS=2, 1024x1024 flat, 10 frames after a warm-up) and
# texture memory; `tilekit texture analyze` adds its JSON for the flat render: grid repetition
# (tiles on their square lattice, hex and hpn on their own triangle lattice of side cell_px),
# seam ratio (square lattices only), cut visibility (tiles: with the labels of the same view;
# hex and hpn blend and have no cuts) and histogram distance.
# Tiles come twice, from the same run: `tiles` (`texture tiles --wide-bands`) and `tiles-thin`
# (`--thin-bands`, the default; a periodic exemplar keeps wide bands, so its two are the same).
# Usage: scripts/texture-compare.sh [EXEMPLAR...]   (default: every PNG in the texture cache)
#   TILEKIT_COMPARE_OUT  output folder (default: out/texture-compare in the repository)
# Writes OUT/NAME/{flat,tilted}-METHOD.png (METHOD: tiles, tiles-thin, hex, hpn), OUT/results.jsonl (one JSON object per texture and
# method) and OUT/table.md, and prints the table.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"
out=${TILEKIT_COMPARE_OUT:-$root/out/texture-compare}
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
mkdir -p "$out"
if (($# == 0)); then
  "$root/scripts/fetch-textures.sh"
  cache=${TILEKIT_TEXTURES:-${XDG_CACHE_HOME:-$HOME/.cache}/tilekit/textures}
  set -- "$cache"/*.png
fi
# The value of "key" in a one-line JSON object (numbers and strings).
field() { sed -n "s/.*\"$1\":\"\\{0,1\\}\\([^,\"}]*\\).*/\\1/p" <<<"$2"; }
analyze=0
"$tk" texture --help 2>/dev/null | grep -q "^  analyze" && analyze=1
: >"$out/results.jsonl"
table="| texture | method | fetches/pixel | GLSL M fragments/s | memory MiB | analyze |\n|---|---|---|---|---|---|\n"
for ex in "$@"; do
  name=$(basename "${ex%.*}")
  dir="$out/$name"
  mkdir -p "$dir"
  echo "texture-compare: $name" >&2
  for bands in tiles tiles-thin; do
    thin=(--wide-bands)
    [ "$bands" = tiles-thin ] && thin=(--thin-bands)
    "$tk" texture tiles --exemplar "$ex" --kind corner --colors 4 --tile-px 64 --seed 1 "${thin[@]}" \
      --out "$dir/$bands" --quiet >/dev/null
    "$tk" texture atlas "$dir/$bands" --out "$dir/atlas-$bands.png" --no-db >/dev/null
    mkdir -p "$dir/labels-$bands"
    "$tk" texture atlas "$dir/$bands/labels" --out "$dir/labels-$bands/atlas.png" --no-db >/dev/null
    "$tk" texture render --atlas "$dir/labels-$bands/atlas.png" --seed 1 --quiet --size 1024x1024 --scale 1 \
      --out "$dir/flat-labels-$bands.png" >/dev/null
  done
  for m in tiles tiles-thin hex hpn; do
    method=${m%-thin}
    atlas="$dir/atlas-tiles.png"
    [ "$m" = tiles-thin ] && atlas="$dir/atlas-tiles-thin.png"
    src=(--method "$method" --atlas "$atlas" --exemplar "$ex" --seed 1 --quiet)
    "$tk" texture render "${src[@]}" --size 1024x1024 --scale 1 --out "$dir/flat-$m.png" >/dev/null
    "$tk" texture render "${src[@]}" --size 1024x576 --scale 1 --tilt 3 --out "$dir/tilted-$m.png" >/dev/null
    j=$("$tk" texture render "${src[@]}" --size 1024x1024 --scale 1 --glsl --frames 10 --json --out "$dir/glsl-$m.png" ||
      echo '{}')
    fetches=$(field fetches_per_pixel "$j")
    speed=$(field glsl_mfragments_per_second "$j")
    memory=$(field memory_bytes "$j")
    a='null'
    if ((analyze)); then
      # hex and hpn: their triangle grid of side S = cell_px, basis (S,0) and (S/2, S sqrt(3)/2)
      # (render/baseline_samplers.hpp's skew, inverted), a vertex at the origin.
      lattice=(--tile-px 64 --labels "$dir/flat-labels-$m.png")
      if [ "$method" != tiles ]; then
        s=$(field cell_px "$j")
        lattice=(--lattice "$(awk -v s="$s" 'BEGIN { printf "%g,0,%g,%g", s, s / 2, s * sqrt(3) / 2 }')")
      fi
      a=$("$tk" texture analyze "$dir/flat-$m.png" "${lattice[@]}" --exemplar "$ex" --json 2>/dev/null || echo null)
    fi
    echo "{\"texture\":\"$name\",\"method\":\"$m\",\"fetches_per_pixel\":${fetches:-null},\"glsl_mfragments_per_second\":${speed:-null},\"memory_bytes\":${memory:-null},\"analyze\":$a}" >>"$out/results.jsonl"
    mib=$(awk -v b="${memory:-0}" 'BEGIN { printf "%.2f", b / 1048576 }')
    table+="| $name | $m | ${fetches:-?} | ${speed:-?} | $mib | $( ((analyze)) && echo yes || echo "not built") |\n"
  done
done
printf "%b" "$table" | tee "$out/table.md"
echo "texture-compare: pictures in $out/*/{flat,tilted}-{tiles,tiles-thin,hex,hpn}.png, results in $out/results.jsonl" >&2
