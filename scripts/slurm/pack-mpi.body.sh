# ---- body of the MPI job (scripts/slurm/pack-mpi.body.sh) ----
# Expects, set above by `tilekit cluster submit --mpi`: TILEKIT, RUN_DIR, MAX_REQUEUES,
# CHECKPOINT_EVERY, LAUNCHER (srun or mpirun), SRUN_MPI (srun's MPI plugin) and the arrays
# COMMAND (`pack`) and PACK_ARGS.
#
# One job = one `tilekit pack --mpi` of SLURM_NTASKS ranks inside this allocation, each rank with
# SLURM_CPUS_PER_TASK threads; rank 0 hands out the subproblems and alone writes the database.
# The run is shard 0 of 1 of the run directory, so `tilekit cluster status` reads it as it reads
# an array's shards:
#   RUN_DIR/shards/shard-0.ckpt         rank 0's checkpoint; rank R writes shard-0.ckpt.rank-R
#   RUN_DIR/shards/shard-0.sqlite       the database (rank 0 only)
#   RUN_DIR/shards/shard-0.attempts     one JSON line per attempt (as an array task's)
#   RUN_DIR/shards/shard-0.done.json    `tilekit pack --json` output once the run is complete
# Signals, requeues and exit codes: pack-common.body.sh, above. The launcher passes a signal on to
# every rank; each rank checkpoints, and the next attempt resumes with --resume on however many
# ranks it gets (the root merges every rank's file).
set -uo pipefail

job=${SLURM_JOB_ID:?"submit this script with sbatch"}
attempt=${SLURM_RESTART_COUNT:-0}
ranks=${SLURM_NTASKS:-1}
threads=${SLURM_CPUS_PER_TASK:-1}
export OMP_NUM_THREADS=$threads

dir="$RUN_DIR/shards"
ckpt="$dir/shard-0.ckpt"
db="$dir/shard-0.sqlite"
done_file="$dir/shard-0.done.json"
attempts="$dir/shard-0.attempts"

say() { printf '%s tilekit MPI run (job %s, attempt %s, %s ranks): %s\n' "$(date -u +%FT%TZ)" "$job" "$attempt" \
  "$ranks" "$*"; }
job_label=$job
record_extra=",\"ranks\":$ranks,\"launcher\":\"$LAUNCHER\""
child=$LAUNCHER
job_word=job
go_on="run submit.sh again to go on"
ckpt_words="$ckpt and its rank files"

take_signals
mkdir -p "$dir"
if [ -s "$done_file" ]; then
  say "already complete ($done_file); nothing to do"
  record 0 false
  exit 0
fi

args=("${PACK_ARGS[@]}" --mpi --threads "$threads" --checkpoint "$ckpt" --checkpoint-every "$CHECKPOINT_EVERY"
      --db "$db" --json)
resumed=false
if [ -s "$ckpt" ]; then
  args+=(--resume "$ckpt")
  resumed=true
fi
case $LAUNCHER in
  # srun does not pass the job's --cpus-per-task on to a step (Slurm >= 22.05): given again here.
  srun) launch=(srun --mpi="$SRUN_MPI" --ntasks="$ranks" --cpus-per-task="$threads" --kill-on-bad-exit=1) ;;
  # mpirun reads the nodes and the task count from Slurm; no binding, so that a rank's threads
  # may use every core of its task.
  mpirun) launch=(mpirun -np "$ranks" --bind-to none) ;;
  *) say "unknown LAUNCHER '$LAUNCHER' (srun or mpirun)"; exit 2 ;;
esac
say "starting (resume: $resumed): ${launch[*]} $TILEKIT ${COMMAND[*]} ${args[*]}"

# Every rank writes its checkpoint file once its search (and its signal handling) has started.
rank_files=("$ckpt")
for ((r = 1; r < ranks; r++)); do rank_files+=("$ckpt.rank-$r"); done
marker="$dir/.attempt-start"
: >"$marker"
child_ready() {
  local f
  for f in "${rank_files[@]}"; do [ "$f" -nt "$marker" ] || return 1; done
}
# A filesystem whose times have a coarse grain may show a file written in the same second as
# the marker as not newer: after 60 s the ranks are taken to be searching anyway.
ready_tries=1200
run_search "${launch[@]}" "$TILEKIT" "${COMMAND[@]}" "${args[@]}"
rm -f "$marker"
finish
