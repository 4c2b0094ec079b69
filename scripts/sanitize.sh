#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (docs/reliability.md): builds
# build-asan/ (the default compiler, -O1 -g1, WALKRAD_SANITIZE=ON, no benchmarks) and runs ctest there,
# less the whole-scene bakes that take minutes under ASan (the Release run covers them): the tests
# labelled "heavy" and the pipeline's Cornell-box bakes (CornellBake.*, CornellHierarchical.*; 6-10
# minutes each under ASan on 2 cores), and the stability suite (label "stability": numerics the Release
# run checks; 6 minutes of CPU under ASan, which kept CI near its 20-minute budget). Still run: every reader, the fuzz replays, the CLI bad-input
# tests (real bakes of the Cornell box), the pipeline's unit tests, the runtime rendering a real bake. Any sanitizer report fails the test that triggered it (-fno-sanitize-recover=all).
# Leaks inside Mesa's driver are suppressed (scripts/lsan.supp: third-party libraries only).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${WALKRAD_ASAN_BUILD_DIR:-$here/build-asan}
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$here" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" \
    -DWALKRAD_SANITIZE=ON -DWALKRAD_BUILD_BENCH=OFF
fi
cmake --build "$build" -j "${WALKRAD_JOBS:-2}"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$here/scripts/lsan.supp:print_suppressions=0}
ctest --test-dir "$build" -j "${WALKRAD_JOBS:-2}" --output-on-failure --timeout 900 -LE "heavy|stability" \
  -E '^(CornellBake|CornellHierarchical)\.'
