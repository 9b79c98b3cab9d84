#!/bin/bash
# `tilekit pack --mpi` under Open MPI's mpirun on this machine (tests/CMakeLists.txt registers it
# when the build found MPI). Usage: mpi-test.sh TILEKIT CASE
#   wang4   the C=2 Wang count on 4 ranks: 203520 solutions, 538 orbits, complete
#   kill    the C=3 corner count under t=(0,3) on 4 ranks; rank 2 is killed (SIGKILL) once the ranks
#           have checkpointed, mpirun ends the job, and `--resume` on 3 ranks completes it: 303264
#   steal   the C=2 Wang count split into 1 subproblem, on 4 ranks of 2 threads: every rank but
#           one starts idle, so the work is stolen (split subtrees); 203520, steals reported
#   killsteal  the kill case with 4 subproblems (nearly all work is stolen pieces), resumed on 2
#           ranks: 303264
# CI runs as root: Open MPI refuses that unless OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM) are set.
set -euo pipefail
tk=$1 case=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# Open MPI's own start-up allocations are never freed (LeakSanitizer reports them from its
# libraries, not from Tilekit): leak checks are off for the ranks; every other ASan/UBSan check stays.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
dir=$(mktemp -d /tmp/tilekit-mpi-test.XXXXXX)
trap 'rm -rf "$dir"' EXIT
cd "$dir"
fail() { echo "FAIL: $*" >&2; exit 1; }
field() { grep -o "\"$1\":[a-z0-9]*" "$2" | head -n 1 | cut -d: -f2; }

case $case in
wang4)
  mpirun --oversubscribe -np 4 "$tk" pack --mpi --kind wang --colors 2 --mode count --threads 1 --quiet \
    --checkpoint c.ckpt --db r.sqlite --json >out.json
  [ "$(field solutions out.json)" = 203520 ] || fail "solutions $(field solutions out.json), expected 203520"
  [ "$(field orbits out.json)" = 538 ] || fail "orbits $(field orbits out.json), expected 538"
  [ "$(field complete out.json)" = true ] || fail "not complete"
  for r in 1 2 3; do [ -s "c.ckpt.rank-$r" ] || fail "rank $r wrote no checkpoint"; done
  [ "$(sqlite3 r.sqlite 'select count(*) from runs')" = 1 ] || fail "the database holds more than the root's run"
  echo "ok: 4 ranks counted 203520 (538 orbits)"
  ;;
steal)
  mpirun --oversubscribe -np 4 "$tk" pack --mpi --kind wang --colors 2 --mode count --threads 2 --quiet \
    --subproblems 1 --checkpoint c.ckpt --db r.sqlite --json >out.json
  [ "$(field solutions out.json)" = 203520 ] || fail "solutions $(field solutions out.json), expected 203520"
  [ "$(field orbits out.json)" = 538 ] || fail "orbits $(field orbits out.json), expected 538"
  [ "$(field nodes out.json)" = 283488 ] || fail "nodes $(field nodes out.json), expected 283488 (every node once)"
  [ "$(field complete out.json)" = true ] || fail "not complete"
  [ "$(field subproblems out.json)" = 1 ] || fail "subproblems $(field subproblems out.json), expected 1"
  steals=$(field steals out.json) pieces=$(field pieces out.json) splits=$(field splits_completed out.json)
  [ "${steals:-0}" -ge 1 ] || fail "no steal reported"
  [ "${pieces:-0}" -ge "$steals" ] || fail "$pieces pieces for $steals steals"
  [ "${splits:-0}" = 1 ] || fail "split subproblems completed: ${splits:-none}, expected 1"
  echo "ok: 1 subproblem on 4 ranks: 203520, $steals steals, $pieces pieces"
  ;;
kill | killsteal)
  group='t=0,3:pi=1,2,0' more=() again=3
  if [ "$case" = killsteal ]; then more=(--subproblems 4) again=2; fi
  mpirun --oversubscribe -np 4 "$tk" pack --mpi --kind corner --colors 3 --mode count --impose "$group" \
    "${more[@]}" --threads 1 --quiet --checkpoint c.ckpt --checkpoint-every 1 --db r.sqlite --json >out1.json 2>err1.txt &
  mp=$!
  # Rank 2's first checkpoint is written before any work; give the ranks 3 s of work after it.
  for _ in $(seq 600); do
    [ -s c.ckpt.rank-2 ] && break
    sleep 0.1
  done
  sleep 3
  victim=""
  for p in $(pgrep -P "$mp"); do
    if tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx OMPI_COMM_WORLD_RANK=2; then victim=$p; fi
  done
  [ -n "$victim" ] || fail "rank 2 not found among mpirun's children (finished already?)"
  kill -9 "$victim"
  if wait "$mp"; then fail "mpirun ended with 0 after rank 2 was killed"; fi
  [ -s c.ckpt ] || fail "no root checkpoint"
  mpirun --oversubscribe -np "$again" "$tk" pack --mpi --resume c.ckpt --quiet --json >out2.json
  [ "$(field solutions out2.json)" = 303264 ] || fail "solutions $(field solutions out2.json), expected 303264"
  [ "$(field complete out2.json)" = true ] || fail "the resumed run is not complete"
  echo "ok: rank 2 killed, resumed on $again ranks: 303264 ($(field steals out2.json) steals in the resumed run)"
  ;;
*) fail "unknown case $case" ;;
esac
