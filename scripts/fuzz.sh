#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, build-fuzz/) and runs each for a bounded time,
# one at a time on one core. Findings (crash, sanitizer report, unexpected exception, leak, timeout,
# out-of-memory) are written to tests/fuzz/crashers/<target>/ to be kept as regression inputs:
# the ctest tests fuzz.replay.* replay them with the saved corpus in every build.
# Usage: scripts/fuzz.sh [SECONDS per target, default 300] [TARGET...]   (targets: gltf chunk
#        walkthrough manifest mgf ies). WALKRAD_FUZZ_MERGE=1 merges new coverage into tests/fuzz/corpus/.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-300}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(gltf chunk walkthrough manifest mgf ies)
build=${WALKRAD_FUZZ_BUILD_DIR:-$here/build-fuzz}
"$here/scripts/install-deps.sh" --fuzz

if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWALKRAD_FUZZ=ON \
    -DWALKRAD_BUILD_PIPELINE=OFF -DWALKRAD_BUILD_RUNTIME=OFF -DWALKRAD_BUILD_BENCH=OFF
fi
cmake --build "$build" -j "${WALKRAD_JOBS:-2}" --target $(printf 'walkrad_fuzz_%s ' "${targets[@]}")

status=0
for t in "${targets[@]}"; do
  work="$build/fuzz-corpus/$t"             # the fuzzer's growing corpus (not committed)
  crashers="$here/tests/fuzz/crashers/$t"
  mkdir -p "$work" "$crashers"
  echo "fuzz: $t for $seconds s"
  # Limits per input: 10 s and 2 GiB. The inputs are bounded at 64 KiB (the seeds are smaller).
  if ! "$build/tests/fuzz/walkrad_fuzz_$t" "$work" "$here/tests/fuzz/corpus/$t" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
      -artifact_prefix="$crashers/" 2>&1 | tee "$build/fuzz-$t.log" | grep -E '^#[0-9]+ +(DONE|INITED)|ERROR|==[0-9]+==|stat::' ; then
    :
  fi
  if grep -qE 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer)|runtime error:|fuzz: unexpected' "$build/fuzz-$t.log"; then
    echo "fuzz: $t: FINDING (see $build/fuzz-$t.log and $crashers/)"
    status=1
  fi
  if [ "${WALKRAD_FUZZ_MERGE:-0}" = 1 ]; then
    "$build/tests/fuzz/walkrad_fuzz_$t" -merge=1 "$here/tests/fuzz/corpus/$t" "$work" -max_len=65536 >/dev/null 2>&1
  fi
done
exit $status
