#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds (Release), runs every test with ctest, then
# the sanitizer run (build-asan/).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/install-deps.sh"
"$here/scripts/build.sh"
build=${WALKRAD_BUILD_DIR:-$here/build}
ctest --test-dir "$build" -j "${WALKRAD_JOBS:-2}" --output-on-failure --timeout 900
# The same suite under AddressSanitizer + UndefinedBehaviorSanitizer, less the heavy bakes
# (scripts/sanitize.sh, docs/reliability.md). WALKRAD_SANITIZE_TESTS=0 skips it.
if [ "${WALKRAD_SANITIZE_TESTS:-1}" != 0 ]; then
  "$here/scripts/sanitize.sh"
fi
