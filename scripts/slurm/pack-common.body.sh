# ---- shared by the pack job bodies (scripts/slurm/pack-common.body.sh) ----
# Functions of pack-array.body.sh and pack-mpi.body.sh, which follow and set what these read:
#   say MESSAGE     one line of the job's log
#   job_label       the "job" of an attempt's line (an array task's id, or the job's)
#   record_extra    more fields for an attempt's line (`,"key":value...`, or empty)
#   attempt, attempts (the file of attempt lines), done_file, resumed, ckpt_words (the checkpoint
#   files, for the log), job_word ("task" or "job"), go_on (what the user does after the requeue bound)
#   child           what runs the search, for the log: tilekit, or the MPI launcher
#   child_ready PID true once the search catches USR1 and TERM (an uncaught USR1 would kill it
#                   without a checkpoint); ready_tries: how many 50 ms waits for it at most
# Signals: Slurm sends USR1 to this script (--signal=B:USR1@S) S seconds before the wall-time
# kill; it is passed to the search, which writes its checkpoint and exits 3; the job then
# requeues itself (scontrol requeue) and its next attempt resumes; at most MAX_REQUEUES times
# (SLURM_RESTART_COUNT counts every requeue, whoever asked). SIGTERM (scancel, scontrol requeue,
# preemption, a limit reached without warning) also makes it checkpoint and exit 3, but the job
# does not requeue itself then: a cancelled run stays cancelled, and Slurm brings back a requeued
# or preempted one by itself.

# A number from tilekit's one-line JSON result $2 (null if absent).
number() { local v; v=$(grep -o "\"$1\":[0-9.eE+-]*" "$2" 2>/dev/null | head -n 1 | cut -d: -f2); echo "${v:-null}"; }
record() {  # record EXIT RESUMED [RESULT_JSON]: one line per attempt in $attempts
  local r=${3:-/dev/null}
  printf '{"time":"%s","job":"%s","attempt":%s,"exit":%s,"resumed":%s,"host":"%s"%s,"solutions":%s,"nodes":%s,"seconds":%s,"total_seconds":%s}\n' \
    "$(date -u +%FT%TZ)" "$job_label" "$attempt" "$1" "$2" "$(hostname -s)" "$record_extra" \
    "$(number solutions "$r")" "$(number nodes "$r")" "$(number seconds "$r")" "$(number total_seconds "$r")" >>"$attempts"
}

# Slurm's signals may come at any moment, even before the search runs: take_signals, first thing.
pid=""        # the child
ready=false   # the search catches USR1 and TERM
pending=""    # a signal that came before that, passed on once it does
warned=false  # USR1 = our wall-time warning; TERM = Slurm ends the job (scancel, requeue, preemption)
on_signal() {
  [ "$1" != USR1 ] || warned=true
  if [ "$ready" = true ]; then
    say "got SIG$1; passing it to $child (pid $pid) to checkpoint and stop"
    kill -s "$1" "$pid" 2>/dev/null || true
  else
    say "got SIG$1 before the search catches signals; passing it on when it does"
    pending=$1
  fi
}
take_signals() {
  trap 'on_signal USR1' USR1
  trap 'on_signal TERM' TERM
}

# run_search COMMAND...: runs it in the background (so that this shell can take Slurm's signals
# and pass them on), its output into $done_file.tmp; sets rc to its exit code.
run_search() {
  "$@" >"$done_file.tmp" &
  pid=$!
  local tries
  for ((tries = 0; tries < ready_tries; tries++)); do
    if child_ready "$pid" || ! kill -0 "$pid" 2>/dev/null; then break; fi
    sleep 0.05
  done
  ready=true
  if [ -n "$pending" ]; then
    say "passing SIG$pending on to $child (pid $pid)"
    kill -s "$pending" "$pid" 2>/dev/null || true
  fi
  local rc2
  while :; do
    wait "$pid"
    rc=$?
    # >128: `wait` was interrupted by a trapped signal; keep waiting while the child runs.
    if ((rc > 128)) && kill -0 "$pid" 2>/dev/null; then continue; fi
    # The child ended while the trap ran: `wait` again returns its own exit status.
    if ((rc > 128)); then
      wait "$pid"
      rc2=$?
      ((rc2 == 127)) || rc=$rc2
    fi
    break
  done
  trap - USR1 TERM
}

# finish: the attempt's line, the log's last word and the job's exit code, from rc.
finish() {
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
        # Not our warning: Slurm is ending this job (a requeue or preemption brings it back by
        # itself; after scancel it must stay cancelled), so do not requeue it here.
        say "checkpointed ($ckpt_words) on SIGTERM; not requeueing (Slurm decides)"
        exit 3
      fi
      if ((attempt >= MAX_REQUEUES)); then
        say "checkpointed, but the requeue bound ($MAX_REQUEUES) is reached; $go_on"
        exit 3
      fi
      say "checkpointed ($ckpt_words); requeueing this $job_word to resume"
      # By this job's own id: an array task's ARRAY_TASK form is refused ("can not be altered
      # now") while another task of the array waits to restart after its own requeue.
      if scontrol requeue "$SLURM_JOB_ID"; then
        # Slurm now ends this attempt and queues the next one; wait here until it does.
        trap 'exit 3' TERM
        sleep 300 &
        wait $!
      else
        say "scontrol requeue $SLURM_JOB_ID failed; $go_on"
      fi
      exit 3
      ;;
    1)
      # Exit 1 = nothing found. With the search space exhausted ("complete":true, e.g. --mode
      # first in a shard without a packing) the work is done all the same.
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
      say "$child failed with exit code $rc"
      exit "$rc"
      ;;
  esac
}
