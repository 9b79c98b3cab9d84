#!/usr/bin/env bash
# Corner packings by search with colour-quotient lifts among the portfolio's candidates,
# through the CLI (process start included). One JSON line per case: wall and CPU seconds (CPU
# includes cadical, a waited-for child), the winner, whether the packing validates; the load first
# and last. Results: BENCHMARKS.md, "Colour-quotient lifts".
#   bash bench/lift_search.sh c8                the C=8 cases: default portfolio (seed 0, twice),
#                                               the lift:4 candidate alone (twice), --lift 4 with
#                                               cadical (seed 1), and the plain search baseline (30 s)
#   bash bench/lift_search.sh portfolio C LIMIT [THREADS]
#                                               the default portfolio for C colours on THREADS threads
#                                               (default 1), stopped after LIMIT s; prints the
#                                               per-candidate table
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
T=${TILEKIT_BIN:-$root/build/tilekit}
D=$(mktemp -d)
trap 'rm -rf "$D"' EXIT
load() { echo "{\"loadavg\":\"$(cut -d' ' -f1-3 /proc/loadavg)\",\"cores\":$(nproc)}"; }
run() {  # C, case name, pack args...
  local c=$1 name=$2
  shift 2
  local s e rc
  s=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$D/t" "$T" pack --kind corner --colors "$c" --quiet --json --db "$D/$name.sqlite" \
    --portfolio-stats - --out "$D/$name.json" "$@" >"$D/out.json" 2>/dev/null
  rc=$?
  e=$(date +%s.%N)
  [ -f "$D/$name.json" ] && "$T" check "$D/$name.json" --json >"$D/check.json" 2>/dev/null  # independent validator
  python3 - "$name" "$rc" "$s" "$e" "$D/t" "$D/out.json" "$D/check.json" <<'PY'
import json, sys
name, rc, s, e, tf, of, cf = sys.argv[1:]
u, sy = map(float, open(tf).read().split()[-2:])
def load(f):
    try: return json.load(open(f))
    except Exception: return {}
j, chk = load(of), load(cf)
p = j.get("portfolio") or {}
print(json.dumps({"case": name, "rc": int(rc), "wall_s": round(float(e) - float(s), 3), "cpu_s": round(u + sy, 3),
                  "found": bool(j.get("solutions")), "validator_packing": chk.get("packing") if j.get("solutions") else None,
                  "winner": p.get("winner"),
                  "candidates": [{k: r[k] for k in ("group", "tries", "seconds", "nodes", "found")} for r in p.get("runs", [])]}))
PY
  rm -f "$D/check.json"
}
load
case "${1:-c8}" in
  c8)
    for r in 1 2; do run 8 portfolio-seed0-rep$r --method search --threads 2 --seed 0; done
    for r in 1 2; do run 8 lift4-cell-seed0-rep$r --method search --threads 2 --seed 0 --candidate lift:4; done
    run 8 lift4-sat-seed1 --lift 4 --formulation sat --seed 1 --time-limit 90
    run 8 plain-baseline --method search --plain --threads 2 --time-limit 30
    ;;
  portfolio)
    run "$2" "portfolio-c$2" --method search --threads "${4:-1}" --time-limit "$3"
    ;;
  *) echo "usage: bash bench/lift_search.sh c8 | portfolio C LIMIT [THREADS]" >&2; exit 2 ;;
esac
load
