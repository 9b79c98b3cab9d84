#!/bin/bash
# BENCHMARKS.md, "Scale-out", MPI: the C=3 corner count under t=(0,3) (303,264) as one process
# (no MPI), as `pack --mpi` on 1 rank and on 2 ranks (one thread each), interleaved REPS times
# (single, 1, 2, single, 1, 2, ...). Prints one line per run (wall s, user + sys CPU s of the
# process tree, solutions, steals, the load average before the run) and the medians.
# Usage: scripts/mpi-bench.sh [REPS] [OUT_DIR] (default 3, /tmp/tilekit-mpi-bench).
set -euo pipefail
tk=${TILEKIT:-$(cd "$(dirname "$0")/.." && pwd)/build/tilekit}
reps=${1:-3}
out=${2:-/tmp/tilekit-mpi-bench}
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
args=(pack --kind corner --colors 3 --mode count --impose 't=0,3:pi=1,2,0' --threads 1 --quiet --json
  --db "$out/bench.sqlite")
field() { grep -o "\"$1\":[a-z0-9.]*" "$2" | head -n 1 | cut -d: -f2; }
: >"$out/runs.txt"
for rep in $(seq "$reps"); do
  for cfg in single 1 2; do
    load=$(cut -d' ' -f1 /proc/loadavg)
    if [ "$cfg" = single ]; then
      /usr/bin/time -f "%e %U %S" -o "$out/time.txt" "$tk" "${args[@]}" >"$out/run.json"
    else
      /usr/bin/time -f "%e %U %S" -o "$out/time.txt" mpirun -np "$cfg" "$tk" "${args[@]}" --mpi >"$out/run.json"
    fi
    read -r wall user sys <"$out/time.txt"
    cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN {printf "%.2f", u + s}')
    echo "$cfg $rep wall $wall cpu $cpu solutions $(field solutions "$out/run.json") steals $(field steals "$out/run.json") load $load" |
      tee -a "$out/runs.txt"
  done
done
median() { sort -n | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
for cfg in single 1 2; do
  w=$(awk -v c="$cfg" '$1 == c {print $4}' "$out/runs.txt" | median)
  c=$(awk -v c="$cfg" '$1 == c {print $6}' "$out/runs.txt" | median)
  echo "median $cfg: wall $w s, cpu $c s"
done
