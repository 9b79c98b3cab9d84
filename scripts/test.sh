#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (docs/TESTING.md):
#   1. ctest on the Release build (build/);
#   2. every libFuzzer harness for a few seconds (build-fuzz/, ASan+UBSan; FUZZ_SECONDS, default 5);
#   3. the end-to-end test against a real single-node Slurm (tests/slurm/cluster-test.sh; needs
#      root, about 2-3 minutes).
# Options: --sanitize runs only the AddressSanitizer + UndefinedBehaviorSanitizer build
# (build-asan/) and the whole ctest suite on it; --full adds that, the ThreadSanitizer engine
# tests (build-tsan/) and fuzzes each harness for FUZZ_SECONDS (default 300 with --full).
# The ASan suite is not in the plain CI run until its time on 2 cores is measured
# (docs/TESTING.md).
# Set TILEKIT_SKIP_SLURM=1 or TILEKIT_SKIP_SANITIZE=1 to leave a step out (it then says so).
# Other arguments go to every ctest run.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
mode=ci
args=()
for a in "$@"; do
  case "$a" in
    --sanitize) mode=sanitize ;;
    --full) mode=full ;;
    *) args+=("$a") ;;
  esac
done
"$root/scripts/setup.sh"
if [ "$mode" = sanitize ]; then
  exec "$root/scripts/sanitize.sh" asan "${args[@]}"
fi
"$root/scripts/build.sh"
# setup.sh installed Mesa's EGL: the GLSL-vs-CPU tests must run (fail, not skip, without a context).
export TILEKIT_REQUIRE_EGL=${TILEKIT_REQUIRE_EGL:-1}
(cd "$root/build" && ctest --output-on-failure -j "$(nproc)" "${args[@]}")
if [ "${TILEKIT_SKIP_SANITIZE:-0}" = 1 ]; then
  echo "test.sh: the fuzz (and with --full, sanitizer) runs were SKIPPED (TILEKIT_SKIP_SANITIZE=1)" >&2
else
  if [ "$mode" = full ]; then
    "$root/scripts/sanitize.sh" asan "${args[@]}"
    "$root/scripts/sanitize.sh" tsan "${args[@]}"
    "$root/scripts/fuzz.sh" "${FUZZ_SECONDS:-300}"
  else
    "$root/scripts/fuzz.sh" "${FUZZ_SECONDS:-5}"
  fi
fi
if [ "${TILEKIT_SKIP_SLURM:-0}" = 1 ]; then
  echo "test.sh: the real-Slurm test was SKIPPED (TILEKIT_SKIP_SLURM=1)" >&2
else
  bash "$root/tests/slurm/cluster-test.sh"
fi
