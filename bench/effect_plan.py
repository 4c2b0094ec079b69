#!/usr/bin/env python3
"""What the effect plan saves: each example baked with its effect plan and with every effect
that costs work forced on (indirect light, visibility rays, importance where there are viewpoints),
median of RUNS bakes each, 2 threads. Prints the table for docs/performance.md.

Usage: bench/effect_plan.py [BUILD_DIR] [RUNS]   (default build, 3)
The office floor is generated with one room (examples/office-floor/make_office_floor.py --rooms 1)."""
import json
import os
import statistics
import subprocess
import sys
import time

build = sys.argv[1] if len(sys.argv) > 1 else "build"
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 3
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
out = os.path.join(build, "bench-effects")
walkrad = os.path.join(build, "pipeline/walkrad")
os.makedirs(out, exist_ok=True)

subprocess.run([sys.executable, os.path.join(root, "examples/office-floor/make_office_floor.py"), "--rooms", "1", "--out", out],
               check=True, stdout=subprocess.DEVNULL)
EXAMPLES = [
    ("cornell-box", os.path.join(root, "examples/cornell-box/cornell-box.gltf"), []),
    ("office-floor (1 room)", os.path.join(out, "office-floor-1.glb"), ["--views", os.path.join(out, "office-floor-1-walkthrough.json")]),
    ("lamp-room", os.path.join(root, "examples/lamp-room/lamp-room.gltf"), []),
    ("lamp-room --empty", os.path.join(root, "examples/lamp-room/lamp-room-empty.gltf"), []),
]
FORCED = ["--effect", "indirect=on", "--effect", "visibility=on"]


def bake(scene, args, name):
    times, report = [], None
    for k in range(runs):
        path = os.path.join(out, name)
        t0 = time.monotonic()
        subprocess.run([walkrad, "bake", scene, "-o", path, "-q", *args], check=True, stdout=subprocess.DEVNULL)
        times.append(time.monotonic() - t0)
        with open(os.path.join(path, "report.json")) as f:
            report = json.load(f)
    return statistics.median(times), report


print(f"Each example baked {runs} times each way at the default error (median wall time, 2 threads).\n")
print("| example | effects the plan turns off | plan: time (s) | rays | all forced on: time (s) | rays | forced / plan time |")
print("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
for label, scene, args in EXAMPLES:
    t_plan, r_plan = bake(scene, args, "plan")
    forced = FORCED + (["--effect", "importance=on"] if r_plan["counts"].get("viewpoints", 0) else [])
    t_all, r_all = bake(scene, args + forced, "forced")
    off = [k for k, e in r_plan["effects"].items() if not e["on"] and k in ("indirect", "visibility", "importance")]
    rays = lambda r: r["counts"].get("visibility_rays", 0) + r["counts"].get("light_rays", 0)
    print(f"| {label} | {', '.join(off) or 'none'} | {t_plan:.2f} | {rays(r_plan):,} | {t_all:.2f} | {rays(r_all):,} | {t_all / t_plan:.2f} |")
