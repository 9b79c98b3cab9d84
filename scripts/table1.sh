#!/usr/bin/env bash
# Reproduces Table 1 of Schloemer & Deussen 2010 (identically coloured 8-neighbours of each
# corner; 100 tilings of random resolution up to 4096x4096, every corner counted) for the
# stochastic (direct, long-period hash) and the Halton method, C = 2..8, and prints one JSON
# line per (C, method) with the paper's values. Usage: scripts/table1.sh [extra analyze args]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"
for algo in halton direct; do
  for c in 2 3 4 5 6 7 8; do
    "$tk" analyze neighbors --colors "$c" --algo "$algo" --tilings 100 --max-size 4096 --seed 1 --json "$@"
  done
done
