#!/usr/bin/env bash
# Runs every benchmark (build/bench_*) and prints their JSON lines (one per case).
# Usage: scripts/bench.sh [ARGS passed to every benchmark]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" >/dev/null
shopt -s nullglob
benches=("$root"/build/bench_*)
if ((${#benches[@]} == 0)); then
  echo "bench.sh: no benchmarks in $root/build" >&2
  exit 1
fi
for b in "${benches[@]}"; do
  [ -x "$b" ] || continue
  echo "bench.sh: $(basename "$b")" >&2
  "$b" "$@"
done
