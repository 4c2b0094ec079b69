#!/usr/bin/env python3
"""walkrad sweep on the Cornell box with coarse settings (errors 1 and 0.1 per hierarchical method, two element
sizes for the classic one): sweep.csv has every documented field and a row per bake; for every method
the error against the path-traced reference falls as the setting gets finer, by more than the
reference's own error bar (16,384 paths a point: at 4,096 the bar, 2.55%, was wider than the drop
from error 1 to 0.1 once coarse bakes took near sources by their parts, 3.06% → 1.50%); the plots, report.md and reference image are written. A second sweep on the
same reference measures progressive refinement (--methods southwell), hemicube form factors (hemicube) and bakes without the final gather
(--without gather). An unknown method is
refused with exit code 2 and leaves no folder.

Usage: test_sweep.py WALKRAD SOURCE_DIR WORK_DIR"""
import csv
import json
import os
import shutil
import subprocess
import sys

walkrad, source, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
scene = os.path.join(source, "examples/cornell-box/cornell-box.gltf")
out = os.path.join(work, "cornell.sweep")
subprocess.run([walkrad, "sweep", scene, "-o", out, "-q", "--errors", "1,0.1", "--element-sizes", "0.12,0.06",
                "--points", "256", "--samples", "16384", "--image-width", "16", "--image-samples", "256"], check=True,
               stdout=subprocess.DEVNULL)

failures = []
FIELDS = ["method", "error", "element_size", "seconds", "cpu_seconds", "elements", "links", "rays", "triangles",
          "peak_rss_mib", "output_bytes", "points", "rms", "rms_weighted", "estimated_error", "max", "max_weighted", "bias", "image_pixels", "image_rms",
          "image_rms_weighted", "reference_ci_rms", "reference_ci_rms_weighted", "reference_image_ci_rms",
          "absorbed_over_emitted", "t_read", "t_prepare", "t_solve", "t_mesh", "t_write"]
with open(os.path.join(out, "sweep.csv")) as f:
    rows = list(csv.DictReader(f))
missing = [c for c in FIELDS if c not in rows[0]]
if missing:
    failures.append(f"sweep.csv lacks {missing}")
if len(rows) != 6:
    failures.append(f"{len(rows)} rows, expected 6 (2 classic, 2 view-independent, 2 importance)")
for r in rows:
    for c in ["seconds", "elements", "links", "rays", "peak_rss_mib", "output_bytes", "points"]:
        if not float(r[c]) > 0:
            failures.append(f"{r['method']}: {c} = {r[c]}, expected > 0")

for r in rows:  # the bake's own estimate, for the hierarchical methods (report.json solver.estimated_error)
    if r["method"] != "classic" and not float(r["estimated_error"]) > 0:
        failures.append(f"{r['method']} {r['error']}: estimated_error = {r['estimated_error']}, expected > 0")

# --reference reuses the first sweep's reference (the same points, to the byte) and refuses one
# traced with other settings.
again = os.path.join(work, "again.sweep")
subprocess.run([walkrad, "sweep", scene, "-o", again, "-q", "--reference", out, "--methods", "importance,southwell,hemicube", "--errors", "1",
                "--element-sizes", "0.12", "--without", "gather", "--points", "256", "--samples", "16384", "--image-width", "16",
                "--image-samples", "256"], check=True, stdout=subprocess.DEVNULL)
with open(os.path.join(out, "reference-points.csv"), "rb") as a, open(os.path.join(again, "reference-points.csv"), "rb") as b:
    if a.read() != b.read():
        failures.append("--reference: reference-points.csv differs from the sweep it reused")
# The same sweep measures progressive refinement (southwell: the classic matrix shot instead of
# gathered, so the same solution), the classic method with hemicube form factors, and each
# hierarchical run without the final gather.
with open(os.path.join(again, "sweep.csv")) as f:
    again_rows = {(r["method"], r["error"] or r["element_size"]): r for r in csv.DictReader(f)}
first = {(r["method"], r["error"] or r["element_size"]): r for r in rows}
if sorted(m for m, _ in again_rows) != ["hemicube", "importance", "importance-no-gather", "southwell"]:
    failures.append(f"--methods importance,southwell,hemicube --without gather: runs {sorted(again_rows)}")
else:
    sw = next(r for (m, _), r in again_rows.items() if m == "southwell")
    gs = next(r for (m, _), r in first.items() if m == "classic" and abs(float(r["element_size"]) - 0.12) < 1e-9)
    if abs(float(sw["rms_weighted"]) - float(gs["rms_weighted"])) > 1e-4:
        failures.append(f"southwell {sw['rms_weighted']} against gauss-seidel {gs['rms_weighted']} at element size 0.12")
other = subprocess.run([walkrad, "sweep", scene, "-o", os.path.join(work, "other.sweep"), "-q", "--reference", out,
                        "--methods", "importance", "--errors", "1", "--points", "128", "--samples", "4096",
                        "--image-width", "16", "--image-samples", "256"], capture_output=True, text=True)
if other.returncode == 0 or "another scene or settings" not in other.stderr:
    failures.append(f"--reference with other settings: exit {other.returncode}, {other.stderr.strip()[:200]}")

for method, setting in [("classic", "element_size"), ("hierarchical", "error"), ("importance", "error")]:
    runs = sorted((r for r in rows if r["method"] == method), key=lambda r: -float(r[setting]))  # coarse first
    if len(runs) != 2:
        failures.append(f"{method}: {len(runs)} runs")
        continue
    coarse, fine = float(runs[0]["rms_weighted"]), float(runs[1]["rms_weighted"])
    bar = float(runs[0]["reference_ci_rms_weighted"])
    print(f"{method}: error {100 * coarse:.2f}% → {100 * fine:.2f}% (reference error bar {100 * bar:.2f}%)")
    if not coarse - fine > bar:
        failures.append(f"{method}: the error does not fall by more than the reference's error bar as {setting} decreases "
                        f"({coarse:.4f} → {fine:.4f}, bar {bar:.4f})")
    if not float(runs[0]["image_rms_weighted"]) > float(runs[1]["image_rms_weighted"]):
        failures.append(f"{method}: the image error does not fall as {setting} decreases")

doc = json.load(open(os.path.join(out, "sweep.json")))
if len(doc["runs"]) != 6 or doc["reference"]["samples"] != 16384:
    failures.append("sweep.json does not hold the runs and the reference settings")
for f in ["error_vs_time.png", "cost_vs_error.png", "report.md", "reference-view-0.png", "reference-points.csv"]:
    if not os.path.getsize(os.path.join(out, f)) > 0:
        failures.append(f"{f} is missing or empty")
if os.path.exists(os.path.join(out, "bakes")):
    failures.append("the bakes were kept without --keep-bakes")

bad = subprocess.run([walkrad, "sweep", scene, "-o", os.path.join(work, "bad.sweep"), "-q", "--methods", "radiosity"],
                     capture_output=True, text=True)
if bad.returncode != 2 or "radiosity" not in bad.stderr or os.path.exists(os.path.join(work, "bad.sweep")):
    failures.append(f"an unknown method: exit {bad.returncode}, stderr {bad.stderr!r}")

for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
