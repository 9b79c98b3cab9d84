# Shared by the real-Slurm tests (cluster-test.sh, mpi-submit-test.sh), sourced after they set
#   root        the repository
#   log_name    the prefix of their log lines
#   DEADLINE    the $SECONDS by which they give up waiting
# Gives TK (the tilekit under test, first on PATH so that the jobs run it), SLURM (the local
# Slurm script), the counters passed/failed, log/check/fatal, start_slurm WORK and the job
# helpers field, time_left, wait_final and attempt_exits.
TK=${TILEKIT_BINARY:-$root/build/tilekit}
# `cluster submit` gives the jobs the tilekit on PATH (an installed one) unless --tilekit says
# otherwise: this build's goes first, so that the jobs run the binary under test.
PATH="$(dirname "$(readlink -f "$TK")"):$PATH"
SLURM=$root/scripts/slurm/local-slurm.sh
passed=0
failed=0

log() { echo "$log_name: $*"; }
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

# start_slurm WORK: installs and starts a one-node Slurm in WORK/slurm and takes its environment;
# on exit (trap) it prints the Slurm and job logs if anything failed, stops Slurm, removes WORK
# and prints "N passed, M failed".
start_slurm() {
  work=$1
  trap finish EXIT
  "$SLURM" install
  "$SLURM" start "$work/slurm" || fatal "Slurm did not start"
  # shellcheck disable=SC1091
  source "$work/slurm/env"
}
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

# Field $2 of job $1 as `scontrol show job` prints it (e.g. JobState, ExitCode, Restarts).
field() {
  scontrol -o show job "$1" 2>/dev/null | head -n 1 | tr ' ' '\n' | awk -v k="$2" 'index($0, k "=") == 1 {
    print substr($0, length(k) + 2); exit }'
}
time_left() { echo $((DEADLINE - SECONDS)); }
# Waits until job $1 reaches a final state and prints it; prints NEVER(...) when its dependency
# can never be met and TEST-TIMEOUT(...) on the test's deadline.
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
    (($(time_left) > 0)) || { echo "TEST-TIMEOUT($state)"; return 0; }
    sleep 1
  done
}
# The exit codes of a shard's attempts (its .attempts file $1), in order, space-separated.
attempt_exits() { { grep -o '"exit":[0-9]*' "$1" 2>/dev/null || true; } | cut -d: -f2 | tr '\n' ' ' | sed 's/ $//'; }
