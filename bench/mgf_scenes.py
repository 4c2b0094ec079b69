#!/usr/bin/env python3
"""Bakes the classic MGF scenes of ../shared/scenes/mgf (view-independent, the hierarchical method) and
prints the table for docs/performance.md: faces read, polygons, elements, links, time, energy balance.
The scenes stay outside the repository (their licence is not ours).

Usage: bench/mgf_scenes.py [BUILD_DIR] [ERROR]   (default build, 0.1)"""
import json
import os
import subprocess
import sys
import time

build = sys.argv[1] if len(sys.argv) > 1 else "build"
eps = sys.argv[2] if len(sys.argv) > 2 else "0.1"
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
scenes = os.path.join(os.path.dirname(root), "shared/scenes/mgf")
out = os.path.join(build, "bench-mgf")
os.makedirs(out, exist_ok=True)

print(f"View-independent hierarchical bakes, --error {eps}, 2 threads, one run each\n")
print("| scene | input polygons | elements | links | rays | time (s) | absorbed / emitted | finite |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
for scene in ["cube.mgf", "corridor.mgf", "office3/office.mgf", "hospital/hosp.mgf"]:
    path = os.path.join(out, scene.replace("/", "-") + ".bake")
    t0 = time.monotonic()
    r = subprocess.run([os.path.join(build, "pipeline/walkrad"), "bake", os.path.join(scenes, scene), "-o", path, "-q",
                        "--view-independent", "--error", eps, "--input-folder", scenes], capture_output=True, text=True)
    seconds = time.monotonic() - t0
    if r.returncode != 0:
        print(f"| {scene} | failed: {r.stderr.strip()[:120]} |")
        continue
    report = json.load(open(os.path.join(path, "report.json")))
    c, e = report["counts"], report["energy"]
    balance = sum(e["absorbed_w"]) / sum(e["emitted_w"])
    finite = all(abs(x) < float("inf") for x in e["absorbed_w"] + e["emitted_w"])
    print(f"| {scene} | {c['input_polygons']} | {c['elements']} | {c['links']} | {c['visibility_rays']} | {seconds:.1f} | "
          f"{balance:.3f} | {'yes' if finite else 'no'} |")
