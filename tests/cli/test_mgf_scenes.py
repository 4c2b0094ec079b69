#!/usr/bin/env python3
"""Every classic MGF scene in ../shared/scenes/mgf loads and bakes view-independently with finite,
non-negative radiosity and a plausible power balance. Skipped (exit 0, said so) when the
scenes are not beside the repository. Usage: test_mgf_scenes.py WALKRAD SOURCE_DIR WORK_DIR"""
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bake_mesh import read_bake_mesh  # noqa: E402

walkrad, source, work = sys.argv[1:4]
scenes = os.path.join(os.path.dirname(os.path.abspath(source)), "shared/scenes/mgf")
if not os.path.isdir(scenes):
    print(f"skipped: no scenes at {scenes}")
    sys.exit(0)
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)

failures = []
# The hospital includes the collection's shared materials (../Materials): outside its own folder, so
# refused by default, naming the flag that admits them, and nothing written.
refused = os.path.join(work, "hospital-refused")
r = subprocess.run([walkrad, "bake", os.path.join(scenes, "hospital/hosp.mgf"), "-o", refused, "-q"],
                   capture_output=True, text=True)
if r.returncode != 3 or "lies outside the input folder" not in r.stderr or "--input-folder" not in r.stderr \
        or os.path.exists(refused):
    failures.append(f"hospital without --input-folder: exit {r.returncode}: {r.stderr.strip()[-300:]}")

names = ["cube.mgf", "corridor.mgf", "office3/office.mgf", "hospital/hosp.mgf"]
for name in names:
    out = os.path.join(work, name.replace("/", "-"))
    r = subprocess.run([walkrad, "bake", os.path.join(scenes, name), "-o", out, "-q", "--view-independent",
                        "--quality", "draft", "--input-folder", scenes], capture_output=True, text=True)
    if r.returncode != 0:
        failures.append(f"{name}: exit {r.returncode}: {r.stderr.strip()[-300:]}")
        continue
    report = json.load(open(os.path.join(out, "report.json")))
    e = report["energy"]
    balance = sum(e["absorbed_w"]) / sum(e["emitted_w"])
    values = [c for b in read_bake_mesh(walkrad, out)[1] for c in b]
    finite = all(math.isfinite(v) and v >= 0 for v in values)
    print(f"{name}: {report['counts']['input_polygons']} polygons, {report['counts']['links']} links, "
          f"{report['total_seconds']:.1f} s, absorbed/emitted {balance:.3f}, radiosity finite: {finite}")
    if not finite:
        failures.append(f"{name}: radiosity not finite and non-negative")
    if not 0.5 < balance < 1.05:  # open scenes lose light through their openings; none may create it
        failures.append(f"{name}: absorbed/emitted {balance:.3f}")

print(f"{len(names) + 1 - len(failures)} passed, {len(failures)} failed")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
