# ---- body of the merge job (scripts/slurm/merge.body.sh) ----
# Expects, set above by `tilekit cluster submit`: TILEKIT, RUN_DIR, SHARDS and SPLIT_AFTER.
# Runs after the whole shard array succeeded (--dependency=afterok:ARRAY): merges the shard
# databases into RUN_DIR/merged.sqlite, writes `tilekit db stats --json` to RUN_DIR/merged.json,
# adds up the shards' portfolio statistics (first-mode runs) into RUN_DIR/portfolio-stats.json
# (`tilekit pack --portfolio-report --portfolio-stats RUN_DIR/portfolio-stats.json` reads it)
# and prints the final count. Solutions are unique by hash, so merging again (or a shard
# counted twice) changes nothing.
set -euo pipefail

dir="$RUN_DIR/shards"
# A split run (SPLIT_AFTER > 0): this job runs after round R (its argument, 0 = the first array).
# `tilekit cluster split` writes the result of every shard now complete and the units of round
# R+1 (cluster/split.hpp); while there are any, they are queued as the next array, with this
# job again after them, and nothing is merged yet.
round=${1:-0}
if [ "${SPLIT_AFTER:-0}" != 0 ]; then
  "$TILEKIT" cluster split --run-dir "$RUN_DIR" --after-round "$round" --json >"$RUN_DIR/split-$((round + 1)).json"
  units=$({ grep -o '"units":[0-9]*' "$RUN_DIR/split-$((round + 1)).json" || true; } | head -n 1 | cut -d: -f2)
  if ((${units:-0} > 0)); then
    next=$((round + 1))
    array=$(sbatch --parsable --array=0-$((units - 1)) "$RUN_DIR/pack-array.sbatch" "$next")
    array=${array%%;*}
    merge=$(sbatch --parsable --dependency=afterok:"$array" "$RUN_DIR/merge.sbatch" "$next")
    merge=${merge%%;*}
    echo "tilekit merge: round $next: $units units of unfinished work, array job $array, then merge job $merge"
    exit 0
  fi
  echo "tilekit merge: no unfinished work after round $round; merging"
fi
inputs=()
missing=()
sum=0
for ((i = 0; i < SHARDS; i++)); do
  if [ -s "$dir/shard-$i.done.json" ] && [ -s "$dir/shard-$i.sqlite" ]; then
    inputs+=("$dir/shard-$i.sqlite")
    for f in "$dir/shard-$i".part-*.sqlite; do  # the work units of a split shard
      if [ -s "$f" ]; then inputs+=("$f"); fi
    done
    # (no "solutions" in an `aperiodic enumerate` shard's result: grep finds nothing, which must
    # not end the job under set -e and pipefail)
    n=$({ grep -o '"solutions":[0-9]*' "$dir/shard-$i.done.json" || true; } | head -n 1 | cut -d: -f2)
    sum=$((sum + ${n:-0}))
  else
    missing+=("$i")
  fi
done
incomplete=()
for ((i = 0; i < SHARDS; i++)); do
  grep -q '"timed_out":true' "$dir/shard-$i.done.json" 2>/dev/null && incomplete+=("$i")
done
if ((${#incomplete[@]})); then
  echo "tilekit merge: warning: shards ${incomplete[*]} stopped at their --time-limit (timed_out); the count is not final" >&2
fi
if ((${#missing[@]})); then
  echo "tilekit merge: shards not complete: ${missing[*]} (see tilekit cluster status --run-dir $RUN_DIR)" >&2
  exit 1
fi

"$TILEKIT" db merge "$RUN_DIR/merged.sqlite" "${inputs[@]}"
stats=()
for ((i = 0; i < SHARDS; i++)); do
  [ -s "$dir/shard-$i.stats.json" ] && stats+=(--portfolio-stats "$dir/shard-$i.stats.json")
done
if ((${#stats[@]})); then
  "$TILEKIT" pack --portfolio-report "${stats[@]}" --out "$RUN_DIR/portfolio-stats.json" --json >/dev/null
  echo "tilekit merge: portfolio statistics of the shards added up in $RUN_DIR/portfolio-stats.json"
fi
"$TILEKIT" db stats --db "$RUN_DIR/merged.sqlite" --json >"$RUN_DIR/merged.json.tmp"
mv -f "$RUN_DIR/merged.json.tmp" "$RUN_DIR/merged.json"
number() { { grep -o "\"$1\":[0-9]*" "$RUN_DIR/merged.json" || true; } | head -n 1 | cut -d: -f2; }
rows=$(number solutions)             # solutions stored, each once (unique by solution hash)
orbits=$(number distinct_solutions)  # how many of them differ up to symmetry
echo "tilekit merge: $SHARDS shards merged into $RUN_DIR/merged.sqlite"
if grep -q '"digest":' "$dir/shard-0.done.json"; then  # aperiodic enumerate: sets and conversions
  echo "tilekit merge: $(number tilesets) tile sets and $(number conversions) conversions"
  exit 0
fi
echo "tilekit merge: the shards reported $sum solutions in all"
if [ "${rows:-0}" != "$sum" ]; then
  echo "tilekit merge: note: the database holds ${rows:-?} (a count-only mode stores none; see the shard logs)"
fi
echo "final count: ${rows:-?} distinct solutions (${orbits:-?} up to symmetry)"
