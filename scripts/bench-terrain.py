#!/usr/bin/env python3
"""Terrain transition sets (`tilekit texture terrain`) on the fetched real textures: for C = 2, 3, 4
terrains and several seeds, the seam ratio (`texture analyze`) of
  - render: a flat 1024x1024 render of the set's atlas (`texture atlas` + `texture render`, the
    direct stochastic tiling through the atlas);
  - tiled-map: a 16x16 map of the set written by `tiled map --tiles DIR` (the direct stochastic
    tiling) and rendered by Tiled's own tmxrasterizer;
  - tiled-sheet: the packed sheet repeated 2x2 as a Tiled map, rendered by tmxrasterizer (the
    sheet's wrap-around borders included);
and the mean step between 4-neighbours of two different terrains inside the tiles
(`terrain_seam_step`) with the default seams (minimum-error cuts refined by a graph cut), the cuts
alone (`--seams cut`) and straight seams on the tiles' middle lines (`--seams straight`, the
baseline), same run, same seed.
Medians over the seeds; one markdown table on stdout.

Usage: python3 scripts/bench-terrain.py [--seeds 3] [--colors 2,3,4] [--tile-px 64]
Needs build/tilekit, scripts/fetch-textures.sh's textures and Tiled (tmxrasterizer).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TK = os.path.join(ROOT, "build", "tilekit")
TERRAINS = [("grass", "grass"), ("dirt", "oa-dirt"), ("gravel", "gravel"), ("rock", "oa-rock")]


def tk(*args):
    r = subprocess.run([TK, *args], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"tilekit {' '.join(args)}: exit {r.returncode}: {r.stderr.strip()}")
    return json.loads(r.stdout) if "--json" in args else None


def rasterize(tmx, png):
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    r = subprocess.run(["tmxrasterizer", tmx, png], capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"tmxrasterizer {tmx}: exit {r.returncode}: {r.stderr.strip()}")


def seam_ratio(png, px):
    return tk("texture", "analyze", png, "--tile-px", str(px), "--json")["seam_ratio"]


def wrapped_sheet_tmx(path, tsx, cols, px):
    rows = [",".join(str((r % cols) * cols + (c % cols) + 1) for c in range(2 * cols)) for r in range(2 * cols)]
    with open(path, "w") as f:
        f.write(f'<?xml version="1.0" encoding="UTF-8"?>\n<map version="1.8" orientation="orthogonal" '
                f'renderorder="right-down" width="{2 * cols}" height="{2 * cols}" tilewidth="{px}" '
                f'tileheight="{px}" infinite="0" nextlayerid="2" nextobjectid="1">\n'
                f' <tileset firstgid="1" source="{tsx}"/>\n'
                f' <layer id="1" name="sheet" width="{2 * cols}" height="{2 * cols}">\n'
                f'  <data encoding="csv">\n' + ",\n".join(rows) + "\n</data>\n </layer>\n</map>\n")


def one(work, c, seed, px):
    terr = [a for t in TERRAINS[:c] for a in ("--terrain", f"{t[0]}={t[1]}")]
    d = os.path.join(work, f"c{c}-s{seed}")
    common = [*terr, "--tile-px", str(px), "--seed", str(seed), "--quiet", "--json"]
    j = tk("texture", "terrain", *common, "--out", d + "/set", "--tiled", d + "/tiled")
    cut = tk("texture", "terrain", *common, "--seams", "cut", "--out", d + "/cut")
    base = tk("texture", "terrain", *common, "--seams", "straight", "--out", d + "/straight")
    tk("texture", "atlas", d + "/set", "--out", d + "/atlas/atlas.png", "--quiet")
    tk("texture", "render", "--atlas", d + "/atlas/atlas.png", "--size", "1024x1024", "--seed", str(seed),
       "--out", d + "/render.png", "--quiet")
    a = tk("texture", "analyze", d + "/render.png", "--tile-px", str(px), "--json")
    m = tk("tiled", "map", "--kind", "corner", "--colors", str(c), "--tiles", d + "/set", "--size", "16x16",
           "--seed", str(seed), "--name", "map", "--out", d + "/map", "--json")
    rasterize(m["tmx"], d + "/map.png")
    cols = j["tiled"]["cols"]
    wrapped_sheet_tmx(os.path.join(d, "tiled", "wrap.tmx"), os.path.basename(j["tiled"]["tsx"]), cols, px)
    rasterize(os.path.join(d, "tiled", "wrap.tmx"), d + "/wrap.png")
    return {"seconds": j["seconds"], "render": a["seam_ratio"], "grid": a["grid_repetition"],
            "tiled_map": seam_ratio(d + "/map.png", px), "tiled_sheet": seam_ratio(d + "/wrap.png", px),
            "step_graph": j["terrain_seam_step"], "step_cut": cut["terrain_seam_step"],
            "step_straight": base["terrain_seam_step"],
            "step_ratio": j["terrain_seam_step"] / base["terrain_seam_step"], "texture_step": j["terrain_mean_step"]}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seeds", type=int, default=3)
    p.add_argument("--colors", default="2,3,4")
    p.add_argument("--tile-px", type=int, default=64)
    a = p.parse_args()
    print("| C | terrains | seeds | synthesis s | seam ratio: render 1024² | Tiled map 16² | Tiled sheet 2x2 "
          "| grid repetition | terrain seam step: graph cut / cut / straight (ratio) | textures' own step |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        for c in [int(x) for x in a.colors.split(",")]:
            runs = [one(work, c, s, a.tile_px) for s in range(1, a.seeds + 1)]
            med = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
            names = ", ".join(t[1] for t in TERRAINS[:c])
            print(f"| {c} | {names} | {a.seeds} | {med['seconds']:.1f} | {med['render']:.3f} | "
                  f"{med['tiled_map']:.3f} | {med['tiled_sheet']:.3f} | {med['grid']:.3f} | "
                  f"{med['step_graph']:.1f} / {med['step_cut']:.1f} / {med['step_straight']:.1f} "
                  f"({med['step_ratio']:.2f}) | "
                  f"{med['texture_step']:.1f} |", flush=True)
            worst = max(max(r["render"], r["tiled_map"], r["tiled_sheet"]) for r in runs)
            print(f"<!-- C={c}: worst seam ratio over seeds and views {worst:.3f} -->", flush=True)


if __name__ == "__main__":
    main()
