#!/usr/bin/env bash
# Configures and builds Tilekit (Release) into build/. Usage: scripts/build.sh [BUILD_DIR]
# A new build directory uses Ninja where it is installed (scripts/setup.sh installs it); one
# already configured keeps its generator. TILEKIT_BENCH=OFF leaves the benchmarks out of this
# build (scripts/test.sh does: they are compiled by the sanitizer build of .ci/run instead).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
gen=()
[ -f "$build/CMakeCache.txt" ] || ! command -v ninja >/dev/null || gen=(-G Ninja)
cmake -S "$root" -B "$build" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release -DTILEKIT_BENCH="${TILEKIT_BENCH:-ON}" >/dev/null
cmake --build "$build" -j "$(nproc)"
