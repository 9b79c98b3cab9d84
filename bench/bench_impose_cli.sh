#!/usr/bin/env bash
# End-to-end time of `tilekit pack --method search` (the portfolio), process start included,
# against `tilekit --version` (process start alone) in the same run. Fresh database and fresh
# portfolio statistics for every run, so no database hit and no learned order. One JSON line per
# case: median and max wall seconds, median CPU seconds over REPS runs, and the load average.
#   bash bench/bench_impose_cli.sh [BUILD_DIR] [REPS] [THREADS] [CASES...]   cases: corner:4 wang:4 ...
#   METHOD=auto bash bench/bench_impose_cli.sh ...   (auto answers C=4 corner from the stored packing)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
reps=${2:-11}
method=${METHOD:-search}
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
  : >"$tmp/times"; : >"$tmp/groups"; : >"$tmp/cpu"
  load0=$(cut -d' ' -f1 /proc/loadavg)
  for ((i = 0; i < reps; ++i)); do
    rm -f "$tmp/db.sqlite" "$tmp/stats.json"
    t0=$(now)
    /usr/bin/time -f "%U %S" -o "$tmp/rusage" "$build/tilekit" pack --kind "$kind" --colors "$colours" \
      --method "$method" --threads "$threads" --seed "$i" \
      --quiet --json --db "$tmp/db.sqlite" --portfolio-stats "$tmp/stats.json" >"$tmp/out.json"
    t1=$(now)
    echo "$t1 - $t0" | bc -l >>"$tmp/times"
    awk '{print $1 + $2}' "$tmp/rusage" >>"$tmp/cpu"
    python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["valid"]; print((j.get("portfolio") or {}).get("winner") or j["method"])' \
      "$tmp/out.json" >>"$tmp/groups"
  done
  load1=$(cut -d' ' -f1 /proc/loadavg)
  printf '{"bench":"impose-cli","method":"%s","tmpdir":"%s","kind":"%s","colors":%s,"threads":%s,"cores":%s,"runs":%s,"median_seconds":%s,"max_seconds":%s,"median_cpu_seconds":%s,"baseline_process_start_seconds":%s,"loadavg":[%s,%s],"winners":"%s"}\n' \
    "$method" "$(dirname "$tmp")" "$kind" "$colours" "$threads" "$(nproc)" "$reps" "$(median <"$tmp/times")" "$(maxv <"$tmp/times")" \
    "$(median <"$tmp/cpu")" "$base" "$load0" "$load1" \
    "$(sort "$tmp/groups" | uniq -c | awk '{printf "%s%s x%s", (NR>1?"; ":""), $2, $1}')"
done
