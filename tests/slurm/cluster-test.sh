#!/usr/bin/env bash
# End-to-end test of `tilekit cluster` on a real Slurm. Needs root and a built
# build/tilekit; installs slurm-wlm and munge if missing and starts a single-node Slurm
# (scripts/slurm/local-slurm.sh) in a temporary directory, stopped by PID when the test ends.
#
#   bash tests/slurm/cluster-test.sh      # scripts/test.sh runs it after ctest
#
# Cases (3 is queued first so that it runs beside 1 and 2):
#  1. The 4-shard array enumerating the 203,520 C=2 Wang packings. A shard searches for well
#     under a second, so the test stops (SIGSTOP) one shard's tilekit inside its search and has
#     Slurm requeue the task (SIGTERM -> checkpoint -> exit 3 -> Slurm requeues -> resume), and
#     does the same with USR1 to another task's batch script, as --signal=B:USR1 does (USR1 ->
#     checkpoint -> exit 3 -> the task requeues itself -> resume). The merge job (afterok)
#     finishes; the merged database holds exactly 203,520 solutions (and as many orbits as an
#     unsharded count), and every shard task ended COMPLETED with exit 0.
#  2. A shard counted twice changes nothing: a finished task requeued, a second merge, and a
#     merge that lists a shard twice.
#  3. Wall time: one shard of a search far longer than its 1-minute limit (counting the C=3
#     corner packings). Slurm's USR1 comes before the limit, tilekit checkpoints and exits 3,
#     the task requeues itself and the next attempt resumes (its counts and time go on from the
#     first); at the requeue bound (1) the task ends with exit 3.
#  4. Resuming the whole run: the same `cluster submit` again resumes from the checkpoint; a
#     scancel then ends it for good (checkpoint, exit 3, no requeue).
#  5. An imposed-group count as an array: the C=3 Wang packings invariant under a
#     group of order 9, 3 shards, one task requeued mid-search (SIGTERM -> checkpoint -> exit 3
#     -> Slurm requeues -> resume); the shards' counts add up to an unsharded count.
#  6. aperiodic enumerate as a 3-shard array, one shard requeued mid-run; the merged
#     shard databases hold exactly the sets and conversions of an unsharded run.
# Ends with the line "N passed, M failed"; exits 1 if any check failed or Slurm did not work.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
log_name=slurm-test
DEADLINE=$((SECONDS + ${TILEKIT_SLURM_TEST_BUDGET:-280}))  # whole test < 5 minutes
# shellcheck source=tests/slurm/lib.sh
source "$root/tests/slurm/lib.sh"
start_slurm "$(mktemp -d /tmp/tilekit-slurm-test.XXXXXX)"

# ---- helpers ----------------------------------------------------------------------------------
submitted_id() { { grep -o "\"$1\":\"[0-9]*\"" <<<"$2" || true; } | { grep -o '[0-9][0-9]*' || true; }; }
json_number() { { grep -o "\"$2\":[0-9]*" "$1" 2>/dev/null || true; } | head -n 1 | cut -d: -f2; }
last_attempt_resumed() { tail -n 1 "$1" | grep -q '"resumed":true'; }
# Bit $2 (a mask) of field $3 (SigCgt, SigPnd, ShdPnd) in /proc/$1/status.
proc_mask() {
  local key mask
  while read -r key mask; do
    [ "$key" = "$3:" ] && { (((16#$mask & $2) == $2)); return; }
  done <"/proc/$1/status"
  return 1
}
USR1_BIT=0x200 TERM_BIT=0x4000
TK_EXE=$(readlink -f "$TK")
# "PID SHARD" of each tilekit of run directory $1 that already catches USR1 and TERM (so it is
# inside its search, where a signal means checkpoint and exit 3). Only shell builtins: a shard
# searches for well under a second, so this must be quick.
searching_tilekits() {
  local d i shard ckpt args
  for d in /proc/[0-9]*; do
    [ "$d/exe" -ef "$TK_EXE" ] || continue
    mapfile -d '' args <"$d/cmdline" 2>/dev/null || continue
    shard="" ckpt=""
    for ((i = 0; i + 1 < ${#args[@]}; i++)); do
      case ${args[i]} in --shard) shard=${args[i + 1]%/*} ;; --checkpoint) ckpt=${args[i + 1]} ;; esac
    done
    [[ "$ckpt" == "$1/shards/"* ]] || continue
    proc_mask "${d#/proc/}" $((USR1_BIT | TERM_BIT)) SigCgt 2>/dev/null && echo "${d#/proc/} $shard"
  done
}
# Waits (up to 10 s) until stopped process $1 has signal bit $2 pending, then lets it go on.
# (Slurm's requeue sends SIGCONT itself before SIGTERM; then the process may be gone already.)
continue_with_pending() {
  local t
  for ((t = 0; t < 200; t++)); do
    [ -e "/proc/$1" ] || return 0
    if proc_mask "$1" "$2" ShdPnd 2>/dev/null || proc_mask "$1" "$2" SigPnd 2>/dev/null; then break; fi
    sleep 0.05
  done
  kill -CONT "$1" 2>/dev/null || true
}

# ---- 3 (queued first, checked last): wall-time limit -> USR1 -> checkpoint -> exit 3 -> requeue ----
# Counting the C=3 corner packings takes far longer than any attempt, so every attempt ends at
# its 1-minute limit: USR1 (50 s, to 60 s more, before it), checkpoint, exit 3, self-requeue;
# the second attempt resumes and is stopped the same way, and then the requeue bound (1) ends it.
run3=$work/walltime
out3=$("$TK" cluster submit --kind corner --colors 3 --mode count --method search --shards 1 --cpus-per-task 1 \
  --time 1 --signal-seconds 50 --checkpoint-every 5 --max-requeues 1 --run-dir "$run3" --json) ||
  fatal "cluster submit (wall time) failed"
array3=$(submitted_id array_job "$out3")
merge3=$(submitted_id merge_job "$out3")
[ -n "$array3" ] && [ -n "$merge3" ] || fatal "no job ids in: $out3"
log "case 3 queued: array $array3 (1 shard, --time 1), merge $merge3"

# The C=2 Wang orbit count (packings up to symmetry) of one unsharded search, to compare with.
ORBITS=$("$TK" pack --kind wang --colors 2 --mode count --method search --threads 1 --quiet --json |
  { grep -o '"orbits":[0-9]*' || true; } | cut -d: -f2)
[ -n "$ORBITS" ] || fatal "tilekit pack --mode count printed no orbit count"

# ---- 1. one task requeued and one sent USR1 mid-run -------------------------------------------
run1=$work/wang2
log "case 1: 4-shard enumeration of the C=2 Wang packings; one task requeued, one sent USR1 mid-run"
t1=$SECONDS
out=$("$TK" cluster submit --kind wang --colors 2 --mode all --method search --shards 4 --cpus-per-task 1 \
  --time 10 --checkpoint-every 1 --run-dir "$run1" --json) || fatal "cluster submit failed"
array=$(submitted_id array_job "$out")
merge=$(submitted_id merge_job "$out")
[ -n "$array" ] && [ -n "$merge" ] || fatal "no job ids in: $out"
check "the jobs run the tilekit on PATH" grep -qF "\"tilekit\":\"$(readlink -f "$TK")\"" <<<"$out"
check "the merge job waits for the whole array (afterok)" \
  test "$(field "$merge" Dependency)" = "afterok:${array}_*(unfulfilled)"

# A C=2 shard searches for about a second, too short to hit by timing. So the test stops (SIGSTOP)
# a shard's tilekit once it is inside its search, has Slurm signal it, and lets it go on.
requeued="" usr1="" next_look=0
while { [ -z "$requeued" ] || [ -z "$usr1" ]; } && (($(time_left) > 0)); do
  pid="" shard=""
  while read -r p s; do
    [ "$s" = "$requeued" ] || { pid=$p shard=$s; break; }
  done < <(searching_tilekits "$run1")
  if [ -z "$pid" ]; then
    if ((SECONDS >= next_look)); then  # once a second: is any shard left to catch?
      [ "$(field "$merge" Reason)" = Dependency ] || break
      next_look=$((SECONDS + 1))
    fi
    sleep 0.01
    continue
  fi
  kill -STOP "$pid"
  # Signal the task by its own job id: Slurm refuses the ARRAY_TASK form ("can not be altered
  # now") while another task of the array waits to restart after a requeue.
  jid=$(field "${array}_$shard" JobId)
  if [ -z "$requeued" ]; then
    requeued=$shard
    log "shard $shard's tilekit (pid $pid) stopped mid-search; scontrol requeue $jid (${array}_$shard)"
    scontrol requeue "$jid" || fatal "scontrol requeue $jid failed"
    continue_with_pending "$pid" $TERM_BIT
  else
    usr1=$shard
    log "shard $shard's tilekit (pid $pid) stopped mid-search; USR1 to the batch script of $jid (as --signal=B:USR1 does)"
    scancel --batch --signal=USR1 "$jid" || fatal "scancel --signal=USR1 $jid failed"
    continue_with_pending "$pid" $USR1_BIT
  fi
done
[ -n "$requeued" ] && [ -n "$usr1" ] || fatal "could not catch two shards mid-search (caught: '$requeued' '$usr1')"

state=$(wait_final "$merge")
check "the merge job completed (state $state)" test "$state" = COMPLETED
check "the merge job exited 0" test "$(field "$merge" ExitCode)" = 0:0
for i in 0 1 2 3; do
  check "shard task $i ended COMPLETED with exit 0 ($(field "${array}_$i" JobState) $(field "${array}_$i" ExitCode))" \
    test "$(field "${array}_$i" JobState) $(field "${array}_$i" ExitCode)" = "COMPLETED 0:0"
done
for i in "$requeued" "$usr1"; do
  exits=$(attempt_exits "$run1/shards/shard-$i.attempts")
  check "shard $i checkpointed and exited 3, then resumed and exited 0 (exits: $exits)" test "$exits" = "3 0"
  check "shard $i's last attempt resumed from its checkpoint" last_attempt_resumed "$run1/shards/shard-$i.attempts"
  check "Slurm counted shard $i's requeue (Restarts=$(field "${array}_$i" Restarts))" \
    test "$(field "${array}_$i" Restarts)" -ge 1
done
check "the shard stopped by scontrol requeue did not requeue itself" \
  grep -q "on SIGTERM; not requeueing" "$run1"/logs/pack-*_"$requeued".out
check "the shard sent USR1 requeued itself" grep -q "requeueing this task to resume" "$run1"/logs/pack-*_"$usr1".out
for i in 0 1 2 3; do
  [ "$i" = "$requeued" ] || [ "$i" = "$usr1" ] || check "shard $i ran once and exited 0" \
    test "$(attempt_exits "$run1/shards/shard-$i.attempts")" = 0
done
# db stats: "solutions" = rows, each unique by solution hash; "distinct_solutions" = orbits.
rows=$(json_number "$run1/merged.json" solutions)
check "the merged database holds exactly 203520 solutions (got $rows)" test "$rows" = 203520
check "... 203520 distinct grids, all validated (plain sqlite3: distinct cells, validated rows)" \
  test "$(sqlite3 "$run1/merged.sqlite" "SELECT COUNT(DISTINCT cells) || ' ' || SUM(validated) FROM solutions
          WHERE kind = 'wang' AND colors = 2 AND rows = 4 AND cols = 4")" = "203520 203520"
orbits=$(json_number "$run1/merged.json" distinct_solutions)
check "... and as many orbits as one unsharded count finds ($orbits vs $ORBITS)" test "$orbits" = "$ORBITS"
check "the merge job printed the final count" grep -q "final count: 203520 distinct solutions" "$run1"/logs/merge-*.out
"$TK" cluster status --run-dir "$run1" --json >"$work/status1.json"
check "cluster status: 4 shards done, 203520 merged" \
  bash -c "grep -q '\"done\":4' '$work/status1.json' && grep -q '\"merged_solutions\":203520' '$work/status1.json'"
log "case 1 took $((SECONDS - t1)) s"

# ---- 2. a shard counted twice changes nothing -------------------------------------------------
log "case 2: a finished shard requeued, merged again, and listed twice in a merge"
scontrol requeue "$(field "${array}_0" JobId)" || fatal "scontrol requeue of the finished task ${array}_0 failed"
again=$(sbatch --parsable --dependency="afterok:${array}_0" "$run1/merge.sbatch")
state=$(wait_final "$again")
check "a second merge ran after the finished shard was requeued ($state)" test "$state" = COMPLETED
check "the requeued finished shard ended with exit 0 again" \
  test "$(field "${array}_0" JobState) $(field "${array}_0" ExitCode)" = "COMPLETED 0:0"
check "... without searching again (its result was there)" grep -q "already complete" "$run1"/logs/pack-*_0.out
rows=$(json_number "$run1/merged.json" solutions)
check "after the second merge: still 203520 solutions (got $rows)" test "$rows" = 203520
check "... and $ORBITS orbits" test "$(json_number "$run1/merged.json" distinct_solutions)" = "$ORBITS"
"$TK" db merge "$work/twice.sqlite" "$run1"/shards/shard-{0,1,2,3}.sqlite "$run1/shards/shard-0.sqlite" >/dev/null ||
  fatal "tilekit db merge with a shard listed twice failed"
"$TK" db stats --db "$work/twice.sqlite" --json >"$work/twice.json"
check "a merge listing shard 0 twice holds 203520 solutions" test "$(json_number "$work/twice.json" solutions)" = 203520
check "... and $ORBITS orbits" test "$(json_number "$work/twice.json" distinct_solutions)" = "$ORBITS"

# ---- 5. an imposed-group count, one task requeued mid-search ----------------------------------
GROUP='t=0,3:pi=1,2,0;t=3,0:piv=1,2,0'
log "case 5: 3-shard count under the group $GROUP; one task requeued mid-search"
t5=$SECONDS
WHOLE=$("$TK" pack --kind wang --colors 3 --mode count --impose "$GROUP" --threads 2 --quiet --json |
  { grep -o '"solutions":[0-9]*' || true; } | cut -d: -f2)
[ -n "$WHOLE" ] || fatal "the unsharded count under $GROUP printed no count"
run5=$work/group
out5=$("$TK" cluster submit --kind wang --colors 3 --mode count --method search --shards 3 --cpus-per-task 1 \
  --time 10 --checkpoint-every 1 --run-dir "$run5" --pack-arg="--impose=$GROUP" --json) || fatal "cluster submit (group) failed"
array5=$(submitted_id array_job "$out5")
merge5=$(submitted_id merge_job "$out5")
[ -n "$array5" ] && [ -n "$merge5" ] || fatal "no job ids in: $out5"
requeued5=""
while [ -z "$requeued5" ] && (($(time_left) > 0)); do
  pid="" shard=""
  read -r pid shard < <(searching_tilekits "$run5" | head -n 1) || true
  if [ -z "${pid:-}" ]; then
    [ "$(field "$merge5" Reason)" = Dependency ] || break
    sleep 0.01
    continue
  fi
  kill -STOP "$pid"
  jid=$(field "${array5}_$shard" JobId)
  requeued5=$shard
  log "group shard $shard's tilekit (pid $pid) stopped mid-search; scontrol requeue $jid"
  scontrol requeue "$jid" || fatal "scontrol requeue $jid failed"
  continue_with_pending "$pid" $TERM_BIT
done
[ -n "$requeued5" ] || fatal "could not catch a group shard mid-search"
state=$(wait_final "$merge5")
check "the group run's merge job completed ($state)" test "$state" = COMPLETED
exits=$(attempt_exits "$run5/shards/shard-$requeued5.attempts")
check "the requeued group shard checkpointed, exited 3, resumed and exited 0 (exits: $exits)" test "$exits" = "3 0"
check "... its last attempt resumed from the checkpoint" last_attempt_resumed "$run5/shards/shard-$requeued5.attempts"
sum5=$(grep -o "the shards reported [0-9]* solutions" "$run5"/logs/merge-*.out | grep -o '[0-9][0-9]*' | head -n 1)
check "the group shards' counts add up to the unsharded count (${sum5:-?} vs $WHOLE)" test "${sum5:-x}" = "$WHOLE"
for i in 0 1 2; do
  check "group shard $i reports the group (order 9)" grep -q '"order":9' "$run5/shards/shard-$i.done.json"
done
log "case 5 took $((SECONDS - t5)) s"

# ---- 6. aperiodic enumerate as a 3-shard array, one shard requeued mid-run: the merged database is
#      the unsharded run's ----
log "case 6: aperiodic enumerate, 3 shards, merged against an unsharded run"
t6=$SECONDS
ENUM_ARGS=(--max-depth 2 --max-tiles 40)
"$TK" aperiodic enumerate "${ENUM_ARGS[@]}" --threads 2 --db "$work/enum-whole.sqlite" --quiet --json >/dev/null ||
  fatal "the unsharded enumerate failed"
run6=$work/enumerate
out6=$("$TK" cluster submit --command enumerate --shards 3 --cpus-per-task 1 --time 10 --checkpoint-every 1 \
  --run-dir "$run6" --pack-arg=--max-depth=2 --pack-arg=--max-tiles=40 --json) || fatal "cluster submit (enumerate) failed"
array6=$(submitted_id array_job "$out6")
merge6=$(submitted_id merge_job "$out6")
[ -n "$array6" ] && [ -n "$merge6" ] || fatal "no job ids in: $out6"
# One shard is stopped once it catches signals and requeued (SIGTERM -> checkpoint -> exit 3 ->
# Slurm requeues -> resume), as in case 1.
requeued6=""
while [ -z "$requeued6" ] && (($(time_left) > 0)) && [ "$(field "$merge6" Reason)" = Dependency ]; do
  read -r pid shard < <(searching_tilekits "$run6") || { sleep 0.01; continue; }
  kill -STOP "$pid"
  requeued6=$shard
  jid=$(field "${array6}_$shard" JobId)
  log "enumerate shard $shard's tilekit (pid $pid) stopped; scontrol requeue $jid (${array6}_$shard)"
  scontrol requeue "$jid" || fatal "scontrol requeue $jid failed"
  continue_with_pending "$pid" $TERM_BIT
done
[ -n "$requeued6" ] || fatal "could not catch an enumerate shard running"
state=$(wait_final "$merge6")
check "the enumerate run's merge job completed ($state)" test "$state" = COMPLETED
exits=$(attempt_exits "$run6/shards/shard-$requeued6.attempts")
check "enumerate shard $requeued6 checkpointed and exited 3, then resumed and exited 0 (exits: $exits)" \
  test "$exits" = "3 0"
check "enumerate shard $requeued6's last attempt resumed from its checkpoint" \
  last_attempt_resumed "$run6/shards/shard-$requeued6.attempts"
check "the merge job counted the sets and conversions" grep -q "tile sets and .* conversions" "$run6"/logs/merge-*.out
rows() {
  sqlite3 "$1" "SELECT 'set ' || content_hash FROM tilesets UNION ALL SELECT 'conv ' || s.content_hash || ' ' ||
    c.method || ' ' || r.content_hash || ' ' || c.soundness FROM conversions c JOIN tilesets s ON s.id = c.source_set
    JOIN tilesets r ON r.id = c.result_set" | sort
}
check "the merged shard databases hold exactly the unsharded run's sets and conversions" \
  diff <(rows "$run6/merged.sqlite") <(rows "$work/enum-whole.sqlite")
log "case 6 took $((SECONDS - t6)) s"

# ---- 3. checked now ---------------------------------------------------------------------------
log "case 3: waiting for the wall-time run ($(time_left) s left)"
state=$(wait_final "${array3}_0")
log3=$(ls "$run3"/logs/pack-*_0.out 2>/dev/null | head -n 1)
log3=${log3:-/dev/null}
exits=$(attempt_exits "$run3/shards/shard-0.attempts")
check "both attempts of the wall-time shard checkpointed and exited 3 (exits: $exits)" test "$exits" = "3 3"
check "Slurm sent USR1 before the limit in both attempts" test "$(grep -c "got SIGUSR1" "$log3")" = 2
check "the first attempt requeued itself" grep -q "attempt 0): checkpointed .*requeueing this task to resume" "$log3"
check "the second attempt resumed from the checkpoint" last_attempt_resumed "$run3/shards/shard-0.attempts"
line_number() { { grep -o "\"$2\":[0-9.eE+-]*" <<<"$1" || true; } | head -n 1 | cut -d: -f2; }
a0=$(sed -n 1p "$run3/shards/shard-0.attempts")
a1=$(sed -n 2p "$run3/shards/shard-0.attempts")
T0=$(line_number "$a0" total_seconds) s1=$(line_number "$a1" seconds) T1=$(line_number "$a1" total_seconds)
check "the second attempt went on from the first: its total time ${T1:-?} s = ${T0:-?} s before + ${s1:-?} s now" \
  awk -v T0="${T0:-0}" -v s1="${s1:-0}" -v T1="${T1:-0}" 'BEGIN { exit !(T0 > 1 && s1 > 1 && T1 - s1 > T0 - 1 && T1 - s1 < T0 + 1) }'
S0=$(line_number "$a0" solutions) S1=$(line_number "$a1" solutions)
check "its count went on from the first's (${S0:-?} then ${S1:-?} solutions)" \
  awk -v a="${S0:-0}" -v b="${S1:-0}" 'BEGIN { exit !(a > 0 && b > a) }'
"$TK" cluster status --run-dir "$run3" --json >"$work/status3.json"
check "cluster status reads the checkpoint's progress (${S1:-?} solutions so far)" \
  grep -q "\"solutions\":${S1:-x}," "$work/status3.json"
check "the second attempt stopped at the requeue bound" grep -q "requeue bound (1) is reached" "$log3"
check "Slurm counted one requeue (Restarts=$(field "${array3}_0" Restarts))" test "$(field "${array3}_0" Restarts)" = 1
check "the task ended with exit 3 at the bound ($state $(field "${array3}_0" ExitCode))" \
  test "$state $(field "${array3}_0" ExitCode)" = "FAILED 3:0"
check "its merge job will never run (afterok not met)" \
  test "$(field "$merge3" Reason)" = DependencyNeverSatisfied
scancel "$merge3" || true

# ---- 4. resuming a whole run: the same submit again; then scancel ends it for good ------------
log "case 4: the wall-time run submitted again (resume the whole run), then cancelled"
# A wall time of 5 minutes, not case 3's 1: Slurm sends the USR1 warning from a periodic check,
# and in one CI run it came 0.4 s after the start (not 10 s or later): the task checkpointed and
# requeued itself before the scancel below. Only the shards and pack arguments must match case 3's.
out4=$("$TK" cluster submit --kind corner --colors 3 --mode count --method search --shards 1 --cpus-per-task 1 \
  --time 5 --signal-seconds 50 --checkpoint-every 5 --max-requeues 1 --run-dir "$run3" --json) ||
  fatal "the second cluster submit into $run3 failed"
array4=$(submitted_id array_job "$out4")
check "the run directory now records two submissions" grep -q '"submissions":2' <<<"$out4"
while ! grep -q "attempt 0): starting (resume: true" "$run3"/logs/pack-"$array4"_0.out 2>/dev/null &&
  (($(time_left) > 0)); do sleep 0.5; done
check "the resubmitted shard resumed from the run's checkpoint" \
  grep -q "attempt 0): starting (resume: true" "$run3"/logs/pack-"$array4"_0.out
for ((t = 0; t < 100; t++)); do  # let tilekit get into its search before the cancel
  [ -n "$(searching_tilekits "$run3")" ] && break
  sleep 0.1
done
scancel "$array4" || fatal "scancel $array4 failed"
state=$(wait_final "${array4}_0")
check "after scancel the task stays cancelled ($state, Restarts=$(field "${array4}_0" Restarts))" \
  test "$state $(field "${array4}_0" Restarts)" = "CANCELLED 0"
check "... and tilekit checkpointed on SIGTERM without requeueing" \
  grep -q "on SIGTERM; not requeueing" "$run3"/logs/pack-"$array4"_0.out
