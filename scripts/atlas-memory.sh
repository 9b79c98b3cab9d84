#!/usr/bin/env bash
# Texture memory per method and atlas size for C = 2..8: the atlas of the complete corner and
# Wang sets (rows x cols from `tilekit atlas lookup --json`: the packing texture atlas uses) of
# T-pixel tiles with its full mip chain (RGBA8), as laid out and resampled to the nearest power of
# two per axis (`texture atlas --power-of-two`: texture/texture_atlas.hpp), beside hex and hpn on
# an S x S exemplar (`texture render --json`'s memory_bytes: hex's mip chain; hpn's Gaussianized
# chain in half floats and its look-up table).
# Usage: scripts/atlas-memory.sh [T] [S]   (default 128 1024; prints a Markdown table)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"
T=${1:-128}
S=${2:-1024}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
field() { sed -n "s/.*\"$1\":\"\\{0,1\\}\\([^,\"}]*\\).*/\\1/p" <<<"$2"; }
# The bytes of a W x H RGBA8 mip chain down to 1x1 (each level max(1, half)).
chain() { awk -v w="$1" -v h="$2" 'BEGIN { s = 0; while (1) { s += w * h * 4; if (w == 1 && h == 1) break; w = (w > 1) ? int(w / 2) : 1; h = (h > 1) ? int(h / 2) : 1 } print s }'; }
# 2^round(log2 n) as texture_atlas.cpp's nearest_power_of_two: up when n >= 2^k sqrt 2.
pow2() { awk -v n="$1" 'BEGIN { k = 1; while (k * 2 <= n) k *= 2; print (n * n >= 2 * k * k) ? 2 * k : k }'; }
mib() { awk -v b="$1" 'BEGIN { printf "%.2f", b / 1048576 }'; }
# An S x S exemplar (only its size matters here).
python3 - "$tmp/ex.png" "$S" <<'PY'
import struct, sys, zlib
path, n = sys.argv[1], int(sys.argv[2])
raw = b''.join(b'\0' + bytes((x * 7 + y * 13) & 255 for x in range(n) for _ in range(3)) for y in range(n))
chunk = lambda t, d: struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
open(path, 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', n, n, 8, 2, 0, 0, 0)) + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))
PY
hex=$(field memory_bytes "$("$tk" texture render --method hex --exemplar "$tmp/ex.png" --size 8x8 --quiet --json --out "$tmp/h.png")")
hpn=$(field memory_bytes "$("$tk" texture render --method hpn --exemplar "$tmp/ex.png" --size 8x8 --quiet --json --out "$tmp/h.png")")
echo "| C | kind | tiles | atlas (${T} px tiles) | MiB | power of two | MiB | texels a tile |"
echo "|---|---|---|---|---|---|---|---|"
for c in 2 3 4 5 6 7 8; do
  for kind in corner wang; do
    j=$("$tk" atlas lookup --kind "$kind" --colors "$c" --json)
    rows=$(field rows "$j")
    cols=$(field cols "$j")
    w=$((cols * T)) h=$((rows * T))
    pw=$(pow2 "$w") ph=$(pow2 "$h")
    texels=$(awk -v p="$pw" -v c="$cols" 'BEGIN { printf "%.2f", p / c }')
    echo "| $c | $kind | $((rows * cols)) | ${w}x$h | $(mib "$(chain "$w" "$h")") | ${pw}x$ph | $(mib "$(chain "$pw" "$ph")") | $texels |"
  done
done
echo
echo "hex on a ${S}x$S exemplar: $(mib "$hex") MiB; hpn: $(mib "$hpn") MiB"
