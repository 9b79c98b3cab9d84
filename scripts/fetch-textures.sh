#!/usr/bin/env bash
# Fetches the real textures Tilekit's texture tests, benchmarks and main job use, into a cache
# (never into git), out of Debian packages by `apt-get download` and `dpkg -x` (no Python):
#   brick.png grass.png gravel.png   512x512 grey, CC0 (CC0Textures via scikit-image): python3-skimage
#   gimp-stone33.ppm gimp-walnut.ppm GIMP's tileable patterns (GPL): gimp-data; the .pat files are
#                                    a header and raw RGB, rewritten as binary PPM
#   oa-dirt.tga oa-brick.tga oa-rock.jpg  OpenArena's tileable textures (GPL-2+): openarena-081-textures
#                                    (a pk3, which is a zip: needs unzip)
# With --held-out, also (only) the held-out textures: material sets no tuning decision looks at,
# from UFO: Alien Invasion (GPL-2+ and others, see its copyright; Debian package ufoai-textures,
# 336 MB), each with its colour map NAME.png and tangent-space normals NAME.normal.png, some with
# specular NAME.spec.png:
#   ufo-brick ufo-tile ufo-wood   brick, floor tiles and planks (structured)
#   ufo-concrete ufo-dirt ufo-mud  concrete, dirt and dry mud (irregular)
# and the material set of Red Eclipse's trak4 textures (Georges 'TRaK' Grondin, CC-BY-3.0; Debian
# package redeclipse-data, 862 MB): every trak4 surface with a colour map and normals (_nm) of
# its size, less the decals (door, grates, trim) and concrete3 (ufo-concrete is a copy), each as
# re-NAME.jpg, re-NAME.normal.png and re-NAME.spec.jpg (_s). Where a surface has lettered colour
# variants (brick2a, paint_blue, ...), the first.
# Idempotent: does nothing when they are there. apt-get runs under flock /tmp/tilekit-apt.lock,
# since other builds on the machine may install at the same time.
#   TILEKIT_TEXTURES  the cache folder (default: ${XDG_CACHE_HOME:-$HOME/.cache}/tilekit/textures)
set -euo pipefail
dest=${TILEKIT_TEXTURES:-${XDG_CACHE_HOME:-$HOME/.cache}/tilekit/textures}
if [ "${1:-}" = --held-out ]; then
  held=(ufo-brick ufo-tile ufo-wood ufo-concrete ufo-dirt ufo-mud)
  re=(brick1 brick2 concrete1 concrete2a concrete4 concrete5 concrete6 paint painted2 plaster1 plaster3
      rust1 rust2 tile1 tile2 tile3 wood1)
  for r in "${re[@]}"; do held+=("re-$r"); done
  missing=0
  for f in "${held[@]}"; do [ -s "$dest/$f.normal.png" ] || missing=1; done
  if [ "$missing" = 0 ]; then
    echo "fetch-textures: the held-out textures (${held[*]}) already in $dest" >&2
    exit 0
  fi
  mkdir -p "$dest"
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  cd "$work"
  chmod 777 "$work"
  flock /tmp/tilekit-apt.lock apt-get download ufoai-textures >/dev/null 2>&1 ||
    { flock /tmp/tilekit-apt.lock apt-get update -q >/dev/null 2>&1 || true; flock /tmp/tilekit-apt.lock apt-get download ufoai-textures >/dev/null; }
  dpkg -x ufoai-textures_*.deb ufo
  pk3=ufo/usr/share/games/ufoai/base/0textures.pk3
  # NAME, the texture in the pk3 (colour map; _nm and _sm beside it), its extension
  while read -r name inner ext; do
    unzip -p "$pk3" "textures/$inner.$ext" >colour.bin
    unzip -p "$pk3" "textures/${inner}_nm.png" >normal.png
    [ -s colour.bin ] && [ -s normal.png ] || { echo "fetch-textures: $inner is not in $pk3" >&2; exit 1; }
    cp colour.bin "$dest/$name.$ext.tmp" && mv "$dest/$name.$ext.tmp" "$dest/$name.$ext"
    cp normal.png "$dest/$name.normal.png.tmp" && mv "$dest/$name.normal.png.tmp" "$dest/$name.normal.png"
    if unzip -p "$pk3" "textures/${inner}_sm.png" >spec.png 2>/dev/null && [ -s spec.png ]; then
      cp spec.png "$dest/$name.spec.png.tmp" && mv "$dest/$name.spec.png.tmp" "$dest/$name.spec.png"
    fi
  done <<'LIST'
ufo-brick tex_buildings/wall_brick01 png
ufo-tile tex_buildings/tile01 png
ufo-wood tex_buildings/floor_wood01 png
ufo-concrete tex_trak/trak4_concrete3 png
ufo-dirt tex_nature/dirt_se05 png
ufo-mud tex_nature/drymud jpg
LIST
  flock /tmp/tilekit-apt.lock apt-get download redeclipse-data >/dev/null 2>&1 ||
    { flock /tmp/tilekit-apt.lock apt-get update -q >/dev/null 2>&1 || true; flock /tmp/tilekit-apt.lock apt-get download redeclipse-data >/dev/null; }
  dpkg-deb --fsys-tarfile redeclipse-data_*.deb | tar -x --wildcards './usr/share/games/redeclipse/data/trak/trak4/*'
  t4=usr/share/games/redeclipse/data/trak/trak4
  # NAME (re-NAME in the cache, the normals' and specular map's stem), its colour map
  while read -r r colour; do
    [ -s "$t4/$colour.jpg" ] && [ -s "$t4/${r}_nm.png" ] || { echo "fetch-textures: trak4 $r is not in redeclipse-data" >&2; exit 1; }
    cp "$t4/$colour.jpg" "$dest/re-$r.jpg.tmp" && mv "$dest/re-$r.jpg.tmp" "$dest/re-$r.jpg"
    cp "$t4/${r}_nm.png" "$dest/re-$r.normal.png.tmp" && mv "$dest/re-$r.normal.png.tmp" "$dest/re-$r.normal.png"
    if [ -s "$t4/${r}_s.jpg" ]; then
      cp "$t4/${r}_s.jpg" "$dest/re-$r.spec.jpg.tmp" && mv "$dest/re-$r.spec.jpg.tmp" "$dest/re-$r.spec.jpg"
    fi
  done <<'LIST'
brick1 brick1
brick2 brick2
concrete1 concrete1a
concrete2a concrete2a
concrete4 concrete4a
concrete5 concrete5a
concrete6 concrete6
paint paint_blue
painted2 painted2
plaster1 plaster1
plaster3 plaster3
rust1 rust1
rust2 rust2
tile1 tile1
tile2 tile2a
tile3 tile3a
wood1 wood1c
LIST
  cat >"$dest/SOURCE-held-out.txt" <<TXT
ufo-*.png/jpg (colour), ufo-*.normal.png (tangent-space normals, _nm), ufo-*.spec.png (specular, _sm):
UFO: Alien Invasion's textures tex_buildings/wall_brick01, tex_buildings/tile01,
tex_buildings/floor_wood01, tex_trak/trak4_concrete3, tex_nature/dirt_se05, tex_nature/drymud
(Debian package ufoai-textures, $(dpkg-deb -f ufoai-textures_*.deb Version), 0textures.pk3); see
/usr/share/doc/ufoai-textures/copyright in the package for each file's licence. Held out: no
tuning decision of Tilekit looks at them.
re-*.jpg (colour), re-*.normal.png (_nm), re-*.spec.jpg (_s): Red Eclipse's data/trak/trak4
textures by Georges 'TRaK' Grondin, CC-BY-3.0 (Debian package redeclipse-data,
$(dpkg-deb -f redeclipse-data_*.deb Version)): ${re[*]}. Held out as well.
TXT
  echo "fetch-textures: ${held[*]} -> $dest" >&2
  exit 0
fi
files=(brick.png grass.png gravel.png gimp-stone33.ppm gimp-walnut.ppm oa-dirt.tga oa-brick.tga oa-rock.jpg)
missing=0
for f in "${files[@]}"; do [ -s "$dest/$f" ] || missing=1; done
if [ "$missing" = 0 ]; then
  echo "fetch-textures: ${files[*]} already in $dest" >&2
  exit 0
fi
mkdir -p "$dest"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# apt-get download drops privileges to _apt where it can; a folder _apt may write to avoids the warning.
chmod 777 "$work"
download() {
  flock /tmp/tilekit-apt.lock apt-get download "$1" >/dev/null 2>&1 && return
  flock /tmp/tilekit-apt.lock apt-get update -q >/dev/null 2>&1 || true
  flock /tmp/tilekit-apt.lock apt-get download "$1" >/dev/null
}
put() {  # put SRC NAME: into the cache atomically
  cp "$1" "$dest/$2.tmp" && mv "$dest/$2.tmp" "$dest/$2"
}

# scikit-image
download python3-skimage
dpkg -x python3-skimage_*.deb skimage
for n in brick grass gravel; do
  src=skimage/usr/lib/python3/dist-packages/skimage/data/$n.png
  [ -s "$src" ] || { echo "fetch-textures: $n.png is not in python3-skimage" >&2; exit 1; }
  put "$src" "$n.png"
done

# GIMP patterns: big-endian u32 header size, version, width, height, bytes per pixel; "GPAT";
# the name; then width x height pixels.
download gimp-data
dpkg -x gimp-data_*.deb gimp
pat_to_ppm() {  # pat_to_ppm PAT OUT
  local h
  read -r -a h <<<"$(od -An -tu1 -N20 "$1" | tr -s ' \n' ' ')"
  be32() { echo $((h[$1] * 16777216 + h[$1 + 1] * 65536 + h[$1 + 2] * 256 + h[$1 + 3])); }
  local size width height bytes
  size=$(be32 0) width=$(be32 8) height=$(be32 12) bytes=$(be32 16)
  [ "$bytes" = 3 ] || { echo "fetch-textures: $1 has $bytes bytes per pixel, not RGB" >&2; exit 1; }
  { printf 'P6\n%d %d\n255\n' "$width" "$height"; tail -c +$((size + 1)) "$1"; } >"$2"
}
for p in Stone/stone33 Wood/walnut; do
  pat_to_ppm "gimp/usr/share/gimp/2.0/patterns/$p.pat" pattern.ppm
  put pattern.ppm "gimp-$(basename "$p").ppm"
done

# OpenArena textures
download openarena-081-textures
dpkg -x openarena-081-textures_*.deb oa
pk3=oa/usr/share/games/openarena/baseoa/pak4-textures.pk3
while read -r inner name; do
  unzip -p "$pk3" "$inner" >texture.bin
  [ -s texture.bin ] || { echo "fetch-textures: $inner is not in $pk3" >&2; exit 1; }
  put texture.bin "$name"
done <<'LIST'
textures/organics/dirt.tga oa-dirt.tga
textures/gothic_wall/proto_brik.tga oa-brick.tga
textures/stone/pjrock16.jpg oa-rock.jpg
LIST

cat >"$dest/SOURCE.txt" <<TXT
brick.png, grass.png, gravel.png: scikit-image data (Debian package python3-skimage,
$(dpkg-deb -f python3-skimage_*.deb Version)): brick from CC0Textures Bricks25, grass from DeviantArt
linolafett "Grass 01", gravel from CC0Textures Gravel04; licensed CC0 (public domain); see
skimage/data/_fetchers.py in the package.
gimp-stone33.ppm, gimp-walnut.ppm: GIMP's patterns Stone/stone33.pat and Wood/walnut.pat (Debian
package gimp-data, $(dpkg-deb -f gimp-data_*.deb Version)), rewritten as PPM; GPL, see
/usr/share/doc/gimp-data/copyright in the package.
oa-dirt.tga, oa-brick.tga, oa-rock.jpg: OpenArena's textures/organics/dirt.tga,
textures/gothic_wall/proto_brik.tga and textures/stone/pjrock16.jpg (Debian package
openarena-081-textures, $(dpkg-deb -f openarena-081-textures_*.deb Version), pak4-textures.pk3);
GPL-2+, see /usr/share/doc/openarena-081-textures/copyright in the package.
TXT
echo "fetch-textures: ${files[*]} -> $dest" >&2
