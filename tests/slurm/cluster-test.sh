#!/usr/bin/env bash
# End-to-end test of `tilekit cluster` on a real Slurm (issue 6). Needs root and a built
# build/tilekit; installs slurm-wlm and munge if missing and starts a single-node Slurm
# (scripts/slurm/local-slurm.sh) in a temporary directory, stopped by PID when the test ends.
#
#   bash tests/slurm/cluster-test.sh      # scripts/test.sh runs it after ctest
#
# Cases:
#  1. requeue: the 4-shard array enumerating the 203,520 C=2 Wang packings; one task is
#     requeued mid-run (scontrol requeue: SIGTERM -> checkpoint -> exit 3 -> resume); the
#     merge job (afterok) finishes; the merged database holds exactly 203,520 distinct
#     solutions and every shard task ended with exit 0.
#  2. twice: a requeue after a shard had finished, a second merge, and a merge that lists a
#     shard twice change nothing.
#  3. walltime: a shard with a 1-minute limit gets USR1 before the limit, checkpoints, exits 3,
#     requeues itself and resumes until it completes.
# Ends with the line "N passed, M failed"; exits 1 if any check failed or Slurm did not work.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
TK=${TILEKIT_BINARY:-$root/build/tilekit}
SLURM=$root/scripts/slurm/local-slurm.sh
DEADLINE=$((SECONDS + ${TILEKIT_SLURM_TEST_BUDGET:-280}))  # whole test < 5 minutes
passed=0
failed=0

log() { echo "slurm-test: $*"; }
check() {  # check DESCRIPTION COMMAND...
  local what=$1
  shift
  if "$@"; then
    passed=$((passed + 1))
    log "ok:   $what"
  else
    failed=$((failed + 1))
    log "FAIL: $what"
  fi
}
fatal() {
  log "FATAL: $*"
  failed=$((failed + 1))
  exit 1
}

[ "$(id -u)" -eq 0 ] || fatal "needs root (it starts munged, slurmctld and slurmd)"
[ -x "$TK" ] || fatal "$TK is not built (run scripts/build.sh)"
"$SLURM" install

work=$(mktemp -d /tmp/tilekit-slurm-test.XXXXXX)
finish() {
  local rc=$?
  if ((failed > 0 || rc != 0)); then
    for f in "$work"/slurm/log/slurmctld.log "$work"/slurm/log/slurmd.log "$work"/*/logs/*.out; do
      [ -f "$f" ] && { echo "---- $f (last 25 lines)"; tail -n 25 "$f"; }
    done
  fi
  "$SLURM" stop "$work/slurm" || true
  rm -rf "$work"
  echo "$passed passed, $failed failed"
  ((failed == 0 && rc == 0)) || exit 1
}
trap finish EXIT
"$SLURM" start "$work/slurm" || fatal "Slurm did not start"
# shellcheck disable=SC1091
source "$work/slurm/env"

# ---- helpers reading Slurm's view of a job --------------------------------------------------
field() { scontrol -o show job "$1" 2>/dev/null | grep -o " $2=[^ ]*" | head -n 1 | cut -d= -f2-; }
time_left() { echo $((DEADLINE - SECONDS)); }
# Waits until job $1 reaches a final state; prints it. Fails on the test's deadline or when a
# dependency can never be satisfied.
wait_final() {
  local state reason
  while :; do
    state=$(field "$1" JobState)
    reason=$(field "$1" Reason)
    case $state in
      COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | BOOT_FAIL | DEADLINE | PREEMPTED)
        echo "$state"
        return 0 ;;
    esac
    [ "$reason" != DependencyNeverSatisfied ] || { echo "NEVER($reason)"; return 0; }
    (($(time_left) > 0)) || { echo "TIMEOUT-OF-TEST($state)"; return 0; }
    sleep 1
  done
}
json_field() { grep -o "\"$2\":[^,}]*" "$1" | head -n 1 | cut -d: -f2; }
attempt_exits() { grep -o '"exit":[0-9]*' "$1" | cut -d: -f2 | tr '\n' ' ' | sed 's/ $//'; }
last_attempt_resumed() { tail -n 1 "$1" | grep -q '"resumed":true'; }

# ---- 1. requeue one task mid-run ------------------------------------------------------------
run1=$work/wang2
log "case 1: 4-shard enumeration of the C=2 Wang packings, one task requeued mid-run"
out=$("$TK" cluster submit --kind wang --colors 2 --mode all --method search --shards 4 --cpus-per-task 1 \
  --time 10 --checkpoint-every 1 --run-dir "$run1" --json) || fatal "cluster submit failed"
array=$(echo "$out" | grep -o '"array_job":"[0-9]*"' | grep -o '[0-9]*')
merge=$(echo "$out" | grep -o '"merge_job":"[0-9]*"' | grep -o '[0-9]*')
[ -n "$array" ] && [ -n "$merge" ] || fatal "no job ids in: $out"
check "the merge job depends on the array (afterok)" \
  test "$(field "$merge" Dependency)" = "afterok:${array}_*(unfulfilled)"

# Requeue the first shard seen running with tilekit mid-run (its checkpoint written, no result).
victim=""
while [ -z "$victim" ] && (($(time_left) > 0)); do
  for i in 0 1 2 3; do
    if [ "$(field "${array}_$i" JobState)" = RUNNING ] && [ -s "$run1/shards/shard-$i.ckpt" ] &&
      [ ! -e "$run1/shards/shard-$i.done.json" ]; then
      victim=$i
      break
    fi
  done
  [ -n "$victim" ] || sleep 0.2
done
[ -n "$victim" ] || fatal "no shard was seen running with a checkpoint"
log "requeueing task ${array}_$victim mid-run"
scontrol requeue "${array}_$victim" || fatal "scontrol requeue ${array}_$victim failed"

state=$(wait_final "$merge")
check "the merge job completed (state $state)" test "$state" = COMPLETED
check "the merge job exited 0" test "$(field "$merge" ExitCode)" = 0:0
for i in 0 1 2 3; do
  check "shard task $i completed with exit 0 ($(field "${array}_$i" JobState) $(field "${array}_$i" ExitCode))" \
    test "$(field "${array}_$i" JobState) $(field "${array}_$i" ExitCode)" = "COMPLETED 0:0"
  check "shard $i's last attempt ended with exit 0" \
    test "$(attempt_exits "$run1/shards/shard-$i.attempts" | awk '{print $NF}')" = 0
done
exits=$(attempt_exits "$run1/shards/shard-$victim.attempts")
check "the requeued shard $victim checkpointed and exited 3, then 0 (exits: $exits)" test "$exits" = "3 0"
check "the requeued shard $victim's last attempt resumed from its checkpoint" \
  last_attempt_resumed "$run1/shards/shard-$victim.attempts"
check "Slurm counted the requeue (Restarts=$(field "${array}_$victim" Restarts))" \
  test "$(field "${array}_$victim" Restarts)" -ge 1
distinct=$(json_field "$run1/merged.json" distinct_solutions)
check "the merged database holds 203520 distinct solutions (got $distinct)" test "$distinct" = 203520
check "the merge log prints the final count" grep -q "final count: 203520 distinct solutions" "$run1"/logs/merge-*.out
status=$("$TK" cluster status --run-dir "$run1" --json)
check "cluster status: 4 shards done, merged 203520" \
  bash -c "grep -q '\"done\":4' <<<'$status' && grep -q '\"merged_distinct_solutions\":203520' <<<'$status'"

# ---- 2. a shard counted twice changes nothing ------------------------------------------------
log "case 2: a finished shard requeued, merged again, and listed twice in a merge"
scontrol requeue "${array}_0" || fatal "scontrol requeue of finished task ${array}_0 failed"
again=$(sbatch --parsable --dependency="afterok:${array}_0" "$run1/merge.sbatch")
state=$(wait_final "$again")
check "the second merge completed after the requeued shard ($state)" test "$state" = COMPLETED
check "the requeued finished shard ended with exit 0 again" \
  test "$(field "${array}_0" JobState) $(field "${array}_0" ExitCode)" = "COMPLETED 0:0"
distinct=$(json_field "$run1/merged.json" distinct_solutions)
check "after the second merge: still 203520 distinct solutions (got $distinct)" test "$distinct" = 203520
"$TK" db merge "$work/twice.sqlite" "$run1"/shards/shard-{0,1,2,3}.sqlite "$run1/shards/shard-0.sqlite" >/dev/null
twice=$("$TK" db stats --db "$work/twice.sqlite" --json)
check "a merge listing shard 0 twice holds 203520 distinct solutions" \
  bash -c "grep -q '\"distinct_solutions\":203520' <<<'$twice'"
check "... and 203520 solutions in all" bash -c "grep -q '\"solutions\":203520' <<<'$twice'"

# ---- 3. wall-time limit: USR1 -> checkpoint -> exit 3 -> requeue -> resume -------------------
run3=$work/walltime
log "case 3: a shard longer than its 1-minute limit (USR1 at most 50+60 s before it)"
out=$("$TK" cluster submit --kind wang --colors 2 --mode all --method search --shards 1 --cpus-per-task 1 \
  --time 1 --signal-seconds 50 --checkpoint-every 5 --max-requeues 4 --run-dir "$run3" \
  --pack-arg=--slow-down --json) || fatal "cluster submit (wall time) failed"
array3=$(echo "$out" | grep -o '"array_job":"[0-9]*"' | grep -o '[0-9]*')
merge3=$(echo "$out" | grep -o '"merge_job":"[0-9]*"' | grep -o '[0-9]*')
state=$(wait_final "$merge3")
check "the wall-time run's merge completed ($state)" test "$state" = COMPLETED
exits=$(attempt_exits "$run3/shards/shard-0.attempts")
check "the shard was stopped at least once with exit 3 and ended with 0 (exits: $exits)" \
  bash -c "[[ '$exits' == 3*' 0' ]]"
check "the shard got USR1 from Slurm before its limit" grep -q "got SIGUSR1" "$run3"/logs/pack-*_0.out
check "the shard requeued itself" grep -q "requeueing this task to resume" "$run3"/logs/pack-*_0.out
check "its last attempt resumed from the checkpoint" last_attempt_resumed "$run3/shards/shard-0.attempts"
check "Slurm counted the requeues (Restarts=$(field "${array3}_0" Restarts))" \
  test "$(field "${array3}_0" Restarts)" -ge 1
check "the task ended COMPLETED 0:0" \
  test "$(field "${array3}_0" JobState) $(field "${array3}_0" ExitCode)" = "COMPLETED 0:0"
distinct=$(json_field "$run3/merged.json" distinct_solutions)
check "the resumed single shard found all 203520 solutions (got $distinct)" test "$distinct" = 203520
