#!/bin/bash
# The traces and simulator tables of BENCHMARKS.md, "Scale-out: traces and the scheduling
# simulator": each run once on one thread with `pack --trace`, then `cluster simulate` at
# P = 16, 128, 1024 and 10000 under every policy. Usage: scripts/scale-traces.sh [OUT_DIR]
# (default /tmp/tilekit-traces; the traces are about 1-3 MB each, not committed).
set -euo pipefail
tk=${TILEKIT:-$(dirname "$0")/../build/tilekit}
out=${1:-/tmp/tilekit-traces}
mkdir -p "$out"
run() {  # run NAME PACK-ARGS...
  local name=$1
  shift
  "$tk" pack "$@" --threads 1 --quiet --trace "$out/$name.jsonl" --db "$out/$name.sqlite" --json >"$out/$name.json" || true
  "$tk" cluster simulate "$out/$name.jsonl" --workers 16,128,1024,10000 | tee "$out/$name.sim.txt"
}
run wang2-count --kind wang --colors 2 --mode count
run corner3-t03-count --kind corner --colors 3 --mode count --impose 't=0,3:pi=1,2,0'
run corner5-first --kind corner --colors 5 --method search --seed 1 --time-limit 90 \
  --portfolio-stats "$out/portfolio-stats.json"
