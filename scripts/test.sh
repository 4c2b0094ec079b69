#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds (Release), runs every test with ctest, then
# the readers' tests and fuzz replays under the sanitizers (build-asan-readers/).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/install-deps.sh"
"$here/scripts/build.sh"
build=${WALKRAD_BUILD_DIR:-$here/build}
ctest --test-dir "$build" -j "${WALKRAD_JOBS:-2}" --output-on-failure --timeout 900
# What reads untrusted files (the formats library's tests, the fuzz replays) under AddressSanitizer +
# UndefinedBehaviorSanitizer (scripts/sanitize.sh --readers, docs/reliability.md): the whole suite under
# them takes longer than CI's budget on its own. WALKRAD_SANITIZE_TESTS=all runs the whole suite, 0 skips it.
case "${WALKRAD_SANITIZE_TESTS:-readers}" in
  0) ;;
  all) "$here/scripts/sanitize.sh" ;;
  *) "$here/scripts/sanitize.sh" --readers ;;
esac
