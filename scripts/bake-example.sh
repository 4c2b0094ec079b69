#!/usr/bin/env bash
# The main job on the bundled example: installs what is missing, builds (Release), bakes the Cornell
# box with its camera as the walkthrough, and renders the walkthrough headless to PNG frames.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/install-deps.sh"
"$here/scripts/build.sh" --target walkrad walkrad-view
build=${WALKRAD_BUILD_DIR:-$here/build}
out=$here/out/cornell-box.bake
"$build/pipeline/walkrad" bake "$here/examples/cornell-box/cornell-box.gltf" -o "$out"
"$build/runtime/walkrad-view" "$out" --headless --frames "$out/frames"
echo "bake: $out (manifest.json, chunk-*.glb, report.json)"
echo "frames: $out/frames"
