#!/usr/bin/env python3
"""Runtime: time to first frame and frame CPU time of walkrad-view, headless on this machine's renderer
(Mesa llvmpipe), for the Cornell box and an office floor; and streaming along the office floor's path
with a budget of a third of its bytes. Bakes what it plays (once, into BUILD_DIR/bench-runtime), then
plays each bake RUNS times as fast as possible (--fps 0) and prints the medians over the runs of
stats.json's figures, as a table for docs/performance.md.

Frame CPU time is what the render thread spends in Player::update + Player::draw (streaming, upload,
draw calls); llvmpipe rasterises on its own threads, and the read-back of each frame to PNG is not in it.

Usage: bench/runtime.py [BUILD_DIR] [RUNS] [HEIGHT]   (default build, 5, 512)"""
import json
import os
import statistics
import subprocess
import sys

build = sys.argv[1] if len(sys.argv) > 1 else "build"
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5
height = sys.argv[3] if len(sys.argv) > 3 else "512"
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
out = os.path.join(build, "bench-runtime")
walkrad = os.path.join(build, "pipeline/walkrad")
view = os.path.join(build, "runtime/walkrad-view")
os.makedirs(out, exist_ok=True)


def bake(name, scene, *args):
    path = os.path.join(out, name)
    if not os.path.exists(os.path.join(path, "manifest.json")):
        subprocess.run([walkrad, "bake", scene, "-o", path, "-q", *args], check=True, stdout=subprocess.DEVNULL)
    return path


def play(bake_dir, *args):
    frames = os.path.join(out, "frames")
    subprocess.run([view, bake_dir, "--frames", frames, "--height", height, *args], check=True,
                   stdout=subprocess.DEVNULL)
    with open(os.path.join(frames, "stats.json")) as f:
        return json.load(f)


cornell = bake("cornell-box", os.path.join(root, "examples/cornell-box/cornell-box.gltf"))
# The Cornell box has one camera: a 240-frame dolly from it into the box, for frame times to sample.
dolly = os.path.join(out, "cornell-dolly.json")
with open(dolly, "w") as f:
    json.dump({"format": "walkrad-walkthrough", "version": 1, "path": {"frames": 240, "yfov_deg": 39.3, "aspect": 1.0,
               "keyframes": [{"time": 0, "position": [0.278, 0.273, -0.8], "target": [0.278, 0.273, 0.28]},
                             {"time": 1, "position": [0.278, 0.273, -0.2], "target": [0.2, 0.25, 0.56]}]}}, f)
subprocess.run([sys.executable, os.path.join(root, "examples/office-floor/make_office_floor.py"), "--rooms", "8",
                "--detail", "0.25", "--out", out], check=True, stdout=subprocess.DEVNULL)
office = bake("office-floor", os.path.join(out, "office-floor.glb"), "--views",
              os.path.join(out, "office-floor-walkthrough.json"), "--quality", "draft", "--chunk-triangles", "2000")

whole = play(office, "--fps", "0")["resident_bytes"]
cases = [("Cornell box, its camera", cornell, ["--fps", "0"]),
         ("Cornell box, 240-frame dolly (--path)", cornell, ["--fps", "0", "--path", dolly]),
         ("office floor, no budget", office, ["--fps", "0"]),
         ("office floor, budget 1/3, 30 frames/s", office, ["--budget-mb", f"{whole / 3 / 1e6:.6f}"])]
print(f"walkrad-view headless, {height} px high, median of {runs} runs; office floor: {whole} B resident in all")
print("| bake | chunks | frames | time to first frame (ms) | frame CPU median (ms) | frame CPU p99 (ms) | "
      "max resident (B) | loads | misses |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for name, bake_dir, args in cases:
    s = [play(bake_dir, *args) for _ in range(runs)]
    med = lambda f: statistics.median(f(x) for x in s)
    print(f"| {name} | {s[0]['chunks_total']} | {s[0]['frames']} | {med(lambda x: x['time_to_first_frame_ms']):.1f} | "
          f"{med(lambda x: x['frame_cpu_ms']['median']):.2f} | {med(lambda x: x['frame_cpu_ms']['p99']):.2f} | "
          f"{max(x['max_resident_bytes'] for x in s)} | {med(lambda x: x['chunk_loads']):.0f} | "
          f"{max(x['chunk_misses'] for x in s)} |")
