#!/usr/bin/env python3
"""`tilekit fill` against the npm port of Wave Function Collapse, same run, same machine.

For each reference sample (tilemap/data/wfc/, the reference's sizes and periodicity) and for
square maps of the sizes given, both fillers get the same seeds and the same time limit per seed:
success rate, median and 95th-percentile seconds per seed (the npm port starts again after each
contradiction, as the reference does, until the limit), and how far each filler's tile
frequencies (over its successful maps) are from the weights: the total variation distance between
the frequency of each oriented tile and its share of the weights (0 = exactly the weights).
Prints a Markdown table (BENCHMARKS.md). Usage:
  NODE_PATH=$(bash scripts/npm-deps.sh)/node_modules python3 scripts/bench-fill-vs-wfc.py \
      [--seeds 100] [--large 128:20,512:3,1024:1] [--limit 10] [--large-limit 60] [--no-reference]
      [--orders scanline,entropy] [--only 'Circuit,Knots T'] [--no-npm]
"""
import argparse, json, os, statistics, subprocess, sys, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tilemap", "data", "wfc")
SAMPLES = [  # set, subset, size, periodic (the reference's samples.xml)
    ("Castle", "", 50, False), ("Circuit", "Turnless", 34, True), ("Circuit", "", 34, True), ("Rooms", "", 30, False),
    ("Knots", "Standard", 24, True), ("Knots", "Dense", 24, True), ("Knots", "CE", 24, True), ("Knots", "C", 24, True),
    ("Knots", "Fabric", 24, True), ("Knots", "Dense Fabric", 24, True), ("Knots", "Crossless", 24, False),
    ("Knots", "TE", 24, False), ("Knots", "T", 24, False), ("Knots", "CL", 24, False)]
LARGE = [("Castle", "", False), ("Circuit", "Turnless", True), ("Knots", "Standard", True), ("Rooms", "", False)]


def p95(xs):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(round(0.95 * (len(xs) - 1))))]


def tv(counts, weights):
    n, w = sum(counts), sum(weights)
    return 0.5 * sum(abs(c / n - x / w) for c, x in zip(counts, weights)) if n else float("nan")


def ours(tilekit, s, sub, size, periodic, seeds, limit, order="auto"):
    runs, counts, weights = [], None, None
    for seed in range(1, seeds + 1):
        cmd = [tilekit, "fill", "--set", os.path.join(DATA, s + ".xml"), "--size", f"{size}x{size}", "--seed", str(seed),
               "--time-limit", str(limit), "--order", order, "--json", "--quiet"]
        if sub: cmd += ["--subset", sub]
        if periodic: cmd.append("--torus")
        p = subprocess.run(cmd, capture_output=True, text=True)
        j = json.loads(p.stdout)
        ok = p.returncode == 0 and j["found"] and j["valid"]
        runs.append((ok, j["seconds"]))
        if ok:
            f = j["frequencies"]
            weights = [x["weight"] for x in f]
            counts = [a + x["cells"] for a, x in zip(counts or [0] * len(f), f)]
    return runs, counts, weights


def npm(s, sub, size, periodic, seeds, limit):
    cmd = ["node", "--max-old-space-size=6000", os.path.join(ROOT, "scripts", "wfc-npm-run.js"),
           os.path.join(DATA, s + ".xml"), sub, str(size), "1" if periodic else "0", "1", str(seeds), str(limit)]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:  # out of memory or crashed: every seed failed
        return [(False, time.time() - t0)] * seeds, None, "node exit %d" % p.returncode
    j = json.loads(p.stdout)
    return [(r["ok"], r["seconds"]) for r in j["runs"]], j["counts"], ""


def row(name, size, filler, runs, counts, weights, limit, note=""):
    ok = [t for good, t in runs if good]
    times = [t for _, t in runs]
    rate = f"{len(ok)}/{len(runs)}"
    med = f"{statistics.median(times):.3f}" if times else "-"
    p = f"{p95(times):.3f}" if times else "-"
    d = f"{tv(counts, weights):.3f}" if counts and weights else "-"
    print(f"| {name} | {size}² | {filler} | {rate} | {med} | {p} | {d} | {limit} |{(' ' + note) if note else ''}", flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tilekit", default=os.path.join(ROOT, "build", "tilekit"))
    ap.add_argument("--seeds", type=int, default=100)
    ap.add_argument("--limit", type=float, default=10)
    ap.add_argument("--large", default="128:20,512:3,1024:1", help="SIZE:SEEDS,... for the four sets")
    ap.add_argument("--large-limit", type=float, default=60)
    ap.add_argument("--no-reference", action="store_true", help="only the larger sizes")
    ap.add_argument("--first", type=int, default=0, help="start at this reference sample (0-based)")
    ap.add_argument("--orders", default="auto", help="tilekit fill --order values, one row each (auto,scanline,entropy)")
    ap.add_argument("--only", default="", help="reference samples to run, e.g. 'Circuit,Knots T' (default: all)")
    ap.add_argument("--no-npm", action="store_true", help="Tilekit's rows only")
    a = ap.parse_args()
    orders = [o for o in a.orders.split(",") if o]
    only = [x.strip() for x in a.only.split(",") if x.strip()]

    def both(name, s, sub, size, periodic, seeds, limit):
        w = None
        for o in orders:
            r, c, w = ours(a.tilekit, s, sub, size, periodic, seeds, limit, o)
            row(name, size, "tilekit fill" + ("" if orders == ["auto"] else f" --order {o}"), r, c, w, limit)
        if not a.no_npm:
            r2, c2, note = npm(s, sub, size, periodic, seeds, limit)
            row(name, size, "npm wavefunctioncollapse", r2, c2, w, limit, note)

    print("| sample | size | filler | filled | median s | p95 s | TV(freq, weights) | limit s |")
    print("|---|---|---|---|---|---|---|---|")
    for s, sub, size, periodic in ([] if a.no_reference else SAMPLES[a.first:]):
        if only and (s + (f" {sub}" if sub else "")) not in only: continue
        name = s + (f" {sub}" if sub else "") + (" (torus)" if periodic else "")
        both(name, s, sub, size, periodic, a.seeds, a.limit)
    for spec in a.large.split(","):
        if not spec: continue
        size, seeds = (int(x) for x in spec.split(":"))
        for s, sub, periodic in LARGE:
            if only and (s + (f" {sub}" if sub else "")) not in only: continue
            name = s + (f" {sub}" if sub else "") + (" (torus)" if periodic else "")
            both(name, s, sub, size, periodic, seeds, a.large_limit)


if __name__ == "__main__":
    sys.exit(main())
