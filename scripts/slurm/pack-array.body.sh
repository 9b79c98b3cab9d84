# ---- body of the shard array task (scripts/slurm/pack-array.body.sh) ----
# Expects, set above by `tilekit cluster submit`: TILEKIT (the binary), RUN_DIR (on the shared
# filesystem), SHARDS, MAX_REQUEUES, CHECKPOINT_EVERY, SPLIT_AFTER and the arrays COMMAND (`pack` or
# `aperiodic enumerate`) and PACK_ARGS (its arguments).
#
# One array task = one shard I of N (I = SLURM_ARRAY_TASK_ID). Each shard owns its files:
#   RUN_DIR/shards/shard-I.ckpt       checkpoint (written every CHECKPOINT_EVERY s and on a signal)
#   RUN_DIR/shards/shard-I.sqlite     its own SQLite database (never shared between tasks:
#                                     SQLite over NFS is not safe for concurrent writers)
#   RUN_DIR/shards/shard-I.attempts   one JSON line per attempt: exit code, resumed or not, and
#                                     tilekit's counts (total_seconds includes earlier attempts)
#   RUN_DIR/shards/shard-I.done.json  `tilekit pack --json` output once the shard is complete
#   RUN_DIR/shards/shard-I.stats.json the portfolio statistics of a first-mode run (the merge job
#                                     adds them up into RUN_DIR/portfolio-stats.json)
# Signals: Slurm sends USR1 to this script (--signal=B:USR1@S) S seconds before the wall-time
# kill; it is forwarded to tilekit, which writes its checkpoint and exits 3. The task then
# requeues itself (scontrol requeue) and its next attempt resumes from the checkpoint; at most
# MAX_REQUEUES times (SLURM_RESTART_COUNT counts every requeue of this task, whoever asked).
# SIGTERM (scancel, scontrol requeue, preemption, a limit reached without warning) also makes
# tilekit checkpoint and exit 3, but the task does not requeue itself then: a cancelled run
# stays cancelled, and Slurm brings back a requeued or preempted one by itself.
set -uo pipefail

task_index=${SLURM_ARRAY_TASK_ID:?"submit this script with sbatch --array=0-$((SHARDS - 1))"}
task="${SLURM_ARRAY_JOB_ID:-$SLURM_JOB_ID}_${task_index}"
attempt=${SLURM_RESTART_COUNT:-0}
export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}
# A split run (SPLIT_AFTER > 0, cluster/split.hpp): round 0 is this array (task I = shard I);
# round R >= 1 (sbatch --array=0-(U-1) pack-array.sbatch R, queued by the merge job) runs
# the units of RUN_DIR/units/round-R.tsv, task T = line T+1 "SHARD PART PARTS".
round=${1:-0}
dir="$RUN_DIR/shards"
if ((round > 0)); then
  unit_line=$(sed -n "$((task_index + 1))p" "$RUN_DIR/units/round-$round.tsv")
  read -r shard part parts <<<"$unit_line"
  [ -n "${parts:-}" ] || { echo "no unit $task_index in $RUN_DIR/units/round-$round.tsv" >&2; exit 2; }
  unit=$((round * 10000000 + task_index))  # cluster/split.hpp, unit_id()
  # The unit resumes from the shard's checkpoint merged with every part's file beside it, and
  # writes its own such file (shard-I.ckpt.rank-UNIT): `pack --part` (cluster/part_work.hpp).
  resume_from="$dir/shard-$shard.ckpt"
  ckpt="$resume_from.rank-$unit"
  db="$dir/shard-$shard.part-$unit.sqlite"
  done_file="$dir/shard-$shard.part-$unit.json"
  attempts="$dir/shard-$shard.part-$unit.attempts"
else
  shard=$task_index
  ckpt="$dir/shard-$shard.ckpt"
  db="$dir/shard-$shard.sqlite"
  done_file="$dir/shard-$shard.done.json"
  attempts="$dir/shard-$shard.attempts"
fi
split_file="$dir/shard-$shard.split.json"
stats="$dir/shard-$shard.stats.json"

say() { printf '%s tilekit shard %s/%s%s (task %s, attempt %s): %s\n' "$(date -u +%FT%TZ)" \
  "$shard" "$SHARDS" "$( ((round == 0)) || echo " part $part/$parts, round $round")" "$task" "$attempt" "$*"; }
# A number from tilekit's one-line JSON result $2 (null if absent).
number() { local v; v=$(grep -o "\"$1\":[0-9.eE+-]*" "$2" 2>/dev/null | head -n 1 | cut -d: -f2); echo "${v:-null}"; }
record() {  # record EXIT RESUMED [RESULT_JSON]: one line per attempt in shard-I.attempts
  local r=${3:-/dev/null}
  printf '{"time":"%s","job":"%s","attempt":%s,"exit":%s,"resumed":%s,"host":"%s","solutions":%s,"nodes":%s,"seconds":%s,"total_seconds":%s}\n' \
    "$(date -u +%FT%TZ)" "$task" "$attempt" "$1" "$2" "$(hostname -s)" "$(number solutions "$r")" \
    "$(number nodes "$r")" "$(number seconds "$r")" "$(number total_seconds "$r")" >>"$attempts"
}

# Slurm's signals may come at any moment, even before tilekit runs: take them from the start.
pid=""        # tilekit
ready=false   # tilekit catches USR1 and TERM (an uncaught USR1 would kill it without a checkpoint)
pending=""    # a signal that came before that, passed on once it does
warned=false  # USR1 = our wall-time warning; TERM = Slurm ends the job (scancel, requeue, preemption)
on_signal() {
  [ "$1" != USR1 ] || warned=true
  if [ "$ready" = true ]; then
    say "got SIG$1; asking tilekit (pid $pid) to checkpoint and stop"
    kill -s "$1" "$pid" 2>/dev/null || true
  else
    say "got SIG$1 before tilekit catches signals; passing it on when it does"
    pending=$1
  fi
}
trap 'on_signal USR1' USR1
trap 'on_signal TERM' TERM

mkdir -p "$dir"

# A requeue after the shard had finished (or a resubmitted run) must not count it twice.
if [ -s "$done_file" ] || { ((round == 0)) && [ -s "$split_file" ]; }; then
  say "already complete or split ($done_file); nothing to do"
  record 0 false
  exit 0
fi

args=("${PACK_ARGS[@]}" --threads "$OMP_NUM_THREADS" --shard "$shard/$SHARDS"
      --checkpoint "$ckpt" --checkpoint-every "$CHECKPOINT_EVERY" --db "$db" --json)
[ "${COMMAND[*]}" != pack ] || ((round > 0)) || args+=(--portfolio-stats "$stats")
# The share of a split run: stop after SPLIT_AFTER seconds, leaving the rest to the next round.
[ "${SPLIT_AFTER:-0}" = 0 ] || args+=(--time-limit "$SPLIT_AFTER")
resumed=false
if ((round > 0)); then
  args+=(--part "$part/$parts" --resume "$resume_from")
  resumed=true
elif [ -s "$ckpt" ]; then
  args+=(--resume "$ckpt")
  resumed=true
fi
say "starting (resume: $resumed, OMP_NUM_THREADS=$OMP_NUM_THREADS): $TILEKIT ${COMMAND[*]} ${args[*]}"

# True once process $1 has handlers for USR1 and TERM (bits 10 and 15 of SigCgt, Linux).
catches_signals() {
  local key mask
  [ -r "/proc/$1/status" ] || return 0  # no /proc: assume it does
  while read -r key mask; do
    [ "$key" = SigCgt: ] || continue
    (((16#$mask & 0x4200) == 0x4200))
    return
  done <"/proc/$1/status"
  return 1
}

# tilekit runs in the background so that this shell can take Slurm's signals and pass them on.
"$TILEKIT" "${COMMAND[@]}" "${args[@]}" >"$done_file.tmp" &
pid=$!
for ((tries = 0; tries < 200; tries++)); do
  if catches_signals "$pid" || ! kill -0 "$pid" 2>/dev/null; then break; fi
  sleep 0.05
done
ready=true
if [ -n "$pending" ]; then
  say "passing SIG$pending on to tilekit (pid $pid)"
  kill -s "$pending" "$pid" 2>/dev/null || true
fi
while :; do
  wait "$pid"
  rc=$?
  # >128: `wait` was interrupted by a trapped signal; keep waiting while tilekit runs.
  if ((rc > 128)) && kill -0 "$pid" 2>/dev/null; then continue; fi
  # tilekit ended while the trap ran: `wait` again returns its own exit status.
  if ((rc > 128)); then
    wait "$pid"
    rc2=$?
    ((rc2 == 127)) || rc=$rc2
  fi
  break
done
trap - USR1 TERM

case $rc in
  0)
    if ((round == 0)) && [ "${SPLIT_AFTER:-0}" != 0 ] && grep -q '"timed_out":true' "$done_file.tmp"; then
      # Past its share: the merge job splits what is left (cluster split) into the next round.
      mv -f "$done_file.tmp" "$split_file"
      record 0 "$resumed" "$split_file"
      say "ran its share ($SPLIT_AFTER s); left the rest to the next round: $(cat "$split_file")"
      exit 0
    fi
    mv -f "$done_file.tmp" "$done_file"
    record 0 "$resumed" "$done_file"
    say "complete: $(cat "$done_file")"
    exit 0
    ;;
  3)
    record 3 "$resumed" "$done_file.tmp"
    rm -f "$done_file.tmp"
    if [ "$warned" != true ]; then
      # Not our warning: Slurm is ending this job (a requeue or preemption brings it back by
      # itself; after scancel it must stay cancelled), so do not requeue it here.
      say "checkpointed ($ckpt) on SIGTERM; not requeueing (Slurm decides)"
      exit 3
    fi
    if ((attempt >= MAX_REQUEUES)); then
      say "checkpointed, but the requeue bound ($MAX_REQUEUES) is reached; resubmit the run to go on"
      exit 3
    fi
    say "checkpointed ($ckpt); requeueing this task to resume"
    # By this task's own job id: the ARRAY_TASK form is refused ("can not be altered now")
    # while another task of the array waits to restart after its own requeue.
    if scontrol requeue "$SLURM_JOB_ID"; then
      # Slurm now ends this attempt and queues the next one; wait here until it does.
      trap 'exit 3' TERM
      sleep 300 &
      wait $!
    else
      say "scontrol requeue $SLURM_JOB_ID failed; resubmit the run to go on"
    fi
    exit 3
    ;;
  1)
    # Exit 1 = nothing found. With the shard's search space exhausted ("complete":true, e.g.
    # --mode first in a shard without a packing) the shard is done all the same.
    if grep -q '"complete":true' "$done_file.tmp" 2>/dev/null; then
      mv -f "$done_file.tmp" "$done_file"
      record 1 "$resumed" "$done_file"
      say "complete, nothing found in this shard: $(cat "$done_file")"
      exit 0
    fi
    record 1 "$resumed" "$done_file.tmp"
    rm -f "$done_file.tmp"
    say "tilekit found nothing and did not finish its search (exit code 1)"
    exit 1
    ;;
  *)
    record "$rc" "$resumed" "$done_file.tmp"
    rm -f "$done_file.tmp"
    say "tilekit failed with exit code $rc"
    exit "$rc"
    ;;
esac
