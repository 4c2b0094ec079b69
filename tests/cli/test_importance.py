#!/usr/bin/env python3
"""Importance puts the effort where the walkthrough looks: on a 4-room office floor whose
walkthrough enters 2 rooms, the importance-driven bake meshes the visited rooms' floors much more finely
than the unvisited ones' (the same floor, cut by the same furniture), while the unvisited rooms still get a
finite, lit solution.

Usage: test_importance.py WALKRAD SOURCE_DIR WORK_DIR"""
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bake_mesh import read_bake_mesh  # noqa: E402

walkrad, source, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
subprocess.run([sys.executable, os.path.join(source, "examples/office-floor/make_office_floor.py"), "--rooms", "4",
                "--detail", "0.05", "--out", work], check=True, stdout=subprocess.DEVNULL)
bake = os.path.join(work, "bake")
subprocess.run([walkrad, "bake", os.path.join(work, "office-floor-4.glb"), "--views",
                os.path.join(work, "office-floor-4-walkthrough.json"), "-o", bake, "-q", "--quality", "draft"],
               check=True, stdout=subprocess.DEVNULL)


positions, radiosity, indices = read_bake_mesh(walkrad, bake)
rooms = json.load(open(os.path.join(work, "office-floor-4-rooms.json")))["rooms"]
failures = []
if not all(math.isfinite(c) and c >= 0 for b in radiosity for c in b):
    failures.append("radiosity is not finite and non-negative everywhere")

stats = {r["name"]: {"triangles": 0, "lit": 0.0} for r in rooms}
for t in range(0, len(indices), 3):
    p = [positions[indices[t + k]] for k in range(3)]
    if any(abs(v[1]) > 1e-3 for v in p):
        continue  # floor triangles: the same floor in every room, cut by the same furniture legs
    c = [sum(v[k] for v in p) / 3 for k in range(3)]
    for r in rooms:  # every surface inside the room: floor, walls, ceiling, furniture
        if all(r["min"][k] - 1e-6 <= c[k] <= r["max"][k] + 1e-6 for k in (0, 1, 2)):
            stats[r["name"]]["triangles"] += 1
            stats[r["name"]]["lit"] = max(stats[r["name"]]["lit"], max(radiosity[indices[t]]))

visited = [r["name"] for r in rooms if r["visited"] and r["name"].startswith("room")]
unvisited = [r["name"] for r in rooms if not r["visited"] and r["name"].startswith("room")]
for name in visited + unvisited:
    print(f"{name}: {'visited' if name in visited else 'unvisited'}, {stats[name]['triangles']} triangles, "
          f"brightest B {stats[name]['lit']:.3g} W/m²")
least_visited = min(stats[n]["triangles"] for n in visited)
most_unvisited = max(stats[n]["triangles"] for n in unvisited)
# Measured at the default: see the printed counts. The bake is deterministic, so the margin guards the method, not noise.
if least_visited < 1.8 * most_unvisited:
    failures.append(f"visited floors have {least_visited} triangles, unvisited up to {most_unvisited}: expected 1.8x")
for name in unvisited:
    if not stats[name]["lit"] > 0:
        failures.append(f"{name}: unvisited room left dark")

print(f"{1 if not failures else 0} passed, {1 if failures else 0} failed")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)

