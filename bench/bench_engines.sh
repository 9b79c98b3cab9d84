#!/usr/bin/env bash
# Two tilekit binaries on the same imposed-group search, seed by seed (written to compare the one
# engine against the separate impose engine it replaced). For every seed both binaries run `pack
# --mode first --impose SPEC --threads T --seed S`, alternating, each with a fresh database, so they
# see the same load on average. CPU seconds (user + sys of the whole process, /usr/bin/time), wall
# seconds, nodes and whether a packing was found, per seed; one JSON line per binary with the
# medians, then one line with the per-seed CPU ratio (new / old) and the load average before and
# after.
#
#   bash bench/bench_engines.sh OLD_TILEKIT NEW_TILEKIT KIND C SPEC [SEEDS] [THREADS] [TIME_LIMIT]
#   bash bench/bench_engines.sh /work/wt/old-engine/build/tilekit build/tilekit corner 5 \
#        't=0,5:pi=1,2,3,4,0' '1 2 3 4 5' 1 120
set -euo pipefail
old=$1 new=$2 kind=$3 colours=$4 spec=$5
seeds=${6:-1 2 3 4 5}
threads=${7:-1}
limit=${8:-120}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
load0=$(cut -d' ' -f1 /proc/loadavg)
run() {  # run NAME BINARY SEED -> appends "seed cpu wall nodes found" to $tmp/NAME
  local name=$1 bin=$2 seed=$3 t0 t1 rc=0
  rm -f "$tmp/db.sqlite" "$tmp/stats.json"
  t0=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$tmp/rusage" "$bin" pack --kind "$kind" --colors "$colours" --method search \
    --impose "$spec" --threads "$threads" --seed "$seed" --time-limit "$limit" --quiet --json \
    --db "$tmp/db.sqlite" >"$tmp/out.json" || rc=$?
  t1=$(date +%s.%N)
  python3 - "$tmp/out.json" "$tmp/rusage" "$seed" "$t0" "$t1" "$rc" >>"$tmp/$name" <<'EOF'
import json, sys
out, rusage, seed, t0, t1, rc = sys.argv[1:]
j = json.load(open(out))
u, s = (float(x) for x in open(rusage).read().split()[-2:])
found = rc == "0" and j.get("valid", False) is True
print(seed, round(u + s, 3), round(float(t1) - float(t0), 3), j.get("nodes", 0), int(found))
EOF
}
for s in $seeds; do
  run old "$old" "$s"
  run new "$new" "$s"
done
load1=$(cut -d' ' -f1 /proc/loadavg)
python3 - "$tmp/old" "$tmp/new" "$old" "$new" "$kind" "$colours" "$spec" "$threads" "$limit" "$load0" "$load1" \
  "$(nproc)" <<'EOF'
import json, statistics, sys
fold, fnew, bold, bnew, kind, colours, spec, threads, limit, l0, l1, cores = sys.argv[1:]
def rows(f):
    return [dict(zip(("seed", "cpu", "wall", "nodes", "found"), map(float, line.split()))) for line in open(f)]
res = {}
for name, f, b in (("old", fold, bold), ("new", fnew, bnew)):
    r = rows(f)
    res[name] = r
    print(json.dumps({"bench": "engines", "engine": name, "binary": b, "kind": kind, "colors": int(colours),
                      "spec": spec, "threads": int(threads), "time_limit": float(limit), "cores": int(cores),
                      "seeds": [int(x["seed"]) for x in r], "cpu_seconds": [x["cpu"] for x in r],
                      "wall_seconds": [x["wall"] for x in r], "nodes": [int(x["nodes"]) for x in r],
                      "found": int(sum(x["found"] for x in r)),
                      "median_cpu_seconds": statistics.median(x["cpu"] for x in r),
                      "median_wall_seconds": statistics.median(x["wall"] for x in r)}))
ratio = [n["cpu"] / o["cpu"] if o["cpu"] > 0 else None for o, n in zip(res["old"], res["new"])]
print(json.dumps({"bench": "engines", "cpu_ratio_new_over_old": ratio,
                  "median_cpu_ratio": statistics.median(
                      x["cpu"] for x in res["new"]) / max(1e-9, statistics.median(x["cpu"] for x in res["old"])),
                  "loadavg": [float(l0), float(l1)]}))
EOF
