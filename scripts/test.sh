#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite: ctest, then the end-to-end test against a real
# single-node Slurm (tests/slurm/cluster-test.sh; needs root, about 2-3 minutes). Set
# TILEKIT_SKIP_SLURM=1 to leave the Slurm test out (it then says so).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
# setup.sh installed Mesa's EGL: the GLSL-vs-CPU tests must run (fail, not skip, without a context).
export TILEKIT_REQUIRE_EGL=${TILEKIT_REQUIRE_EGL:-1}
(cd "$root/build" && ctest --output-on-failure -j "$(nproc)" "$@")
if [ "${TILEKIT_SKIP_SLURM:-0}" = 1 ]; then
  echo "test.sh: the real-Slurm test was SKIPPED (TILEKIT_SKIP_SLURM=1)" >&2
else
  bash "$root/tests/slurm/cluster-test.sh"
fi
