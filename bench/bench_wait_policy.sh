#!/usr/bin/env bash
# CPU seconds of a short `tilekit pack --method search` with the idle OpenMP threads released at
# the end of the search (the default) against the same binary with the release off
# (GOMP_SPINCOUNT set to libgomp's default 300,000: the same spin, no release), runs alternating,
# and OMP_WAIT_POLICY=passive (no spin at all) as the floor, fresh database each run. CPU is the child's rusage (microseconds, not /usr/bin/time's 10 ms).
# One JSON line per case: median CPU and wall seconds of each variant and the load average.
#   bash bench/bench_wait_policy.sh [BUILD_DIR] [REPS] [THREADS] [CASES...]   cases: corner:4 wang:4 ...
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
reps=${2:-15}
threads=${3:-2}
shift $(( $# < 3 ? $# : 3 ))
cases=("$@")
((${#cases[@]})) || cases=(corner:4 wang:4)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for c in "${cases[@]}"; do
  python3 - "$build/tilekit" "${c%%:*}" "${c##*:}" "$reps" "$threads" "$tmp" <<'PY'
import json, os, resource, statistics, subprocess, sys, time
tk, kind, colours, reps, threads, tmp = sys.argv[1:7]
def run(env_extra, seed):
    db = os.path.join(tmp, "db.sqlite")
    if os.path.exists(db): os.remove(db)
    env = dict(os.environ, **env_extra)
    for k in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT"):
        if k not in env_extra: env.pop(k, None)
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN); t0 = time.monotonic()
    subprocess.run([tk, "pack", "--kind", kind, "--colors", colours, "--method", "search",
                    "--threads", threads, "--seed", str(seed), "--quiet", "--json", "--db", db,
                    "--portfolio-stats", os.path.join(tmp, "stats.json")],
                   env=env, check=True, stdout=subprocess.DEVNULL)
    t1 = time.monotonic(); r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime), t1 - t0
variants = {"release": {}, "spin_no_release": {"GOMP_SPINCOUNT": "300000"},
            "passive": {"OMP_WAIT_POLICY": "passive"}}
res = {v: ([], []) for v in variants}
load0 = os.getloadavg()[0]
for i in range(int(reps)):
    for v, e in variants.items():
        cpu, wall = run(e, i)
        res[v][0].append(cpu); res[v][1].append(wall)
out = {"bench": "wait-policy", "kind": kind, "colors": int(colours), "threads": int(threads),
       "cores": os.cpu_count(), "runs": int(reps)}
for v, (cpu, wall) in res.items():
    out[v] = {"median_cpu_seconds": round(statistics.median(cpu), 4),
              "median_wall_seconds": round(statistics.median(wall), 4)}
out["cpu_ratio_release_over_spin"] = round(out["release"]["median_cpu_seconds"] /
                                           out["spin_no_release"]["median_cpu_seconds"], 3)
out["loadavg"] = [load0, os.getloadavg()[0]]
print(json.dumps(out))
PY
done
