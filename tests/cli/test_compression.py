#!/usr/bin/env python3
"""Draco on real output: the Cornell box's chunks are at least 5× smaller than the same bake
uncompressed, and decode back to the same vertices with _RADIOSITY within the stated error (walkrad diff,
relative RMS ≤ 1e-3). Usage: test_compression.py WALKRAD SOURCE_DIR WORK_DIR"""
import glob
import os
import shutil
import subprocess
import sys

walkrad, source, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
scene = os.path.join(source, "examples/cornell-box/cornell-box.gltf")
plain, draco = os.path.join(work, "plain"), os.path.join(work, "draco")
for out, extra in [(plain, ["--no-compression"]), (draco, [])]:
    subprocess.run([walkrad, "bake", scene, "-o", out, "-q", *extra], check=True, stdout=subprocess.DEVNULL)
size = lambda d: sum(os.path.getsize(p) for p in glob.glob(os.path.join(d, "chunk-*.glb")))
ratio = size(plain) / size(draco)
r = subprocess.run([walkrad, "diff", plain, draco, "--tolerance", "1e-3"], capture_output=True, text=True)
print(f"uncompressed {size(plain)} B, Draco {size(draco)} B: {ratio:.1f}×")
print(r.stdout, end="")
failures = []
if ratio < 5:
    failures.append(f"Draco chunks only {ratio:.2f}× smaller")
# The only difference diff may report is the setting itself.
others = [l for l in r.stdout.splitlines() if l.startswith("differs:") and "setting compress" not in l]
if others:
    failures.append("decoded chunks differ beyond the stated error: " + "; ".join(others))
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
