#!/usr/bin/env bash
# Builds the libFuzzer harnesses of fuzz/ (clang, -fsanitize=fuzzer,address,undefined) in
# build-fuzz/, makes their seed corpora from Tilekit's own outputs (build/tilekit), and runs each
# harness for SECONDS (default 10). Prints one line per harness (runs, seconds, runs/s, corpus)
# and fails if any harness found a crash, leak, hang or sanitizer report (the input is kept in
# build-fuzz/crashes/NAME/; turn it into a regression test). Usage:
#   scripts/fuzz.sh [SECONDS_PER_HARNESS] [HARNESS...]
#   FUZZ_RUNS=1000000 scripts/fuzz.sh 0   each harness for exactly that many executions (SECONDS 0:
#                                         no time bound), the issue-15 figure in docs/TESTING.md
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-10}
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(tile_set tiling checkpoint db_export group_spec portfolio_stats probability_map flags)
"$root/scripts/setup.sh"
[ -x "$root/build/tilekit" ] || "$root/scripts/build.sh"
fz=$root/build-fuzz
cmake -S "$root" -B "$fz" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g" -DTILEKIT_FUZZ=ON -DTILEKIT_TESTS=OFF -DTILEKIT_BENCH=OFF >/dev/null
targets=()
for h in "${harnesses[@]}"; do targets+=(--target "fuzz_$h"); done
cmake --build "$fz" -j "$(nproc)" "${targets[@]}"

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
  python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["group"]["spec"], end="")' "$s/portfolio.json" \
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
}
make_seeds

# ---- runs ----
status=0
printf '%-16s %12s %8s %10s %8s  %s\n' harness runs seconds runs/s corpus result
for h in "${harnesses[@]}"; do
  mkdir -p "$fz/corpus/$h" "$fz/crashes/$h"
  log=$fz/fuzz_$h.log
  rc=0
  (cd "$fz" && "./fuzz_$h" -max_total_time="$seconds" ${FUZZ_RUNS:+-runs=$FUZZ_RUNS} -max_len=16384 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$fz/crashes/$h/" "$fz/corpus/$h" >"$log" 2>&1) || rc=$?
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
