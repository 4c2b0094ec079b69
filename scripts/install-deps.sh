#!/usr/bin/env bash
# Installs what walkrad's build, tests and examples need, from Debian packages and the npm registry.
# Idempotent: it asks apt and npm only for what is missing, and does nothing when all is present.
# --fuzz: also clang and its libFuzzer runtime, for scripts/fuzz.sh (the CI only replays, with gcc).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

packages=(
  build-essential cmake ninja-build pkg-config python3
  libtinygltf-dev libdraco-dev libembree-dev libopenvdb-dev libboost-iostreams-dev libopenvdb-tools
  libmeshoptimizer-dev libtbb-dev nlohmann-json3-dev libstb-dev libcli11-dev libfmt-dev libspdlog-dev libpolyclipping-dev
  libgtest-dev libgmock-dev libbenchmark-dev python3-matplotlib libopenmpi-dev openmpi-bin
  libglfw3-dev libepoxy-dev libegl-dev libgl-dev libopengl-dev libgl1-mesa-dri libegl-mesa0 xvfb xauth
  chromium
)

[ "${1:-}" = --fuzz ] && packages+=(clang libclang-rt-14-dev)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
# Node.js runs the Khronos glTF validator and builds the web viewer; any Node >= 18 will do (Debian's,
# or one already present). Debian's chromium runs the web viewer's test (web/test/test_web.mjs).
command -v node >/dev/null 2>&1 || missing+=(nodejs)
command -v npm >/dev/null 2>&1 || missing+=(npm)

if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}"
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The validator is pinned by tools/validator/package-lock.json.
if [ ! -d "$here/tools/validator/node_modules/gltf-validator" ]; then
  echo "install-deps: installing the Khronos glTF validator (npm)"
  (cd "$here/tools/validator" && npm ci --no-audit --no-fund --loglevel=error)
fi

# The web viewer's three.js, its bundler (esbuild) and the browser driver of its test (playwright-core),
# pinned by web/package-lock.json.
if [ ! -d "$here/web/node_modules/three" ] || [ ! -d "$here/web/node_modules/esbuild" ] || [ ! -d "$here/web/node_modules/playwright-core" ]; then
  echo "install-deps: installing the web viewer's packages (npm)"
  (cd "$here/web" && npm ci --no-audit --no-fund --loglevel=error)
fi
