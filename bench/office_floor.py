#!/usr/bin/env python3
"""office-floor: what importance saves, and how the view-independent bake grows with the building.
Generates the building with examples/office-floor/make_office_floor.py for each size, bakes it
view-independently and (for the default 8 rooms) importance-driven from its walkthrough, at one requested error,
and prints the tables for docs/performance.md.

Usage: bench/office_floor.py [BUILD_DIR] [ERROR] [SIZES]   (default build, 0.1, 1,2,4,8)"""
import json
import os
import subprocess
import sys
import time

build = sys.argv[1] if len(sys.argv) > 1 else "build"
eps = sys.argv[2] if len(sys.argv) > 2 else "0.1"
sizes = [int(x) for x in (sys.argv[3] if len(sys.argv) > 3 else "1,2,4,8").split(",")]
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
out = os.path.join(build, "bench-office")
walkrad = os.path.join(build, "pipeline/walkrad")
os.makedirs(out, exist_ok=True)


def generate(rooms):
    subprocess.run([sys.executable, os.path.join(root, "examples/office-floor/make_office_floor.py"), "--rooms", str(rooms),
                    "--out", out], check=True, stdout=subprocess.DEVNULL)
    suffix = "" if rooms == 8 else f"-{rooms}"
    return os.path.join(out, f"office-floor{suffix}.glb"), os.path.join(out, f"office-floor{suffix}-walkthrough.json")


def bake(name, scene, views, *args):
    path = os.path.join(out, name)
    t0 = time.monotonic()
    subprocess.run([walkrad, "bake", scene, "--views", views, "-o", path, "-q", "--error", eps, *args], check=True,
                   stdout=subprocess.DEVNULL)
    seconds = time.monotonic() - t0
    with open(os.path.join(path, "report.json")) as f:
        r = json.load(f)
    e = r["energy"]
    balance = sum(e["absorbed_w"]) / sum(e["emitted_w"])
    return seconds, r["counts"], balance


rows = []
for rooms in sizes:
    scene, views = generate(rooms)
    rows.append((rooms,) + bake(f"vi-{rooms}", scene, views, "--view-independent"))
print(f"View-independent bakes, --error {eps}, 2 threads, one run each\n")
print("| rooms | input polygons | elements | links | rays | time (s) | links × | time × | absorbed / emitted |")
print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
prev = None
for rooms, seconds, counts, balance in rows:
    growth = ("", "") if prev is None else (f"{counts['links'] / prev[1]['links']:.2f}", f"{seconds / prev[0]:.2f}")
    print(f"| {rooms} | {counts['input_polygons']} | {counts['elements']} | {counts['links']} | {counts['visibility_rays']} | "
          f"{seconds:.1f} | {growth[0]} | {growth[1]} | {balance:.3f} |")
    prev = (seconds, counts)

if 8 in sizes:
    scene, views = generate(8)
    vi = next(r for r in rows if r[0] == 8)
    imp = bake("importance-8", scene, views)
    print(f"\nImportance-driven against view-independent, 8 rooms, --error {eps} (walkthrough visits 2 rooms)\n")
    print("| oracle | elements | links | rays | time (s) | absorbed / emitted |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for name, (seconds, counts, balance) in [("view-independent (B·A·ρ·F)", vi[1:]), ("importance (B·I·ρ·F)", imp)]:
        print(f"| {name} | {counts['elements']} | {counts['links']} | {counts['visibility_rays']} | {seconds:.1f} | {balance:.3f} |")
    print(f"\nlinks ratio {imp[1]['links'] / vi[2]['links']:.3f}, time ratio {imp[0] / vi[1]:.3f}")
