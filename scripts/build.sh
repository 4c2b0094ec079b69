#!/usr/bin/env bash
# Configures and builds walkrad (Release) in build/. Sized for small machines: at most 2 jobs unless
# WALKRAD_JOBS says otherwise. Extra arguments go to `cmake --build` (e.g. --target walkrad).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${WALKRAD_BUILD_DIR:-$here/build}
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$here" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" -j "${WALKRAD_JOBS:-2}" "$@"
