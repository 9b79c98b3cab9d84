#!/usr/bin/env bash
# Sets up, builds and tests (docs/TESTING.md, with the measured time of each step). The default is
# the README's test command, about ten minutes on 2 cores once set up (ccache warm; see TESTING.md):
#   0. the layer check (scripts/check-layers.sh: includes against each folder README's
#      "May include" line, no cycles) and the doc check (scripts/check-docs.sh: every source file
#      in its folder README, every file a doc names present), before anything is built;
#   1. the Release build (build/, Ninja; the benchmarks are left to the sanitizer build) and its
#      ctest suite less the tests labelled "slow" (the SIGKILL/SIGTERM/resume rounds and shard
#      merges of pack and enumerate, tests/CMakeLists.txt);
#   2. every libFuzzer harness of fuzz/ through fuzz_driver of the Release build: its seeds, then
#      seeded mutants, FUZZ_SECONDS each (default 5), two at a time (scripts/fuzz.sh --driver);
#   3. the end-to-end test against a real single-node Slurm (tests/slurm/cluster-test.sh; needs
#      root, 2-3 minutes; then tests/slurm/mpi-submit-test.sh, `cluster submit --mpi` with srun,
#      about 2 minutes), under flock /tmp/tilekit-slurm.lock: the machine has one Slurm. It
#      waits on Slurm (a wall-time limit of one minute, requeues) for more than half of its time,
#      so it starts right after the build and runs beside steps 1 and 2; its output is printed
#      when it ends, with its own time.
# Options:
#   --sanitize  the sanitizer step (.ci/run runs the first part, and the second less "slow"): the "slow" tests in the Release build (built
#               first if it is not there), the whole ctest suite under AddressSanitizer +
#               UndefinedBehaviorSanitizer (build-asan/, which also compiles the benchmarks and
#               every file on its own), and every harness under libFuzzer with ASan+UBSan
#               (build-fuzz/, FUZZ_SECONDS each, default 5)
#   --full      everything: the Release build and its whole suite, the ASan+UBSan suite, the
#               ThreadSanitizer engine tests (build-tsan/), libFuzzer for FUZZ_SECONDS (default
#               300) per harness, and the real-Slurm test
# TILEKIT_SKIP_SLURM=1 or TILEKIT_SKIP_FUZZ=1 leaves a step out (it then says so). Other
# arguments go to every ctest run. Each step ends with one line: what ran, how it ended, how long.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
mode=default
args=()
for a in "$@"; do
  case "$a" in
    --sanitize) mode=sanitize ;;
    --full) mode=full ;;
    *) args+=("$a") ;;
  esac
done
start=$SECONDS
step() {  # step NAME COMMAND...: runs it, then one line with its time and the total so far
  local t0=$SECONDS rc=0
  "${@:2}" || rc=$?
  echo "test.sh: $1 $([ $rc -eq 0 ] && echo ok || echo "FAILED (exit $rc)") in $((SECONDS - t0)) s (total $((SECONDS - start)) s)" >&2
  return $rc
}
release_ctest() {  # release_ctest CTEST_ARGS...: the Release suite, with EGL and the browser required
  # setup.sh installed Mesa's EGL and chromium: the GLSL-vs-CPU tests and the browser test of the
  # preview page must run (fail, not skip, without a context or a browser).
  (cd "$root/build" && TILEKIT_REQUIRE_EGL=${TILEKIT_REQUIRE_EGL:-1} TILEKIT_REQUIRE_BROWSER=${TILEKIT_REQUIRE_BROWSER:-1} \
    ctest --output-on-failure -j "$(nproc)" "$@")
}
step "set-up" "$root/scripts/setup.sh"
step "layer check" bash "$root/scripts/check-layers.sh"
step "doc check" bash "$root/scripts/check-docs.sh"
slurm_pid=""
slurm_log=$root/build/slurm-test.log
start_slurm() {  # the real-Slurm test in the background, its output and exit code in build/
  if [ "$mode" = sanitize ] || [ "${TILEKIT_SKIP_SLURM:-0}" = 1 ]; then return 0; fi
  rm -f "$slurm_log" "$slurm_log.end"
  (
    t0=$SECONDS rc=0
    # the job-array test, then `cluster submit --mpi` (srun --mpi=pmix), under one lock
    flock /tmp/tilekit-slurm.lock bash -c 'bash "$1/tests/slurm/cluster-test.sh"; a=$?
      bash "$1/tests/slurm/mpi-submit-test.sh"; b=$?; exit $((a > b ? a : b))' _ "$root" >"$slurm_log" 2>&1 || rc=$?
    echo "$rc $((SECONDS - t0))" >"$slurm_log.end"
  ) &
  slurm_pid=$!
}
finish_slurm() {  # waits for it, prints its output, returns its exit code
  wait "$slurm_pid" || true
  slurm_pid=""
  cat "$slurm_log"
  local rc=1 took=?
  [ -f "$slurm_log.end" ] && read -r rc took <"$slurm_log.end"
  echo "test.sh: the real-Slurm test itself ran $took s, beside the steps before it" >&2
  return "$rc"
}
# A step that fails ends this script (set -e): the Slurm test still ends first, so that no
# daemon of it is left running.
trap '[ -z "$slurm_pid" ] || finish_slurm >/dev/null 2>&1 || true' EXIT
if [ "$mode" = default ]; then
  # The benchmarks are compiled by the sanitizer build (--sanitize), not here.
  step "Release build" env TILEKIT_BENCH=OFF "$root/scripts/build.sh"
  start_slurm
  step "Release ctest (all but the slow label)" release_ctest -LE slow "${args[@]}"
else
  # Keeps the benchmarks of a build/ that has them (scripts/build.sh alone builds them).
  bench=OFF
  grep -q '^TILEKIT_BENCH:BOOL=ON' "$root/build/CMakeCache.txt" 2>/dev/null && bench=ON
  step "Release build" env TILEKIT_BENCH=$bench "$root/scripts/build.sh"
  start_slurm
  if [ "$mode" = sanitize ]; then
    step "Release ctest (the slow label)" release_ctest -L slow "${args[@]}"
  else
    step "Release ctest (all)" release_ctest "${args[@]}"
  fi
  step "ASan+UBSan build and ctest" "$root/scripts/sanitize.sh" asan "${args[@]}"
  [ "$mode" = full ] && step "TSan build and engine tests" "$root/scripts/sanitize.sh" tsan "${args[@]}"
fi
if [ "${TILEKIT_SKIP_FUZZ:-0}" = 1 ]; then
  echo "test.sh: the fuzz run was SKIPPED (TILEKIT_SKIP_FUZZ=1)" >&2
elif [ "$mode" = default ]; then
  step "fuzz_driver run (Release)" "$root/scripts/fuzz.sh" --driver "${FUZZ_SECONDS:-5}"
else
  step "libFuzzer build and run (ASan+UBSan)" "$root/scripts/fuzz.sh" "${FUZZ_SECONDS:-$([ "$mode" = full ] && echo 300 || echo 5)}"
fi
if [ "$mode" = sanitize ]; then
  exit 0
elif [ "${TILEKIT_SKIP_SLURM:-0}" = 1 ]; then
  echo "test.sh: the real-Slurm test was SKIPPED (TILEKIT_SKIP_SLURM=1)" >&2
else
  step "real-Slurm test (waited for)" finish_slurm
fi
