#!/usr/bin/env python3
"""Merges the runs of several `walkrad sweep` folders of the same scene, walkthrough and reference
settings into one folder, and plots it. The reference is deterministic (every point has its own random
stream), so sweeps with the same --points/--samples/--seed/--image-* measure against the same
reference: this script refuses to merge unless their reference-points.csv are byte-identical.
Used for docs/accuracy.md, where a long classic run and a later hierarchical sweep share one plot.

Usage: bench/merge_sweeps.py OUT SWEEP_DIR[:METHOD,...]...   (only those methods' runs from that folder;
the first folder's reference images are kept)"""
import csv
import filecmp
import json
import os
import shutil
import subprocess
import sys

out = sys.argv[1]
folders, keep = [], []
for arg in sys.argv[2:]:
    folder, _, methods = arg.partition(":")
    folders.append(folder)
    keep.append(set(methods.split(",")) if methods else None)
first, *rest = folders
for other in rest:
    if not filecmp.cmp(os.path.join(first, "reference-points.csv"), os.path.join(other, "reference-points.csv"), shallow=False):
        sys.exit(f"merge_sweeps: {other} was measured against another reference than {first}")
shutil.rmtree(out, ignore_errors=True)
shutil.copytree(first, out)
doc = json.load(open(os.path.join(first, "sweep.json")))
doc["command"] = " ; ".join([doc["command"]] + [json.load(open(os.path.join(o, "sweep.json")))["command"] for o in rest])
doc["runs"] = []
for folder, methods in zip(folders, keep):
    doc["runs"] += [r for r in json.load(open(os.path.join(folder, "sweep.json")))["runs"] if methods is None or r["method"] in methods]
with open(os.path.join(out, "sweep.json"), "w") as f:
    json.dump(doc, f, indent=2)
rows, fields = [], None
for folder, methods in zip(folders, keep):
    with open(os.path.join(folder, "sweep.csv")) as f:
        reader = csv.DictReader(f)
        fields = fields or reader.fieldnames
        rows += [r for r in reader if methods is None or r["method"] in methods]
with open(os.path.join(out, "sweep.csv"), "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=fields, restval="", extrasaction="ignore")
    writer.writeheader()
    writer.writerows(rows)
subprocess.run(["/usr/bin/python3", os.path.join(out, "plot_sweep.py"), out], check=True)
print(f"merge_sweeps: {len(doc['runs'])} runs in {out}")
