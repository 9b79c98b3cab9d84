#!/usr/bin/env bash
# Runs the harnesses of fuzz/ (one per parser of outside input) on seed corpora made from
# Tilekit's own outputs (build/tilekit), SECONDS each (default 10), FUZZ_JOBS (default: the number
# of cores) at a time. Prints one line per harness (runs, seconds, runs/s, corpus) and fails if any
# harness found a crash, hang or sanitizer report (the input is kept in CRASHES/NAME/; turn it into
# a regression test). Two engines:
#   scripts/fuzz.sh [SECONDS] [HARNESS...]
#       libFuzzer: clang, -fsanitize=fuzzer,address,undefined, in build-fuzz/ (every library rebuilt
#       instrumented); coverage-guided, with leaks and memory errors reported. Corpora grow in
#       build-fuzz/corpus/NAME/ from run to run; crashes in build-fuzz/crashes/NAME/.
#   scripts/fuzz.sh --driver [SECONDS] [HARNESS...]
#       fuzz_driver (fuzz/driver.cpp) of the Release build (build/, g++, asserts on): every seed,
#       then mutants of them (a plain mutation loop, seeded by FUZZ_SEED, default 1, so a run is
#       repeatable; no coverage guidance, no sanitizer); crashes, failed asserts and property checks,
#       hangs and runaway memory fail it. Fresh corpora in build/fuzz-driver/corpus/NAME/ each run;
#       crashes in build/fuzz-driver/crashes/NAME/. What scripts/test.sh runs.
#   FUZZ_RUNS=1000000 scripts/fuzz.sh 0   each harness for exactly that many executions (SECONDS 0:
#                                         no time bound), the 10^6-execution figures in docs/TESTING.md
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
engine=libfuzzer
if [ "${1:-}" = --driver ]; then
  engine=driver
  shift
fi
seconds=${1:-10}
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(tile_set tiling checkpoint db_export group_spec portfolio_stats probability_map flags
  results_db texture_input point_tiles specs decide_checkpoint smallest_record tiled_map)
jobs=${FUZZ_JOBS:-$(nproc)}
"$root/scripts/setup.sh"
[ -x "$root/build/tilekit" ] || "$root/scripts/build.sh"
if [ "$engine" = driver ]; then
  [ -x "$root/build/fuzz_driver" ] || cmake --build "$root/build" -j "$(nproc)" --target fuzz_driver
  fz=$root/build/fuzz-driver
  rm -rf "$fz/corpus"  # fresh seeds each run: the driver adds nothing to its corpus
  run_harness() { "$root/build/fuzz_driver" "$1" -seed="${FUZZ_SEED:-1}" "${@:2}"; }
else
  fz=$root/build-fuzz
  gen=()
  [ -f "$fz/CMakeCache.txt" ] || ! command -v ninja >/dev/null || gen=(-G Ninja)
  cmake -S "$root" -B "$fz" "${gen[@]}" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g -fdebug-prefix-map=$root=." -DTILEKIT_FUZZ=ON -DTILEKIT_TESTS=OFF -DTILEKIT_BENCH=OFF >/dev/null
  targets=()
  for h in "${harnesses[@]}"; do targets+=(--target "fuzz_$h"); done
  cmake --build "$fz" -j "$(nproc)" "${targets[@]}"
  run_harness() { "$fz/fuzz_$1" -print_final_stats=1 "${@:2}"; }
fi

# ---- seed corpora: the project's own outputs, made fresh (never stored in git) ----
tk=$root/build/tilekit
seeds=$(mktemp -d)
trap 'rm -rf "$seeds"' EXIT
db=$seeds/r.sqlite
seed() {  # seed NAME FILE: copy FILE into NAME's corpus
  mkdir -p "$fz/corpus/$1"
  cp "$2" "$fz/corpus/$1/seed-$(basename "$2")"
}
make_seeds() {
  local s=$seeds
  for f in "$root"/tilesets/data/*.tiles; do seed tile_set "$f"; done
  for set in culik-13 complete-corner-2 compact-wang-2 complete-wang-2x3; do
    "$tk" tileset show "$set" --json >"$s/$set.json" && seed tile_set "$s/$set.json"
  done
  "$tk" aperiodic convert culik-13 --method diagonal --out "$s/diag.tiles" >/dev/null && seed tile_set "$s/diag.tiles"
  "$tk" tile --set complete-corner-2 --algo direct --size 5x4 --out "$s/tile.json" >/dev/null && seed tiling "$s/tile.json"
  "$tk" tile --set complete-wang-2x3 --algo scanline --size 3x3 --out "$s/wang.json" >/dev/null && seed tiling "$s/wang.json"
  seed tiling "$root/tilesets/data/packing-corner-2.json"
  "$tk" pack --kind corner --colors 2 --mode all --quiet --db "$db" >/dev/null
  "$tk" pack --kind wang --colors 2 --method construct --quiet --db "$db" --out "$s/pack.json" >/dev/null &&
    seed tiling "$s/pack.json"
  "$tk" aperiodic verify kari-14 --max-period 2 --db "$db" >/dev/null 2>&1 || true
  "$tk" db export --db "$db" --out "$s/export.json" >/dev/null && seed db_export "$s/export.json"
  "$tk" pack --kind corner --colors 4 --method search --threads 1 --quiet --json --portfolio-stats "$s/stats.json" \
    --db "$db" >"$s/portfolio.json"
  seed portfolio_stats "$s/stats.json"
  python3 -c 'import json,sys; print((json.load(open(sys.argv[1])).get("group") or {}).get("spec", ""), end="")' "$s/portfolio.json" \
    >"$s/group-found" && seed group_spec "$s/group-found"
  # group specs and flags as the README documents them
  local i=0
  for g in 't=0,4:pi=1,2,3,0' 't=0,8:pi=1,0,3,2' 't=0,2:pi=(0 1)' 't=0,4:pih=1,0;t=4,0:piv=1,0' 't=0,4:pi=(0 1 2 3)'; do
    printf '%s' "$g" >"$s/group-$i" && seed group_spec "$s/group-$i"
    i=$((i + 1))
  done
  for v in 16x16 64x48 3/64 0/1 4096 4294967296/1; do
    printf '%s' "$v" >"$s/flag-${v//\//_}" && seed flags "$s/flag-${v//\//_}"
  done
  printf '{"colors":2,"rows":1,"cols":2,"p":[[[1,0],[0.25,0.75]]]}' >"$s/map.json" && seed probability_map "$s/map.json"
  printf '{"colors":3,"rows":2,"cols":1,"p":[[[0.5,0.5,0]],[[0,0,1]]]}' >"$s/map3.json" && seed probability_map "$s/map3.json"
  # checkpoints: an interrupted count (subproblems in flight) and a restart search; the
  # harness reads byte 0 as the mode (odd: whole file; even: body under a valid header)
  "$tk" pack --kind wang --colors 2 --mode count --threads 2 --quiet --checkpoint "$s/count.ckpt" \
    --time-limit 0.05 --db "$db" >/dev/null || true
  "$tk" pack --kind corner --colors 3 --method search --plain --quiet --checkpoint "$s/restart.ckpt" \
    --time-limit 0.05 --db "$db" >/dev/null || true
  "$tk" pack --kind corner --colors 4 --method search --quiet --checkpoint "$s/portfolio.ckpt" --portfolio-stats "$s/stats2.json" \
    --time-limit 0.05 --db "$db" >/dev/null || true
  for c in "$s"/*.ckpt; do
    [ -f "$c" ] || continue
    { printf '\001'; cat "$c"; } >"$c.whole" && seed checkpoint "$c.whole"
    { printf '\000'; tail -n +3 "$c"; } >"$c.body" && seed checkpoint "$c.body"
  done
  # results database edit programs (fuzz_results_db.cpp reads bytes as choices)
  for p in '' '\000\000\000' '\004\001\007' '\007\001\003\001\002' '\005\002\001' '\010\001\001\002\003\004\005\006'; do
    i=$((${i:-0} + 1))
    printf "$p" >"$s/edits-$i" && seed results_db "$s/edits-$i"
  done
  # texture inputs: a PNG, image headers that claim 23000 x 23000 pixels, an atlas manifest of a
  # two-colour atlas with 16-pixel tiles, and the tiles.json beside its tiles
  "$tk" texture tiles --exemplar brick --colors 2 --tile-px 16 --search 0 \
    --quiet --out "$s/ttiles" >/dev/null
  mkdir -p "$s/atlas"
  "$tk" texture atlas "$s/ttiles" --out "$s/atlas/atlas.png" --no-db --quiet >/dev/null
  { printf '\000'; cat "$s/ttiles/tile-0000.png"; } >"$s/img.png" && seed texture_input "$s/img.png"
  python3 - "$s" <<'PY'
import struct, sys, zlib
def chunk(t, d): return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 23000, 23000, 8, 2, 0, 0, 0)) + \
      chunk(b"IDAT", zlib.compress(b"\0" * 64)) + chunk(b"IEND", b"")
open(sys.argv[1] + "/bomb.png", "wb").write(b"\0" + png)
open(sys.argv[1] + "/bomb.ppm", "wb").write(b"\0P6\n23000 23000\n255\n" + b"\0" * 64)
def tiff(w, h, bps, fmt, data):  # a grey TIFF, one uncompressed strip (image/tiff.cpp reads it as stored)
    tags = [(256, 3, w), (257, 3, h), (258, 3, bps), (259, 3, 1), (262, 3, 1), (273, 4, 8 + 2 + 12 * 10 + 4),
            (277, 3, 1), (278, 3, h), (279, 4, len(data)), (339, 3, fmt)]
    ifd = struct.pack("<H", len(tags)) + b"".join(
        struct.pack("<HHI", t, k, 1) + (struct.pack("<HH", v, 0) if k == 3 else struct.pack("<I", v)) for t, k, v in tags)
    return b"II*\0" + struct.pack("<I", 8) + ifd + struct.pack("<I", 0) + data
open(sys.argv[1] + "/ramp16.tif", "wb").write(b"\0" + tiff(4, 4, 16, 1, b"".join(struct.pack("<H", 4000 * i) for i in range(16))))
open(sys.argv[1] + "/float.tif", "wb").write(tiff(8, 8, 32, 3, b"".join(struct.pack("<f", i * 0.5 - 3.5) for i in range(64))))
open(sys.argv[1] + "/bomb.tif", "wb").write(b"\0" + tiff(23000, 23000, 8, 1, b"\0" * 64))
PY
  seed texture_input "$s/bomb.png" && seed texture_input "$s/bomb.ppm"
  # TIFF and OpenEXR: a 16-bit TIFF, a TIFF that claims 23000 x 23000 pixels, and the OpenEXR tile
  # that `texture tiles` writes for a float map (here a float TIFF)
  seed texture_input "$s/ramp16.tif" && seed texture_input "$s/bomb.tif"
  "$tk" texture tiles --exemplar brick --colors 1 --tile-px 16 --search 0 --map "d=$s/float.tif" \
    --quiet --out "$s/ftiles" >/dev/null
  { printf '\000'; cat "$s/ftiles/maps/d/tile-0000.exr"; } >"$s/img.exr" && seed texture_input "$s/img.exr"
  { printf '\001'; cat "$s/atlas/atlas.json"; } >"$s/atlas.seed" && seed texture_input "$s/atlas.seed"
  { printf '\002'; cat "$s/ttiles/tiles.json"; } >"$s/tiles.seed" && seed texture_input "$s/tiles.seed"
  # point tile files, whole (byte 0: 0 .ptiles, 1 .rtiles) and without their checksum line (2, 3)
  "$tk" points tiles --colors 1 --points 8 --rho 0.5 --no-db --quiet --out "$s/t.ptiles" >/dev/null
  "$tk" points recursive --points 8 --no-db --quiet --out "$s/t.rtiles" >/dev/null
  { printf '\000'; cat "$s/t.ptiles"; } >"$s/p0" && seed point_tiles "$s/p0"
  { printf '\001'; cat "$s/t.rtiles"; } >"$s/p1" && seed point_tiles "$s/p1"
  { printf '\002'; head -n -1 "$s/t.ptiles"; } >"$s/p2" && seed point_tiles "$s/p2"
  { printf '\003'; head -n -1 "$s/t.rtiles"; } >"$s/p3" && seed point_tiles "$s/p3"
  # the small languages: density expressions, objects, windows, lifts, method and hash names
  i=0
  for v in '\000500 * x' '\0001000 * (exp(-20 * ((x-0.5)^2 + (y-0.5)^2)) + 0.05)' '\000clamp(sin(pi*x), 0, r)' \
    '\001tree:1,rock:3' '\0020,0,100,100' '\002-1.5e3,2,4e-1,1e2' '\0034' '\003m=4,base=b.json' '\004dual' '\005perm'; do
    printf "$v" >"$s/spec-$i" && seed specs "$s/spec-$i"
    i=$((i + 1))
  done
  # verify checkpoints of kari-14 (undecided at k = 2): whole (odd byte 0) and body (even)
  "$tk" aperiodic verify kari-14 --route transducer --max-k 2 --checkpoint "$s/d.ckpt" --quiet >/dev/null 2>&1 || true
  if [ -f "$s/d.ckpt" ]; then
    { printf '\001'; cat "$s/d.ckpt"; } >"$s/d.whole" && seed decide_checkpoint "$s/d.whole"
    { printf '\000'; tail -n +3 "$s/d.ckpt"; } >"$s/d.body" && seed decide_checkpoint "$s/d.body"
  fi
  # chain records: the embedded one
  seed smallest_record "$root/aperiodic/data/smallest-chain.json"
  # maps painted in Tiled: a filled corner map, and the same in Tiled's XML layer format
  "$tk" fill --set complete-corner-2 --size 5x4 --seed 3 --tiled "$s/tmx" --quiet >/dev/null && seed tiled_map "$s/tmx/corner-2-fill.tmx"
  printf '<map orientation="orthogonal" width="2" height="1" tilewidth="8" tileheight="8">\n <tileset firstgid="1" source="t.tsx"/>\n <layer name="a" width="2" height="1"><data><tile gid="3"/><tile/></data></layer>\n</map>\n' \
    >"$s/xml.tmx" && seed tiled_map "$s/xml.tmx"
}
make_seeds

# ---- runs: FUZZ_JOBS harnesses at a time, then one line each in order ----
mkdir -p "$fz/logs"
one() {  # one NAME: runs harness NAME, leaves its log and exit code in $fz/logs/
  local h=$1 rc=0
  mkdir -p "$fz/corpus/$h" "$fz/crashes/$h"
  (cd "$fz" && TILEKIT_MEMORY=1G run_harness "$h" -max_total_time="$seconds" ${FUZZ_RUNS:+-runs=$FUZZ_RUNS} -max_len=16384 \
    -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$fz/crashes/$h/" "$fz/corpus/$h" >"$fz/logs/$h.log" 2>&1) || rc=$?
  echo "$rc" >"$fz/logs/$h.rc"
}
for h in "${harnesses[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  one "$h" &
done
wait
status=0
printf '%-16s %12s %8s %10s %8s  %s\n' harness runs seconds runs/s corpus result
for h in "${harnesses[@]}"; do
  log=$fz/logs/$h.log
  rc=$(cat "$fz/logs/$h.rc" 2>/dev/null || echo 1)
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  took=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)
  files=$(ls "$fz/corpus/$h" | wc -l)
  result=ok
  if [ "$rc" -ne 0 ]; then
    result="FAILED (exit $rc; see $log and $fz/crashes/$h/)"
    status=1
  fi
  rate=$([ -n "$took" ] && [ "${took:-0}" -gt 0 ] && echo $(( ${runs:-0} / took )) || echo -)
  printf '%-16s %12s %8s %10s %8s  %s\n' "$h" "${runs:--}" "${took:--}" "$rate" "$files" "$result"
done
exit $status
