#!/usr/bin/env bash
# The hardware anisotropic filter against the 16-tap path and hex tiling, in one run: the main
# job's tilted view (1024x576, scale 1, tilt 3) of grass, corner tiles C = 4 of 64 px, 16x
# anisotropy (and, as taps1 and hardware1, trilinear: one tap, an isotropic textureGrad), drawn by `texture render --glsl --frames N` on llvmpipe (LP_NUM_THREADS=2). Prints
# per method the texture fetches per pixel and the GLSL M fragments/s of each of R rounds and
# their median (the methods alternate within a round, so that the machine's load falls on all).
# Usage: scripts/texture-filter-bench.sh [EXEMPLAR] [ROUNDS] [FRAMES]   (default grass 3 5)
#   TILEKIT_BENCH_OUT  output folder (default: out/texture-filter-bench in the repository)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"
ex=${1:-grass}
rounds=${2:-3}
frames=${3:-5}
out=${TILEKIT_BENCH_OUT:-$root/out/texture-filter-bench}
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
mkdir -p "$out"
field() { sed -n "s/.*\"$1\":\"\\{0,1\\}\\([^,\"}]*\\).*/\\1/p" <<<"$2"; }
[ -f "$out/atlas.json" ] || {
  "$tk" texture tiles --exemplar "$ex" --kind corner --colors 4 --tile-px 64 --seed 1 --wide-bands --out "$out/tiles" --quiet >/dev/null
  "$tk" texture atlas "$out/tiles" --out "$out/atlas.png" --no-db >/dev/null
}
view=(--size 1024x576 --scale 1 --tilt 3 --seed 1 --quiet --glsl --frames "$frames" --json)
methods=(taps hardware hex taps1 hardware1)
declare -A rates fetches
for ((r = 1; r <= rounds; ++r)); do
  for m in "${methods[@]}"; do
    case $m in
      taps) src=(--method tiles --atlas "$out/atlas.png" --filter taps --aniso 16) ;;
      hardware) src=(--method tiles --atlas "$out/atlas.png" --filter hardware --aniso 16) ;;
      hex) src=(--method hex --exemplar "$ex" --aniso 16) ;;
      taps1) src=(--method tiles --atlas "$out/atlas.png" --filter taps --aniso 1) ;;
      hardware1) src=(--method tiles --atlas "$out/atlas.png" --filter hardware --aniso 1) ;;
    esac
    j=$("$tk" texture render "${src[@]}" "${view[@]}" --out "$out/$m.png")
    rates[$m]+="$(field glsl_mfragments_per_second "$j") "
    fetches[$m]=$(field fetches_per_pixel "$j")
  done
done
echo "| method | fetches/pixel | GLSL M fragments/s per round | median |"
echo "|---|---|---|---|"
for m in "${methods[@]}"; do
  median=$(tr ' ' '\n' <<<"${rates[$m]}" | sed '/^$/d' | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}')
  printf '| %s | %.2f | %s| %.2f |\n' "$m" "${fetches[$m]}" "${rates[$m]}" "$median"
done
