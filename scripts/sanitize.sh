#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (docs/reliability.md), with the
# default compiler, WALKRAD_SANITIZE=ON and no benchmarks. Any sanitizer report fails the test that
# triggered it (-fno-sanitize-recover=all). Leaks inside Mesa's driver are suppressed (scripts/lsan.supp:
# third-party libraries only).
#
#   scripts/sanitize.sh --readers   what reads untrusted files: the formats library's tests (every reader,
#                                   bad input, truncations) and the fuzz replays (ctest label "readers"),
#                                   in build-asan-readers/ at -O0 -g1 (half the compile time of -O1 for
#                                   tests that run in seconds). Builds only those targets. scripts/test.sh
#                                   runs this: the whole suite below took about 25 minutes here (an
#                                   incremental build and 20 minutes of tests), past CI's 20-minute budget.
#   scripts/sanitize.sh             the whole suite, in build-asan/ at -O1 -g1, less the whole-scene bakes
#                                   that take minutes under ASan (the Release run covers them): the tests
#                                   labelled "heavy", the pipeline's Cornell-box bakes (CornellBake.*,
#                                   CornellHierarchical.*) and the stability suite (label "stability":
#                                   numerics the Release run checks). Run it before landing a change to
#                                   the pipeline or the runtime.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
scope=${1:-all}
case "$scope" in
  --readers) scope=readers; build=${WALKRAD_ASAN_BUILD_DIR:-$here/build-asan-readers}; optimise="-O0 -g1" ;;
  all) build=${WALKRAD_ASAN_BUILD_DIR:-$here/build-asan}; optimise="-O1 -g1" ;;
  *) echo "usage: $0 [--readers]" >&2; exit 2 ;;
esac
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$here" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$optimise" -DCMAKE_C_FLAGS_RELWITHDEBINFO="$optimise" \
    -DWALKRAD_SANITIZE=ON -DWALKRAD_BUILD_BENCH=OFF
fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$here/scripts/lsan.supp:print_suppressions=0}
if [ "$scope" = readers ]; then
  cmake --build "$build" -j "${WALKRAD_JOBS:-2}" --target walkrad_readers  # tests/fuzz/CMakeLists.txt
  ctest --test-dir "$build" -j "${WALKRAD_JOBS:-2}" --output-on-failure --timeout 900 -L readers
  exit
fi
cmake --build "$build" -j "${WALKRAD_JOBS:-2}"
ctest --test-dir "$build" -j "${WALKRAD_JOBS:-2}" --output-on-failure --timeout 900 -LE "heavy|stability" \
  -E '^(CornellBake|CornellHierarchical)\.'
