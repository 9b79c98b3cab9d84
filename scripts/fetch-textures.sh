#!/usr/bin/env bash
# Fetches the real textures Tilekit's texture tests, benchmarks and main job use, into a cache
# (never into git), out of Debian packages by `apt-get download` and `dpkg -x` (no Python):
#   brick.png grass.png gravel.png   512x512 grey, CC0 (CC0Textures via scikit-image): python3-skimage
#   gimp-stone33.ppm gimp-walnut.ppm GIMP's tileable patterns (GPL): gimp-data; the .pat files are
#                                    a header and raw RGB, rewritten as binary PPM
#   oa-dirt.tga oa-brick.tga oa-rock.jpg  OpenArena's tileable textures (GPL-2+): openarena-081-textures
#                                    (a pk3, which is a zip: needs unzip)
# Idempotent: does nothing when they are there. apt-get runs under flock /tmp/tilekit-apt.lock,
# since other builds on the machine may install at the same time.
#   TILEKIT_TEXTURES  the cache folder (default: ${XDG_CACHE_HOME:-$HOME/.cache}/tilekit/textures)
set -euo pipefail
dest=${TILEKIT_TEXTURES:-${XDG_CACHE_HOME:-$HOME/.cache}/tilekit/textures}
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
