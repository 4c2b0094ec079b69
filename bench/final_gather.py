#!/usr/bin/env python3
"""What the final gather costs, or its discontinuity meshing: the default bake with and
without the effect (--effect EFFECT=off; EFFECT gather or discontinuities), alternating, the phases from
report.json (solve; gather: the adaptive mesh's tests and splits; mesh: the discontinuity cuts, the
vertices' point evaluation and the gather's direct light), the triangles and the chunk bytes. The
Cornell box three times each (medians), office-floor with 8 rooms (--detail 0.05) once each.

Usage: bench/final_gather.py [BUILD_DIR] [OUT] [EFFECT]   (default build, build/bench-gather, gather)"""
import json
import os
import statistics
import subprocess
import sys

build = sys.argv[1] if len(sys.argv) > 1 else "build"
out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(build, "bench-gather")
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
walkrad = os.path.join(build, "pipeline/walkrad")
effect = sys.argv[3] if len(sys.argv) > 3 else "gather"
os.makedirs(out, exist_ok=True)


def bake(name, scene, extra):
    folder = os.path.join(out, name)
    subprocess.run([walkrad, "bake", scene, "-o", folder, "-q", "--threads", "2", *extra], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(folder, "report.json")) as f:
        r = json.load(f)
    phase = {}
    for p in r["phases"]:
        phase[p["name"]] = phase.get(p["name"], 0.0) + p["seconds"]
    size = sum(os.path.getsize(os.path.join(folder, c)) for c in os.listdir(folder) if c.startswith("chunk-"))
    return {"total": r["total_seconds"], "solve": phase.get("solve", 0), "gather": phase.get("gather", 0),
            "mesh": phase.get("mesh", 0), "triangles": r["counts"]["triangles"], "bytes": size}


office = os.path.join(out, "office-8-scene")
subprocess.run([sys.executable, os.path.join(root, "examples/office-floor/make_office_floor.py"), "--rooms", "8", "--detail",
                "0.05", "--out", office], check=True, stdout=subprocess.DEVNULL)
cases = [("Cornell box", os.path.join(root, "examples/cornell-box/cornell-box.gltf"), [], 3),
         ("office-floor, 8 rooms", os.path.join(office, "office-floor.glb"),
          ["--views", os.path.join(office, "office-floor-walkthrough.json")], 1)]
print(f"| scene | {effect} | total (s) | solve (s) | gather (s) | mesh (s) | triangles | chunk bytes |")
print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
for title, scene, extra, runs in cases:
    results = {True: [], False: []}
    for k in range(runs):
        for on in (True, False):
            results[on].append(bake(f"{title[:6].strip()}-{on}-{k}", scene, extra + ([] if on else ["--effect", effect + "=off"])))
    for on in (True, False):
        rs = results[on]
        m = {key: statistics.median(r[key] for r in rs) for key in rs[0]}
        print(f"| {title} | {'on' if on else 'off'} | {m['total']:.2f} | {m['solve']:.2f} | {m['gather']:.2f} | {m['mesh']:.2f} | "
              f"{m['triangles']:.0f} | {m['bytes']:.0f} |")
