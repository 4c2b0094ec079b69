#!/usr/bin/env python3
"""Hierarchical against classic radiosity on the Cornell box: error against a fine classic solution
(relative RMS of radiosity where the camera looks) and bake time, for several requested errors and the classic
default. Prints the table for docs/performance.md.

Usage: bench/hierarchical_vs_classic.py [BUILD_DIR] [FINE_ELEMENT_SIZE]   (default build, 0.015 m)
The fine reference takes minutes; it is kept in BUILD_DIR/bench-bakes/ and reused when present."""
import json
import os
import subprocess
import sys
import time

build = sys.argv[1] if len(sys.argv) > 1 else "build"
fine_size = sys.argv[2] if len(sys.argv) > 2 else "0.015"
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
scene = os.path.join(root, "examples/cornell-box/cornell-box.gltf")
out = os.path.join(build, "bench-bakes")
walkrad = os.path.join(build, "pipeline/walkrad")


def bake(name, *args):
    path = os.path.join(out, name)
    t0 = time.monotonic()
    subprocess.run([walkrad, "bake", scene, "-o", path, "-q", "--exposure", "1", *args], check=True,
                   stdout=subprocess.DEVNULL)
    seconds = time.monotonic() - t0
    with open(os.path.join(path, "report.json")) as f:
        report = json.load(f)
    return path, seconds, report["counts"]


os.makedirs(out, exist_ok=True)
fine_name = f"classic-fine-{fine_size}"
fine_path = os.path.join(out, fine_name)
if os.path.exists(os.path.join(fine_path, "report.json")):
    with open(os.path.join(fine_path, "report.json")) as f:
        r = json.load(f)
    fine = (fine_path, r["total_seconds"], r["counts"])
else:
    fine = bake(fine_name, "--method", "classic", "--element-size", fine_size, "--rays", "2")

runs = [("classic, default mesh", bake("classic-default", "--method", "classic"))]
for eps in ["0.4", "0.2", "0.1", "0.05"]:
    runs.append((f"hierarchical, --error {eps}", bake(f"hier-{eps}", "--error", eps)))
for eps in ["0.2", "0.1"]:
    runs.append((f"hierarchical view-independent, --error {eps}", bake(f"hier-vi-{eps}", "--error", eps, "--view-independent")))
rms = {}
res = subprocess.run([os.path.join(build, "bench/walkrad_compare_bakes"), fine[0], *[r[1][0] for r in runs]],
                     check=True, capture_output=True, text=True).stdout
for line in res.splitlines():
    path, value = line.rsplit(" ", 1)
    rms[path] = float(value)

print(f"Reference: classic, elements of {fine_size} m, 2 rays per point: {fine[2]['elements']} elements, "
      f"{fine[1]:.1f} s\n")
print("| method | elements | links or pairs | rays | time (s) | relative RMS vs reference |")
print("| --- | ---: | ---: | ---: | ---: | ---: |")
for name, (path, seconds, counts) in runs:
    links = counts.get("links", counts.get("form_factor_pairs"))
    print(f"| {name} | {counts['elements']} | {links} | {counts['visibility_rays']} | {seconds:.2f} | {100 * rms[path]:.2f}% |")
