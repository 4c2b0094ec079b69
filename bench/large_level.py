#!/usr/bin/env python3
"""Large levels against their rays: generates office-floor levels of the given room counts
(examples/office-floor/make_office_floor.py, full detail, the walkthrough in 2 rooms), bakes each with
build/bench/walkrad_level_rays_bench (importance-driven; view-independent too with --vi), and prints
the table for docs/performance.md: per phase seconds, rays and peak memory, and the solve's rays per
second against a bare rtcOccluded1 loop over a sample of the same rays on as many threads, and against
the same sample cast as the solve casts it (each link's rays in one rtcOccluded1M call, coherent);
then, for each bake, its solve's rounds: links made, rays, seconds, and rays per second against the
same bare loop (report.json's solver.rounds).

Usage: bench/large_level.py [--build BUILD] [--rooms 32 64 150] [--vi] [--threads 2] [--every 1024] [--work DIR]
One bake per level and mode, as long as the bake takes (the 150-room level: minutes to a quarter of an
hour on 2 cores); the machine is shared, so quote the ratio, which comes from one process."""
import argparse
import json
import os
import subprocess
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ap = argparse.ArgumentParser()
ap.add_argument("--build", default=os.path.join(root, "build"))
ap.add_argument("--rooms", type=int, nargs="+", default=[32, 64, 150])
ap.add_argument("--vi", action="store_true", help="also bake each level view-independent")
ap.add_argument("--threads", type=int, default=2)
ap.add_argument("--every", type=int, default=1024,
                help="sample the links of one hash bucket in EVERY (the sample is held in memory: 48 bytes a ray)")
ap.add_argument("--work", default=None, help="where the levels and bakes go (default BUILD/bench-levels)")
args = ap.parse_args()
bench = os.path.join(args.build, "bench/walkrad_level_rays_bench")
work = args.work or os.path.join(args.build, "bench-levels")
os.makedirs(work, exist_ok=True)

print("| rooms | mode | links | phase: seconds / rays / peak MiB | solve rays/s | bare loop rays/s | ratio | "
      "batched loop rays/s | ratio |")
print("| ---: | --- | ---: | --- | ---: | ---: | ---: | ---: | ---: |")
by_round = []
for rooms in args.rooms:
    level = os.path.join(work, f"office-{rooms}")
    # The generator names a level of other than 8 rooms by its size.
    name = "office-floor" if rooms == 8 else f"office-floor-{rooms}"
    scene = os.path.join(level, name + ".glb")
    if not os.path.exists(scene):
        subprocess.run([sys.executable, os.path.join(root, "examples/office-floor/make_office_floor.py"), "--rooms", str(rooms),
                        "--out", level], check=True, stdout=subprocess.DEVNULL)
    for mode in ["importance"] + (["view-independent"] if args.vi else []):
        out = os.path.join(work, f"bake-{rooms}-{mode}")
        cmd = [bench, scene, out, "--views", os.path.join(level, name + "-walkthrough.json"), "--threads", str(args.threads),
               "--every", str(args.every)] + (["--view-independent"] if mode == "view-independent" else [])
        r = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout.strip().splitlines()[-1])
        phases = "; ".join(f"{p['name']} {p['seconds']:.1f}" + (f" / {p['rays'] / 1e6:.0f} M" if p.get("rays") else "") +
                           f" / {p['peak_mb']}" for p in r["phases"] if p["seconds"] >= 0.5)
        print(f"| {rooms} | {mode} | {r['links']:,} | {phases} | {r['solve_rays_per_s'] / 1e6:.2f} M | "
              f"{r['bare_rays_per_s'] / 1e6:.2f} M | {r['solve_over_bare']:.2f} | {r['batched_rays_per_s'] / 1e6:.2f} M | "
              f"{r['solve_over_batched']:.2f} |", flush=True)
        by_round.append((rooms, mode, r["rounds"]))

print()
print("| rooms | mode | round | links made | rays | seconds | rays/s | of the bare loop |")
print("| ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
for rooms, mode, rounds in by_round:
    for k, t in enumerate(rounds, 1):
        # A round read back from a checkpoint has no time, so no rate: "-".
        seconds = f"{t['seconds']:.1f}" if t["seconds"] is not None else "-"
        per_s = f"{t['rays_per_s'] / 1e6:.2f} M" if t["rays_per_s"] is not None else "-"
        over = f"{t['over_bare']:.2f}" if t["over_bare"] is not None else "-"
        print(f"| {rooms} | {mode} | {k} | {t['new_links']:,} | {t['rays'] / 1e6:.1f} M | {seconds} | {per_s} | {over} |")
