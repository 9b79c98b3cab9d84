#!/usr/bin/env bash
# Sanitizer builds and their test runs (docs/TESTING.md).
#   scripts/sanitize.sh asan [CTEST_ARGS...]  AddressSanitizer + UndefinedBehaviorSanitizer (GCC, -O1) in
#                                           build-asan/, then the whole ctest suite (the "slow" label
#                                           too). This build also compiles the benchmarks (the
#                                           README's test command does not) and compiles every file on
#                                           its own (TILEKIT_UNITY=OFF: each must include what it uses)
#   scripts/sanitize.sh tsan [CTEST_ARGS...]  ThreadSanitizer (clang, libomp with its Archer tool) in
#                                           build-tsan/, then the parallel engine tests: counts,
#                                           checkpoints and resumes, kills, signals and shards
# Any sanitizer report fails the test that triggered it (halt_on_error, no recovery).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
kind=${1:?usage: scripts/sanitize.sh asan|tsan [ctest args]}
shift
jobs=$(nproc)
# Debug information names paths relative to the checkout, so ccache (which otherwise hashes the
# working directory of a -g compile) shares these builds between checkouts: CI's fresh clone
# builds from the cache.
prefix_map="-fdebug-prefix-map=$root=."
gen=()
generator() {  # Ninja for a new build directory (one already configured keeps its generator)
  [ -f "$1/CMakeCache.txt" ] || ! command -v ninja >/dev/null || gen=(-G Ninja)
}
case "$kind" in
  asan)
    build=$root/build-asan
    # GCC 12 at -O1 with the sanitizers reports false maybe-uninitialized warnings inside
    # libstdc++ (std::function in <regex>); -Werror would turn them into errors.
    flags="-O1 -g $prefix_map -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -Wno-maybe-uninitialized"
    generator "$build"
    cmake -S "$root" -B "$build" "${gen[@]}" -DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_FLAGS_RELEASE="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
      -DTILEKIT_BENCH=ON -DTILEKIT_UNITY=OFF -DTILEKIT_GLUE_OPT= -DTILEKIT_CLI_OPT= >/dev/null
    cmake --build "$build" -j "$jobs"
    export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=0:strict_string_checks=1}
    export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
    (cd "$build" && ctest --output-on-failure -j "$jobs" "$@")
    ;;
  tsan)
    build=$root/build-tsan
    flags="-O1 -g $prefix_map -fsanitize=thread -fno-omit-frame-pointer"
    generator "$build"
    cmake -S "$root" -B "$build" "${gen[@]}" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_FLAGS_RELEASE="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" -DTILEKIT_BENCH=OFF \
      -DTILEKIT_GLUE_OPT= -DTILEKIT_CLI_OPT= >/dev/null
    cmake --build "$build" -j "$jobs" --target tilekit test_solver test_cli
    # libomp's own synchronisation is invisible to TSan without its Archer tool.
    archer=$(ls /usr/lib/llvm-*/lib/libarcher.so 2>/dev/null | tail -1)
    export OMP_TOOL_LIBRARIES=${archer:?libarcher.so not found (libomp-dev)}
    # libomp itself is not instrumented; Archer asks for its accesses to be ignored (else false reports).
    export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1:ignore_noninstrumented_modules=1}
    engine='Checkpoint|Resume|ParallelSearch|Solve\.|Counts|PackKill|PackSignals|PackShards|Shard|ImposeCounts|SearchStateCheck'
    (cd "$build" && ctest --output-on-failure -j "$jobs" -R "$engine" "$@")
    ;;
  *)
    echo "usage: scripts/sanitize.sh asan|tsan [ctest args]" >&2
    exit 2
    ;;
esac
