#!/usr/bin/env python3
"""Runs bench/visibility_bench.cpp (median of N repetitions, one thread) and prints the table for
docs/performance.md: rays/s of the form factor stage's visibility against a bare rtcOccluded1 loop on
the same rays. Usage: bench/visibility.py [BUILD_DIR] [REPETITIONS]"""
import json
import subprocess
import sys

build = sys.argv[1] if len(sys.argv) > 1 else "build"
reps = sys.argv[2] if len(sys.argv) > 2 else "5"
out = subprocess.run([f"{build}/bench/walkrad_visibility_bench", f"--benchmark_repetitions={reps}",
                      "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
                     check=True, capture_output=True, text=True).stdout
runs = {b["run_name"]: b for b in json.loads(out)["benchmarks"] if b.get("aggregate_name") == "median"}
ms = {name: b["real_time"] for name, b in runs.items()}  # milliseconds
rays = runs["BM_BareOccluded1Loop"]["rays"]
bare = rays / (ms["BM_BareOccluded1Loop"] / 1e3)
stream = rays / (ms["BM_StreamOccluded1M"] / 1e3)
stage_ms = ms["BM_FormFactors/visibility:1"] - ms["BM_FormFactors/visibility:0"]
stage = rays / (stage_ms / 1e3)
print(f"Cornell box, elements of 0.04 m, {rays / 1e6:.2f} M visibility rays, 1 thread, median of {reps} runs\n")
print("| what | time (ms) | rays/s | vs bare loop |")
print("| --- | ---: | ---: | ---: |")
print(f"| bare loop of rtcOccluded1 on the stage's rays | {ms['BM_BareOccluded1Loop']:.0f} | {bare / 1e6:.2f} M | 1.00 |")
print(f"| the same rays through rtcOccluded1M (RayScene) | {ms['BM_StreamOccluded1M']:.0f} | {stream / 1e6:.2f} M | {stream / bare:.2f} |")
print(f"| form factors without visibility | {ms['BM_FormFactors/visibility:0']:.0f} | | |")
print(f"| form factors with visibility | {ms['BM_FormFactors/visibility:1']:.0f} | | |")
print(f"| visibility stage (difference: sampling, shafts, batching, rays) | {stage_ms:.0f} | {stage / 1e6:.2f} M | {stage / bare:.2f} |")
