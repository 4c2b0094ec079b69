#!/usr/bin/env python3
"""Volumetric against exact visibility on the dense hedge (examples/dense-hedge): bake time
(median of RUNS), Embree rays, grid integrations, links by kind of visibility, and the relative RMS
difference of the wall's radiosity as the walkthrough's camera sees it (96 x 96 rays, through
bench/walkrad_compare_bakes). Prints the table for docs/performance.md.

Usage: bench/volumes.py [BUILD_DIR] [RUNS] [OBJECTS] [THREADS] [cubes|leaves]   (default build, 3, 8400, 2,
cubes; leaves: flat square leaves, open sheets)"""
import json
import os
import statistics
import subprocess
import sys
import time

build = sys.argv[1] if len(sys.argv) > 1 else "build"
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 3
cubes = sys.argv[3] if len(sys.argv) > 3 else "8400"
threads = sys.argv[4] if len(sys.argv) > 4 else "2"
kind = sys.argv[5] if len(sys.argv) > 5 else "cubes"
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
out = os.path.join(build, "bench-volumes" if kind == "cubes" else "bench-volumes-" + kind)
walkrad = os.path.join(build, "pipeline/walkrad")
subprocess.run([sys.executable, os.path.join(root, "examples/dense-hedge/make_dense_hedge.py"), "--cubes", cubes, *(["--leaves"] if kind == "leaves" else []), out],
               check=True)
scene = os.path.join(out, "dense-hedge.glb")
views = os.path.join(out, "dense-hedge-walkthrough.json")

configs = [("exact rays (--effect volumes=off)", "exact", ["--effect", "volumes=off"]),
           ("volumes, penumbra ratio 1 (default)", "volume", []),
           ("volumes, penumbra ratio 0.5", "volume-0.5", ["--penumbra-ratio", "0.5"])]
results = {}
for k in range(runs):  # interleaved, so that a slow spell of the machine hits every configuration
    for _, name, args in configs:
        path = os.path.join(out, name)
        t0 = time.monotonic()
        subprocess.run([walkrad, "bake", scene, "--views", views, "-o", path, "-q", "--threads", threads, "--exposure", "1", *args],
                       check=True, stdout=subprocess.DEVNULL)
        results.setdefault(name, []).append(time.monotonic() - t0)

rms = {}
res = subprocess.run([os.path.join(build, "bench/walkrad_compare_bakes"), os.path.join(out, "exact"),
                      *[os.path.join(out, c[1]) for c in configs[1:]]], check=True, capture_output=True, text=True).stdout
for line in res.splitlines():
    path, value = line.rsplit(" ", 1)
    rms[os.path.basename(path)] = float(value)

def ratio(x):
    return f"{x:,.0f}" if x >= 100 else f"{x:.2f}"


base_time = statistics.median(results["exact"])
with open(os.path.join(out, "exact", "report.json")) as f:
    base_rays = json.load(f)["counts"]["visibility_rays"]
print(f"{cubes} {kind} ({(12 if kind == 'cubes' else 2) * int(cubes)} triangles), {runs} runs each, {threads} threads; "
      "times are medians.\n")
print("| visibility | links: exact / volume / unoccluded | Embree rays | grid integrations | bake (s) | time ratio | "
      "ray ratio | wall RMS vs exact |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for label, name, _ in configs:
    with open(os.path.join(out, name, "report.json")) as f:
        c = json.load(f)["counts"]
    t = statistics.median(results[name])
    rays = c["visibility_rays"]
    print(f"| {label} | {c['exact_links']:,} / {c['volume_links']:,} / {c['unoccluded_links']:,} | {rays:,} | "
          f"{c['grid_segments']:,} | {t:.2f} | {ratio(base_time / t)}× | {ratio(base_rays / max(rays, 1))}× | "
          f"{'—' if name == 'exact' else f'{100 * rms[name]:.2f}%'} |")
