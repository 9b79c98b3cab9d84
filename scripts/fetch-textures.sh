#!/usr/bin/env bash
# Fetches the real textures Tilekit's texture tests, benchmarks and main job use, into a cache
# (never into git): the CC0 textures brick.png, grass.png and gravel.png (512x512 grey, from
# CC0Textures via scikit-image) out of the Debian package python3-skimage, by `apt-get download`
# and `dpkg -x` (no Python needed). Idempotent: does nothing when they are there.
#   TILEKIT_TEXTURES  the cache folder (default: ${XDG_CACHE_HOME:-$HOME/.cache}/tilekit/textures)
set -euo pipefail
dest=${TILEKIT_TEXTURES:-${XDG_CACHE_HOME:-$HOME/.cache}/tilekit/textures}
names=(brick grass gravel)
have=1
for n in "${names[@]}"; do [ -s "$dest/$n.png" ] || have=0; done
if [ "$have" = 1 ]; then
  echo "fetch-textures: ${names[*]} already in $dest" >&2
  exit 0
fi
mkdir -p "$dest"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# apt-get download drops privileges to _apt where it can; a folder _apt may write to avoids the warning.
chmod 777 "$work"
if ! apt-get download python3-skimage >/dev/null 2>&1; then
  apt-get update -q >/dev/null 2>&1 || true
  apt-get download python3-skimage >/dev/null
fi
dpkg -x python3-skimage_*.deb x
src=x/usr/lib/python3/dist-packages/skimage/data
for n in "${names[@]}"; do
  [ -s "$src/$n.png" ] || { echo "fetch-textures: $n.png is not in python3-skimage" >&2; exit 1; }
  cp "$src/$n.png" "$dest/$n.png.tmp" && mv "$dest/$n.png.tmp" "$dest/$n.png"
done
cat >"$dest/SOURCE.txt" <<TXT
brick.png, grass.png, gravel.png: scikit-image data (Debian package python3-skimage,
$(dpkg-deb -f python3-skimage_*.deb Version)): brick from CC0Textures Bricks25, grass from DeviantArt
linolafett "Grass 01", gravel from CC0Textures Gravel04;
licensed CC0 (public domain); see skimage/data/_fetchers.py in the package.
TXT
echo "fetch-textures: ${names[*]} -> $dest" >&2
