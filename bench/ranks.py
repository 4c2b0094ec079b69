#!/usr/bin/env python3
"""A bake over several ranks against one process (see docs/scaling.md): generates an office-floor
level (examples/office-floor/make_office_floor.py, full detail, the walkthrough in 2 rooms) and bakes it
with --solver jacobi as one process of 1 and of 2 threads and as mpirun -np 2 ranks of 1 thread, one
after another, each under /usr/bin/time -v; prints the table for docs/scaling.md (wall, solve, gather
and mesh, links and their memory per rank, exchange seconds, peak memory per rank), whether the bakes'
chunks and manifests are byte-identical, and the model's fit: T(N) = R + D/N from the 1-thread and 2-rank
totals, and the two threads' speed-up.

Usage: bench/ranks.py [--build BUILD] [--rooms 32] [--detail 1] [--work DIR] [--skip-one-thread]
As long as the three bakes take (32 rooms: about 25 minutes on 2 cores; 150 rooms: about an hour).
Run it on an otherwise idle machine and quote ratios from one run of this script."""
import argparse
import filecmp
import glob
import json
import os
import re
import subprocess
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ap = argparse.ArgumentParser()
ap.add_argument("--build", default=os.path.join(root, "build"))
ap.add_argument("--rooms", type=int, default=32)
ap.add_argument("--work", default=None, help="where the level and bakes go (default BUILD/bench-ranks)")
ap.add_argument("--detail", type=float, default=1.0, help="make_office_floor.py's --detail (1: full)")
ap.add_argument("--skip-one-thread", action="store_true", help="no 1-thread bake (no fit of the model)")
args = ap.parse_args()
walkrad = os.path.join(args.build, "pipeline/walkrad")
work = args.work or os.path.join(args.build, "bench-ranks")
level = os.path.join(work, f"office-{args.rooms}-{args.detail:g}")
name = "office-floor" if args.rooms == 8 else f"office-floor-{args.rooms}"
scene, views = os.path.join(level, name + ".glb"), os.path.join(level, name + "-walkthrough.json")
if not os.path.exists(scene):
    subprocess.run([sys.executable, os.path.join(root, "examples/office-floor/make_office_floor.py"), "--rooms",
                    str(args.rooms), "--detail", str(args.detail), "--out", level], check=True, stdout=subprocess.DEVNULL)
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
mpirun = ["mpirun", "--oversubscribe", "--bind-to", "none"]
runs = [("one process, 2 threads", [], 2)] + ([] if args.skip_one_thread else [("one process, 1 thread", [], 1)]) + \
       [("2 ranks × 1 thread", mpirun + ["-np", "2"], 1)]


def bake(label, prefix, threads):
    out = os.path.join(work, "bake-" + re.sub(r"[^a-z0-9]+", "-", label.lower()).strip("-"))
    cmd = ["/usr/bin/time", "-v", *prefix, walkrad, "bake", scene, "--views", views, "-o", out, "--solver", "jacobi",
           "--threads", str(threads), "-q"]
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"{label}: exit {r.returncode}: {r.stderr[-500:]}")
    report = json.load(open(os.path.join(out, "report.json")))
    # /usr/bin/time's "Elapsed (wall clock) time (h:mm:ss or m:ss): 7:49.36"
    clock = re.search(r"Elapsed \(wall clock\) time.*: ([\d:.]+)", r.stderr).group(1).split(":")
    report["wall_s"] = sum(float(x) * 60 ** k for k, x in enumerate(reversed(clock)))
    return out, report


def seconds(report, *names):
    return sum(p["seconds"] for p in report["phases"] if not names or p["name"] in names)


def ranks_of(report):
    """Per rank: links held, link MiB, exchange seconds, peak MiB (one process: its own)."""
    per = report.get("ranks", {}).get("per_rank")
    if per:
        return [(p["links_held"], p["link_mb_peak"], p["exchange_seconds"], p["peak_memory_mb"]) for p in per]
    return [(report["counts"]["links"], report["solver"]["link_mb_peak"], 0.0, max(p["peak_mb"] for p in report["phases"]))]


def joined(values, form):
    return " / ".join(form.format(v) for v in values)


print("| run | wall (s) | solve (s) | gather + mesh (s) | links held, per rank | link MiB per rank | exchange (s) | "
      "peak RSS per rank (MiB) |")
print("| --- | ---: | ---: | ---: | --- | --- | --- | ---: |")
results = {}
for label, prefix, threads in runs:
    out, report = bake(label, prefix, threads)
    results[label] = (out, report)
    held, mb, exchange, peak = zip(*ranks_of(report))
    print(f"| {label} | {report['wall_s']:.1f} | {seconds(report, 'solve'):.1f} | {seconds(report, 'gather', 'mesh'):.1f} | "
          f"{joined(held, '{:,}')} | {joined(mb, '{:,.0f}')} | {joined(exchange, '{:.1f}')} | {joined(peak, '{:,}')} |",
          flush=True)


def files(folder):
    return sorted(os.path.basename(p) for p in glob.glob(os.path.join(folder, "chunk-*.glb"))) + ["manifest.json"]


first = results[runs[0][0]][0]
same = all(files(out) == files(first) and all(filecmp.cmp(os.path.join(first, f), os.path.join(out, f), shallow=False)
                                              for f in files(first)) for out, _ in results.values())
print(f"\nchunks and manifests byte-identical: {'yes' if same else 'NO'}")
one, divided = results["one process, 2 threads"][1], results["2 ranks × 1 thread"][1]
t2, tr = one["wall_s"], divided["wall_s"]
print(f"2 ranks of 1 thread / one process of 2 threads: {tr / t2:.2f}×")
print(f"link memory per rank / one process's: {max(r[1] for r in ranks_of(divided)) / one['solver']['link_mb_peak']:.2f}×")
if "one process, 1 thread" in results:
    t1 = results["one process, 1 thread"][1]["wall_s"]
    d = 2 * (t1 - tr)
    print(f"model: D = {d:.0f} s divided, R = {t1 - d:.0f} s replicated (1 thread); two threads {t1 / t2:.2f}×")
sys.exit(0 if same else 1)
