#!/usr/bin/env python3
"""Same-run comparison of two tilekit binaries (an old build against a new one) on the jobs whose
speed a change must not lose: pack (the C=2 Wang count), tile (the direct stochastic tiling), points
generate and texture tiles. The two binaries run alternately (old, new, then new, old, ...), each
case REPS times; it prints one JSON line per case with the median CPU seconds of each binary (user +
system of the process, steadier than wall time on a shared machine), their ratio new/old, and
whether both printed the same result (the count, the tiling's hash, the points' count, the tile
set's files). Usage: scripts/compare-builds.py OLD_TILEKIT NEW_TILEKIT [REPS (default 5)]
"""
import hashlib
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile

TEXTURES = os.environ.get("TILEKIT_TEXTURES", os.path.expanduser("~/.cache/tilekit/textures"))


def cases(work):
    """(name, args, what must agree between the binaries: a function of the JSON and the folder)"""
    return [
        ("pack wang C=2 count, 1 thread",
         ["pack", "--kind", "wang", "--colors", "2", "--mode", "count", "--method", "search", "--threads", "1", "--quiet", "--json",
          "--db", os.path.join(work, "p.sqlite")],
         lambda j, d: (j["solutions"], j["orbits"], j["nodes"])),
        ("tile corner C=4 direct 2048x2048",
         ["tile", "--set", "complete-corner-4", "--algo", "direct", "--size", "2048x2048", "--seed", "7", "--json",
          "--out", os.path.join(work, "t.json")],
         lambda j, d: (j["valid"], file_hash(os.path.join(d, "t.json")))),
        ("points generate 1e7, 1 thread",
         ["points", "generate", "--window", "0,0,3162,3162", "--density", "1", "--threads", "1", "--quiet", "--json",
          "--out", os.path.join(work, "p.f32")],
         lambda j, d: (j["points"], file_hash(os.path.join(d, "p.f32")))),
        ("texture tiles corner C=2 64 px, 1 thread",
         ["texture", "tiles", "--exemplar", os.path.join(TEXTURES, "gravel.png"), "--kind", "corner", "--colors", "2",
          "--tile-px", "64", "--threads", "1", "--quiet", "--json", "--out", os.path.join(work, "tiles")],
         lambda j, d: file_hash(os.path.join(d, "tiles", "tileset.png"))),
    ]


def file_hash(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()[:16]


def run(binary, args):
    p = subprocess.run([binary] + args, capture_output=True)
    if p.returncode != 0:
        sys.exit(f"compare-builds: {binary} {' '.join(args)} exited {p.returncode}: {p.stderr.decode()[-300:]}")
    return json.loads(p.stdout)


def cpu_of(binary, args):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    j = run(binary, args)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return j, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    old, new = sys.argv[1], sys.argv[2]
    reps = int(sys.argv[3]) if len(sys.argv) > 3 else 5
    with tempfile.TemporaryDirectory() as root:
        for name, _, _ in cases(root):
            times = {"old": [], "new": []}
            results = {}
            for i in range(reps):
                order = [("old", old), ("new", new)] if i % 2 == 0 else [("new", new), ("old", old)]
                for label, binary in order:
                    work = os.path.join(root, label)
                    os.makedirs(work, exist_ok=True)
                    _, args, agree = next(c for c in cases(work) if c[0] == name)
                    for leftover in ("p.sqlite", "p.f32", "t.json"):
                        if os.path.exists(os.path.join(work, leftover)):
                            os.remove(os.path.join(work, leftover))
                    j, cpu = cpu_of(binary, args)
                    times[label].append(cpu)
                    results[label] = agree(j, work)
            mo, mn = statistics.median(times["old"]), statistics.median(times["new"])
            print(json.dumps({"case": name, "reps": reps, "old_cpu_s": round(mo, 4), "new_cpu_s": round(mn, 4),
                              "ratio_new_old": round(mn / mo, 3) if mo > 0 else None,
                              "same_result": results["old"] == results["new"]}), flush=True)


if __name__ == "__main__":
    main()
