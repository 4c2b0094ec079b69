#!/usr/bin/env python3
"""corridor levels: the error where the walkthrough looks, whatever the level's size.
Generates rooms along one corridor (examples/corridor-level/make_corridor_level.py: walls of no thickness, a
doorway a room, the corridor's floor, ceiling and far wall one quad each along the whole level, the walkthrough
in the first two rooms) for each room count, bakes it with the default settings on 2 threads, and measures it
with `walkrad sweep` against a path-traced reference of the same points (made once per level and kept in the work
folder: later runs reuse it). Prints the table of docs/accuracy.md.

Usage: bench/corridor_level.py BUILD_DIR WORK_DIR [ROOMS ...] [--samples N] [--points N]
  (default rooms 4 16 64, 131072 reference paths a point, 1024 points)"""
import argparse
import json
import os
import subprocess
import sys
import time

ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
ap.add_argument("build")
ap.add_argument("work")
ap.add_argument("rooms", nargs="*", type=int, default=[4, 16, 64])
ap.add_argument("--samples", type=int, default=131072)
ap.add_argument("--points", type=int, default=1024)
args = ap.parse_args()
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
walkrad = os.path.join(args.build, "pipeline/walkrad")
os.makedirs(args.work, exist_ok=True)


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


print("| rooms | corridor | wall (s) | peak MiB | elements | links | proven hidden | RMS (w) | bias | reference bar | estimate | estimate / RMS |")
print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for n in args.rooms:
    run([sys.executable, os.path.join(root, "examples/corridor-level/make_corridor_level.py"), "--rooms", str(n), "--out", args.work])
    scene = os.path.join(args.work, f"corridor-{n}.glb")
    views = os.path.join(args.work, f"corridor-{n}-walkthrough.json")
    ref = os.path.join(args.work, f"reference-{n}-{args.samples}")
    common = ["--views", views, "--methods", "none", "--points", str(args.points), "--samples", str(args.samples),
              "--image-width", "0", "--threads", "2", "--no-plots", "-q"]
    if not os.path.exists(os.path.join(ref, "reference.bin")):
        run([walkrad, "sweep", scene, "-o", ref, *common])
    bake = os.path.join(args.work, f"bake-{n}")
    t0 = time.monotonic()
    run([walkrad, "bake", scene, "--views", views, "-o", bake, "-q", "--threads", "2"])
    seconds = time.monotonic() - t0
    out = os.path.join(args.work, f"sweep-{n}")
    run([walkrad, "sweep", scene, "-o", out, "--reference", ref, "--measure", bake, *common])
    with open(os.path.join(out, "sweep.json")) as f:
        r = json.load(f)["runs"][0]
    with open(os.path.join(bake, "report.json")) as f:
        report = json.load(f)
    c = report["counts"]
    peak = max(p["peak_mb"] for p in report["phases"])
    est = r["estimated_error"] or 0.0
    print(f"| {n} | {5 * n} m | {seconds:.1f} | {peak:.0f} | {c['elements']} | {c['links']} | {c.get('proven_hidden_links', 0)} | "
          f"{100 * r['rms_weighted']:.2f}% | {100 * r['bias']:+.2f}% | {100 * r['reference_ci_rms_weighted']:.2f}% | "
          f"{100 * est:.2f}% | {est / r['rms_weighted']:.2f} |", flush=True)
