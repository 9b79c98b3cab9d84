#!/usr/bin/env bash
# Sets up, builds and tests (docs/TESTING.md). The default is the README's test command, about
# ten minutes on 2 cores once set up:
#   0. the layer check (scripts/check-layers.sh: includes against each folder README's
#      "May include" line, no cycles), before anything is built;
#   1. the Release build (build/) and its whole ctest suite;
#   2. every libFuzzer harness for a few seconds (build-fuzz/, ASan+UBSan; FUZZ_SECONDS, default 5);
#   3. the end-to-end test against a real single-node Slurm (tests/slurm/cluster-test.sh; needs
#      root, 2-3 minutes), under flock /tmp/tilekit-slurm.lock: the machine has one Slurm.
# Options:
#   --full      adds the whole suite under AddressSanitizer + UndefinedBehaviorSanitizer
#               (build-asan/), the ThreadSanitizer engine tests (build-tsan/) and long fuzzing
#               (FUZZ_SECONDS, default 300 per harness)
#   --sanitize  only the ASan+UBSan suite (what .ci/run adds after the default run)
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
step "set-up" "$root/scripts/setup.sh"
step "layer check" bash "$root/scripts/check-layers.sh"
if [ "$mode" = sanitize ]; then
  step "ASan+UBSan build and ctest" "$root/scripts/sanitize.sh" asan "${args[@]}"
  exit
fi
step "Release build" "$root/scripts/build.sh"
# setup.sh installed Mesa's EGL and chromium: the GLSL-vs-CPU tests and the browser test of the
# preview page must run (fail, not skip, without a context or a browser).
export TILEKIT_REQUIRE_EGL=${TILEKIT_REQUIRE_EGL:-1}
export TILEKIT_REQUIRE_BROWSER=${TILEKIT_REQUIRE_BROWSER:-1}
step "Release ctest" bash -c 'cd "$0/build" && ctest --output-on-failure -j "$(nproc)" "${@:1}"' "$root" "${args[@]}"
if [ "$mode" = full ]; then
  step "ASan+UBSan build and ctest" "$root/scripts/sanitize.sh" asan "${args[@]}"
  step "TSan build and engine tests" "$root/scripts/sanitize.sh" tsan "${args[@]}"
fi
if [ "${TILEKIT_SKIP_FUZZ:-0}" = 1 ]; then
  echo "test.sh: the fuzz run was SKIPPED (TILEKIT_SKIP_FUZZ=1)" >&2
else
  step "fuzz build and run" "$root/scripts/fuzz.sh" "${FUZZ_SECONDS:-$([ "$mode" = full ] && echo 300 || echo 5)}"
fi
if [ "${TILEKIT_SKIP_SLURM:-0}" = 1 ]; then
  echo "test.sh: the real-Slurm test was SKIPPED (TILEKIT_SKIP_SLURM=1)" >&2
else
  step "real-Slurm test" flock /tmp/tilekit-slurm.lock bash "$root/tests/slurm/cluster-test.sh"
fi
