#!/usr/bin/env bash
# End-to-end time of `tilekit pack --method auto` (the imposed-group portfolio), process start
# included, against `tilekit --version` (process start alone) in the same run. Fresh database
# and fresh portfolio statistics for every run, so no database hit and no learned order.
# One JSON line per case: median and max wall seconds over REPS runs.
#   bash bench/bench_impose_cli.sh [BUILD_DIR] [REPS] [THREADS] [CASES...]   cases: corner:4 wang:4 ...
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
reps=${2:-11}
threads=${3:-2}
shift $(( $# < 3 ? $# : 3 ))
cases=("$@")
((${#cases[@]})) || cases=(corner:4 wang:4 corner:5 wang:5)
# TMPDIR picks where the database and statistics live (e.g. TMPDIR=/dev/shm to take disk fsyncs out).
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
median() { sort -g | awk '{a[NR]=$1} END {printf "%.4f", a[int((NR+1)/2)]}'; }
maxv() { sort -g | tail -1 | awk '{printf "%.4f", $1}'; }
now() { date +%s.%N; }
: >"$tmp/base"
for ((i = 0; i < reps; ++i)); do
  t0=$(now); "$build/tilekit" --version >/dev/null; t1=$(now)
  echo "$t1 - $t0" | bc -l >>"$tmp/base"
done
base=$(median <"$tmp/base")
for c in "${cases[@]}"; do
  kind=${c%%:*}; colours=${c##*:}
  : >"$tmp/times"; : >"$tmp/groups"
  for ((i = 0; i < reps; ++i)); do
    rm -f "$tmp/db.sqlite" "$tmp/stats.json"
    t0=$(now)
    "$build/tilekit" pack --kind "$kind" --colors "$colours" --method auto --threads "$threads" --seed "$i" \
      --quiet --json --db "$tmp/db.sqlite" --portfolio-stats "$tmp/stats.json" >"$tmp/out.json"
    t1=$(now)
    echo "$t1 - $t0" | bc -l >>"$tmp/times"
    python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["valid"]; print(j["portfolio"]["winner"])' \
      "$tmp/out.json" >>"$tmp/groups"
  done
  printf '{"bench":"impose-cli","tmpdir":"%s","kind":"%s","colors":%s,"threads":%s,"cores":%s,"runs":%s,"median_seconds":%s,"max_seconds":%s,"baseline_process_start_seconds":%s,"winners":"%s"}\n' \
    "$(dirname "$tmp")" "$kind" "$colours" "$threads" "$(nproc)" "$reps" "$(median <"$tmp/times")" "$(maxv <"$tmp/times")" "$base" \
    "$(sort "$tmp/groups" | uniq -c | awk '{printf "%s%s x%s", (NR>1?"; ":""), $2, $1}')"
done
