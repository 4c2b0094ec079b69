#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds (Release), runs every test with ctest.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/install-deps.sh"
"$here/scripts/build.sh"
build=${WALKRAD_BUILD_DIR:-$here/build}
ctest --test-dir "$build" -j "${WALKRAD_JOBS:-2}" --output-on-failure --timeout 900
