#!/usr/bin/env bash
# End-to-end test of `tilekit cluster submit --mpi` on a real Slurm: one MPI job whose ranks
# `srun --mpi=pmix` starts inside the allocation. Needs root, a build/tilekit built with MPI and
# the machine's one Slurm (scripts/test.sh runs it after cluster-test.sh, under the same lock):
#
#   flock /tmp/tilekit-slurm.lock bash tests/slurm/mpi-submit-test.sh
#
# Cases:
#  1. srun (PMIx): the C=2 Wang count on 2 ranks counts 203,520 (538 orbits), complete; rank 1
#     wrote its own checkpoint; `cluster status --json` reads the run as one MPI job, done.
#  2. Checkpoint, requeue and resume on another number of ranks: the C=3 corner count under
#     t=(0,3) on 2 ranks (srun). USR1 to the batch script, as --signal=B:USR1 sends it
#     (every rank checkpoints, exit 3, the job requeues itself); the requeued attempt resumes and
#     is cancelled (scancel: checkpoint, exit 3, no requeue); `cluster submit` again with 1 rank
#     resumes from the merged rank files and completes: 303,264.
#  3. mpirun inside the allocation (--launcher mpirun): the C=2 Wang count, 203,520.
#  4. Adaptive splitting of a job array (no MPI: `--split-after`, cluster/split.hpp): the C=2 Wang
#     count in 2 shards stopped after a quarter of the time the whole count takes here (a fixed
#     3 ms was eaten by a unit's first checkpoint under load: no unit got anything done, and
#     the rounds doubled without end); the merge job queues the split units as a
#     follow-up array and itself after it, and merges when nothing is left: 203,520.
# Ends with the line "N passed, M failed"; exits 1 if any check failed or Slurm did not work.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
log_name=slurm-mpi-test
DEADLINE=$((SECONDS + ${TILEKIT_SLURM_MPI_TEST_BUDGET:-420}))  # about 2 minutes on a quiet machine
# shellcheck source=tests/slurm/lib.sh
source "$root/tests/slurm/lib.sh"
# Slurm runs these jobs as root here; Open MPI refuses root unless told (the jobs inherit this).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d /tmp/tilekit-slurm-mpi-test.XXXXXX)
if "$TK" pack --mpi --kind wang --colors 1 --mode count --quiet --db "$work/probe.sqlite" 2>&1 | grep -q "without MPI"; then
  log "skipped: $TK was built without MPI"
  rm -rf "$work"
  echo "0 passed, 0 failed"
  exit 0
fi
start_slurm "$work"

# Waits until file $1 exists and was written after file $2 (or the deadline).
wait_newer() {
  while ! [ "$1" -nt "$2" ]; do
    (($(time_left) > 0)) || return 1
    sleep 0.2
  done
}
json_value() { { grep -o "\"$2\":[a-z0-9]*" "$1" 2>/dev/null || true; } | head -n 1 | cut -d: -f2; }
resumed_flags() { { grep -o '"resumed":[a-z]*' "$1" 2>/dev/null || true; } | cut -d: -f2 | tr '\n' ' ' | sed 's/ $//'; }
job_of() { { grep -o '"mpi_job":"[0-9]*"' <<<"$1" || true; } | { grep -o '[0-9][0-9]*' || true; }; }
equals() { [ "$1" = "$2" ] || { log "  got '$1', expected '$2'"; return 1; }; }

# ---- 1. srun --mpi=pmix: the C=2 Wang count on 2 ranks ---------------------------------------
r1=$work/wang2
out=$("$TK" cluster submit --mpi --ntasks 2 --kind wang --colors 2 --time 5 --run-dir "$r1" --json)
j1=$(job_of "$out")
[ -n "$j1" ] || fatal "submit printed no job id: $out"
log "case 1: MPI job $j1 (srun --mpi=pmix, 2 ranks)"
check "1: the MPI job completed (srun --mpi=pmix, 2 ranks)" equals "$(wait_final "$j1")" COMPLETED
check "1: 203520 solutions" equals "$(json_value "$r1/shards/shard-0.done.json" solutions)" 203520
check "1: 538 orbits" equals "$(json_value "$r1/shards/shard-0.done.json" orbits)" 538
check "1: complete" equals "$(json_value "$r1/shards/shard-0.done.json" complete)" true
check "1: rank 1 wrote its own checkpoint" test -s "$r1/shards/shard-0.ckpt.rank-1"
check "1: the ranks were started by srun --mpi=pmix" grep -q "starting (resume: false): srun --mpi=pmix --ntasks=2" \
  "$r1"/logs/pack-mpi-"$j1".out
st=$("$TK" cluster status --run-dir "$r1" --json)
st=$(tr -d ' \n' <<<"$st")
check "1: cluster status reads one MPI job of 2 ranks, done" \
  bash -c '[[ $1 == *\"mpi_ranks\":2,* && $1 == *\"done\":1,* ]]' _ "$st"

# ---- 2. USR1 -> checkpoint -> requeue -> resume; scancel; resubmitted on 1 rank --------------
r2=$work/corner3
args=(--kind corner --colors 3 --pack-arg=--impose=t=0,3:pi=1,2,0 --checkpoint-every 1 --time 10 --run-dir "$r2")
out=$("$TK" cluster submit --mpi --ntasks 2 "${args[@]}" --json)
j2=$(job_of "$out")
[ -n "$j2" ] || fatal "submit printed no job id: $out"
log "case 2: MPI job $j2 (the C=3 corner count, 2 ranks)"
mkdir -p "$r2/shards"
touch "$work/mark0"
if wait_newer "$r2/shards/shard-0.ckpt.rank-1" "$work/mark0"; then
  sleep 2
  scancel --signal=USR1 --batch "$j2"
  # the requeued attempt: its restart count goes to 1, then its ranks write again
  while [ "$(field "$j2" Restarts)" != 1 ] && (($(time_left) > 0)); do sleep 0.2; done
  touch "$work/mark1"
  while [ "$(field "$j2" JobState)" != RUNNING ] && (($(time_left) > 0)); do sleep 0.2; done
  wait_newer "$r2/shards/shard-0.ckpt.rank-1" "$work/mark1" || true
  sleep 2
  scancel "$j2"
else
  log "rank 1 of job $j2 wrote no checkpoint"
fi
check "2: the cancelled job ended CANCELLED" equals "$(wait_final "$j2")" CANCELLED
check "2: two attempts, both checkpointed (exit 3)" equals "$(attempt_exits "$r2/shards/shard-0.attempts")" "3 3"
check "2: the requeued attempt resumed" equals "$(resumed_flags "$r2/shards/shard-0.attempts")" "false true"
check "2: no result yet" test ! -e "$r2/shards/shard-0.done.json"
st=$("$TK" cluster status --run-dir "$r2" --json)
check "2: cluster status shows the checkpointed run" grep -q '"checkpointed":1' <<<"$(tr -d ' \n' <<<"$st")"
out=$("$TK" cluster submit --mpi --ntasks 1 "${args[@]}" --json)
j3=$(job_of "$out")
log "case 2: resubmitted as MPI job $j3 (1 rank)"
check "2: the resubmitted job (1 rank) completed" equals "$(wait_final "$j3")" COMPLETED
check "2: 303264 solutions after two checkpoints and a resume on 1 rank" \
  equals "$(json_value "$r2/shards/shard-0.done.json" solutions)" 303264
check "2: complete" equals "$(json_value "$r2/shards/shard-0.done.json" complete)" true
check "2: exits 3 3 0, the last two attempts resumed" equals \
  "$(attempt_exits "$r2/shards/shard-0.attempts")/$(resumed_flags "$r2/shards/shard-0.attempts")" "3 3 0/false true true"

# ---- 3. mpirun inside the allocation -----------------------------------------------------------
r3=$work/wang2-mpirun
out=$("$TK" cluster submit --mpi --ntasks 2 --launcher mpirun --kind wang --colors 2 --time 5 --run-dir "$r3" --json)
j4=$(job_of "$out")
log "case 3: MPI job $j4 (mpirun, 2 ranks)"
check "3: the MPI job completed (mpirun)" equals "$(wait_final "$j4")" COMPLETED
check "3: 203520 solutions" equals "$(json_value "$r3/shards/shard-0.done.json" solutions)" 203520
check "3: the ranks were started by mpirun" grep -q "starting (resume: false): mpirun -np 2" "$r3"/logs/pack-mpi-"$j4".out

# ---- 4. adaptive splitting of a job array: follow-up arrays queued by the merge job ------------
r4=$work/wang2-split
whole=""  # the fastest of three counts (as tests/cluster/split-test.sh)
for k in 1 2 3; do
  t=$("$TK" pack --kind wang --colors 2 --mode count --threads 1 --json --db "$work/probe4-$k.sqlite" 2>/dev/null |
    grep -o '"seconds":[0-9.eE+-]*' | head -n 1 | cut -d: -f2)
  [ -n "$t" ] && whole=$(awk -v a="$t" -v b="${whole:-$t}" 'BEGIN { print (a < b ? a : b) }')
done
after4=$(awk -v t="${whole:-0.012}" 'BEGIN { a = t / 4; if (a < 0.003) a = 0.003; printf "%.4f", a }')
out=$("$TK" cluster submit --kind wang --colors 2 --mode count --shards 2 --split-after "$after4" --split-ways 2 \
  --time 5 --run-dir "$r4" --json)
m4=$({ grep -o '"merge_job":"[0-9]*"' <<<"$out" || true; } | { grep -o '[0-9][0-9]*' || true; })
log "case 4: split run (shards stopped after $after4 s), first merge job $m4"
check "4: the first merge job completed" equals "$(wait_final "$m4")" COMPLETED
# The last merge job is the one whose log says it merged.
while ! grep -qs "the shards reported" "$r4"/logs/merge-*.out && (($(time_left) > 0)); do sleep 1; done
check "4: round 1 of split units ran" test -s "$r4/units/round-1.tsv"
check "4: the merge job queued the follow-up array and merged at the end" \
  grep -qs "the shards reported 203520 solutions in all" "$r4"/logs/merge-*.out
sum4=$(cat "$r4"/shards/shard-0.done.json "$r4"/shards/shard-1.done.json 2>/dev/null | grep -o '"solutions":[0-9]*' |
  cut -d: -f2 | paste -sd+ | bc)
check "4: 203520 solutions from the split shards' results" equals "${sum4:-}" 203520
