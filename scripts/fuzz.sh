#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, build-fuzz/) and runs each for a bounded time.
# Findings (crash, sanitizer report, unexpected exception, leak, timeout, out-of-memory) are written
# to tests/fuzz/crashers/<target>/ to be kept as regression inputs: the ctest tests fuzz.replay.*
# replay them with the saved corpus in every build.
# Usage: scripts/fuzz.sh [SECONDS per target, default 300] [TARGET...]   (targets: gltf chunk
#        walkthrough manifest mgf ies). WALKRAD_FUZZ_PARALLEL=N runs N targets at a time (default 1,
#        one core each); WALKRAD_FUZZ_CPU=1 counts SECONDS as the fuzzer's CPU time, not the clock's
#        (a run shares its core with other work and still gets its time); WALKRAD_FUZZ_MERGE=1 merges
#        new coverage into tests/fuzz/corpus/.
# Each run appends a line to build-fuzz/fuzz-summary.tsv: target, commit, wall and CPU seconds,
# runs, coverage (edges), corpus size, peak RSS, result. docs/reliability.md's tables are these lines.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-300}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(gltf chunk walkthrough manifest mgf ies)
build=${WALKRAD_FUZZ_BUILD_DIR:-$here/build-fuzz}
# Each input is written to a file before it is read (tests/fuzz/fuzz_input.h): in memory, not on disk
# (3.0 times the runs a second here: 8,889 against 2,970 for the manifest target).
[ -z "${TMPDIR:-}" ] && [ -w /dev/shm ] && export TMPDIR=/dev/shm
parallel=${WALKRAD_FUZZ_PARALLEL:-1}
"$here/scripts/install-deps.sh" --fuzz

if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWALKRAD_FUZZ=ON \
    -DWALKRAD_BUILD_PIPELINE=OFF -DWALKRAD_BUILD_RUNTIME=OFF -DWALKRAD_BUILD_BENCH=OFF
fi
cmake --build "$build" -j "${WALKRAD_JOBS:-2}" --target $(printf 'walkrad_fuzz_%s ' "${targets[@]}")
commit=$(git -C "$here" rev-parse --short HEAD)$(git -C "$here" diff --quiet HEAD -- formats tests/fuzz || echo +)

# Runs one target; returns 1 on a finding.
fuzz_one() {
  local t=$1 work="$build/fuzz-corpus/$t" crashers="$here/tests/fuzz/crashers/$t" log="$build/fuzz-$t.log"
  mkdir -p "$work" "$crashers"
  echo "fuzz: $t for $seconds s"
  # Limits per input: 10 s and 2 GiB. The inputs are bounded at 64 KiB (the seeds are smaller).
  local wall=$seconds
  [ "${WALKRAD_FUZZ_CPU:-0}" = 1 ] && wall=$((seconds * 4))  # the watchdog below ends it
  /usr/bin/time -f 'fuzz-cpu: %U %S' -o "$build/fuzz-$t.time" \
    "$build/tests/fuzz/walkrad_fuzz_$t" "$work" "$here/tests/fuzz/corpus/$t" -max_total_time="$wall" \
    -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$crashers/" >"$log" 2>&1 &
  local timer=$!
  if [ "${WALKRAD_FUZZ_CPU:-0}" = 1 ]; then
    # libFuzzer ends on SIGINT with its final statistics; its CPU time is utime + stime in clock ticks.
    local tick pid used
    tick=$(getconf CLK_TCK)
    sleep 2
    pid=$(pgrep -P "$timer" -f "walkrad_fuzz_$t" | head -1 || true)
    while [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; do
      used=$(awk -v t="$tick" '{print int(($14 + $15) / t)}' "/proc/$pid/stat" 2>/dev/null || echo 0)
      if ((used >= seconds)); then kill -INT "$pid"; break; fi
      sleep 5
    done
  fi
  wait "$timer" || true
  grep -E '^#[0-9]+ +(DONE|INITED)|ERROR|==[0-9]+==|stat::' "$log" | sed "s/^/fuzz: $t: /" || true
  local result="no finding" status=0
  if grep -qE 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer)|runtime error:|fuzz: unexpected' "$log"; then
    echo "fuzz: $t: FINDING (see $log and $crashers/)"
    result=finding status=1
  fi
  local runs cov corpus rss cpu
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rss=$(sed -n 's/^stat::peak_rss_mb: *//p' "$log" | tail -1)
  cov=$(grep -oE ' cov: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || echo 0)
  corpus=$(grep -oE ' corp: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || echo 0)
  cpu=$(awk '/^fuzz-cpu:/ {printf "%.0f", $2 + $3}' "$build/fuzz-$t.time")
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s MB\t%s\n' "$t" "$commit" "$seconds" "$cpu" "${runs:-0}" "$cov" "$corpus" \
    "${rss:-?}" "$result" >>"$build/fuzz-summary.tsv"
  if [ "${WALKRAD_FUZZ_MERGE:-0}" = 1 ]; then
    "$build/tests/fuzz/walkrad_fuzz_$t" -merge=1 "$here/tests/fuzz/corpus/$t" "$work" -max_len=65536 >/dev/null 2>&1
  fi
  return $status
}

status=0
running=0
for t in "${targets[@]}"; do
  if ((running >= parallel)); then
    wait -n || status=1
    running=$((running - 1))
  fi
  fuzz_one "$t" &
  running=$((running + 1))
done
while ((running > 0)); do
  wait -n || status=1
  running=$((running - 1))
done
exit $status
