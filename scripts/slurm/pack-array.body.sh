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
# Signals, requeues and exit codes: pack-common.body.sh, above.
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
job_label=$task
record_extra=""
child=tilekit
job_word=task
go_on="resubmit the run to go on"
ckpt_words=$ckpt
ready_tries=200
# True once process $1 has handlers for USR1 and TERM (bits 10 and 15 of SigCgt, Linux).
child_ready() {
  local key mask
  [ -r "/proc/$1/status" ] || return 0  # no /proc: assume it does
  while read -r key mask; do
    [ "$key" = SigCgt: ] || continue
    (((16#$mask & 0x4200) == 0x4200))
    return
  done <"/proc/$1/status"
  return 1
}

take_signals
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

run_search "$TILEKIT" "${COMMAND[@]}" "${args[@]}"
if ((rc == 0 && round == 0)) && [ "${SPLIT_AFTER:-0}" != 0 ] && grep -q '"timed_out":true' "$done_file.tmp"; then
  # Past its share: the merge job splits what is left (cluster split) into the next round.
  mv -f "$done_file.tmp" "$split_file"
  record 0 "$resumed" "$split_file"
  say "ran its share ($SPLIT_AFTER s); left the rest to the next round: $(cat "$split_file")"
  exit 0
fi
finish
