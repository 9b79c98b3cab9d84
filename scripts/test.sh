#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (docs/TESTING.md):
#   0. the layer check (scripts/check-layers.sh: includes against each folder README's
#      "May include" line, no cycles), before anything is built;
#   1. ctest on the Release build (build/);
#   2. ctest again on the AddressSanitizer + UndefinedBehaviorSanitizer build (build-asan/,
#      LeakSanitizer on): the whole suite;
#   3. every libFuzzer harness for a few seconds (build-fuzz/, ASan+UBSan; FUZZ_SECONDS, default 5);
#   4. the end-to-end test against a real single-node Slurm (tests/slurm/cluster-test.sh; needs
#      root, about 2-3 minutes).
# Options: --sanitize runs only step 2; --full adds the ThreadSanitizer engine tests (build-tsan/)
# and fuzzes each harness for FUZZ_SECONDS (default 300 with --full).
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
bash "$root/scripts/check-layers.sh"
if [ "$mode" = sanitize ]; then
  exec "$root/scripts/sanitize.sh" asan "${args[@]}"
fi
"$root/scripts/build.sh"
# setup.sh installed Mesa's EGL and chromium: the GLSL-vs-CPU tests and the browser test of the
# preview page must run (fail, not skip, without a context or a browser).
export TILEKIT_REQUIRE_EGL=${TILEKIT_REQUIRE_EGL:-1}
export TILEKIT_REQUIRE_BROWSER=${TILEKIT_REQUIRE_BROWSER:-1}
(cd "$root/build" && ctest --output-on-failure -j "$(nproc)" "${args[@]}")
if [ "${TILEKIT_SKIP_SANITIZE:-0}" = 1 ]; then
  echo "test.sh: the sanitizer and fuzz runs were SKIPPED (TILEKIT_SKIP_SANITIZE=1)" >&2
else
  "$root/scripts/sanitize.sh" asan "${args[@]}"
  if [ "$mode" = full ]; then
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
