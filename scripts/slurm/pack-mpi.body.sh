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
# Signals as in an array task (pack-array.body.sh): USR1 (--signal=B:USR1@S) is passed to the
# launcher, which passes it to every rank; each rank checkpoints and the job exits 3 and requeues
# itself (at most MAX_REQUEUES times); the next attempt resumes with --resume, on however many
# ranks it gets (the root merges every rank's file). SIGTERM: checkpoint, exit 3, no requeue.
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
number() { local v; v=$(grep -o "\"$1\":[0-9.eE+-]*" "$2" 2>/dev/null | head -n 1 | cut -d: -f2); echo "${v:-null}"; }
record() {  # record EXIT RESUMED [RESULT_JSON]: one line per attempt in shard-0.attempts
  local r=${3:-/dev/null}
  printf '{"time":"%s","job":"%s","attempt":%s,"exit":%s,"resumed":%s,"host":"%s","ranks":%s,"launcher":"%s","solutions":%s,"nodes":%s,"seconds":%s,"total_seconds":%s}\n' \
    "$(date -u +%FT%TZ)" "$job" "$attempt" "$1" "$2" "$(hostname -s)" "$ranks" "$LAUNCHER" \
    "$(number solutions "$r")" "$(number nodes "$r")" "$(number seconds "$r")" "$(number total_seconds "$r")" >>"$attempts"
}

pid=""        # the launcher (srun or mpirun)
ready=false   # every rank has written its first checkpoint of this attempt: they catch USR1 and TERM
pending=""    # a signal that came before that, passed on once they do
warned=false  # USR1 = our wall-time warning; TERM = Slurm ends the job
on_signal() {
  [ "$1" != USR1 ] || warned=true
  if [ "$ready" = true ]; then
    say "got SIG$1; passing it to $LAUNCHER (pid $pid), which passes it to every rank"
    kill -s "$1" "$pid" 2>/dev/null || true
  else
    say "got SIG$1 before every rank catches signals; passing it on when they do"
    pending=$1
  fi
}
trap 'on_signal USR1' USR1
trap 'on_signal TERM' TERM

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

# Written by every rank once its search (and its signal handling) has started.
rank_files=("$ckpt")
for ((r = 1; r < ranks; r++)); do rank_files+=("$ckpt.rank-$r"); done
marker="$dir/.attempt-start"
: >"$marker"
all_written() {
  local f
  for f in "${rank_files[@]}"; do [ "$f" -nt "$marker" ] || return 1; done
}

"${launch[@]}" "$TILEKIT" "${COMMAND[@]}" "${args[@]}" >"$done_file.tmp" &
pid=$!
# A filesystem whose times have a coarse grain may show a file written in the same second as
# the marker as not newer: after 60 s the ranks are taken to be searching anyway.
for ((tries = 0; tries < 1200; tries++)); do
  if all_written || ! kill -0 "$pid" 2>/dev/null; then break; fi
  sleep 0.05
done
ready=true
if [ -n "$pending" ]; then
  say "passing SIG$pending on to $LAUNCHER (pid $pid)"
  kill -s "$pending" "$pid" 2>/dev/null || true
fi
while :; do
  wait "$pid"
  rc=$?
  if ((rc > 128)) && kill -0 "$pid" 2>/dev/null; then continue; fi
  if ((rc > 128)); then
    wait "$pid"
    rc2=$?
    ((rc2 == 127)) || rc=$rc2
  fi
  break
done
trap - USR1 TERM
rm -f "$marker"

case $rc in
  0)
    mv -f "$done_file.tmp" "$done_file"
    record 0 "$resumed" "$done_file"
    say "complete: $(cat "$done_file")"
    exit 0
    ;;
  3)
    record 3 "$resumed" "$done_file.tmp"
    rm -f "$done_file.tmp"
    if [ "$warned" != true ]; then
      say "checkpointed ($ckpt and its rank files) on SIGTERM; not requeueing (Slurm decides)"
      exit 3
    fi
    if ((attempt >= MAX_REQUEUES)); then
      say "checkpointed, but the requeue bound ($MAX_REQUEUES) is reached; run submit.sh again to go on"
      exit 3
    fi
    say "checkpointed ($ckpt and its rank files); requeueing this job to resume"
    if scontrol requeue "$SLURM_JOB_ID"; then
      trap 'exit 3' TERM
      sleep 300 &
      wait $!
    else
      say "scontrol requeue $SLURM_JOB_ID failed; run submit.sh again to go on"
    fi
    exit 3
    ;;
  1)
    # Exit 1 = nothing found; with the search space exhausted ("complete":true) the run is done.
    if grep -q '"complete":true' "$done_file.tmp" 2>/dev/null; then
      mv -f "$done_file.tmp" "$done_file"
      record 1 "$resumed" "$done_file"
      say "complete, nothing found: $(cat "$done_file")"
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
    say "$LAUNCHER ended with exit code $rc"
    exit "$rc"
    ;;
esac
