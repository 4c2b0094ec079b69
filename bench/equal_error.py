#!/usr/bin/env python3
"""Importance-driven against view-independent at equal error: for each importance-driven
run of a `walkrad sweep`, the view-independent run with the same weighted error, interpolated log-log
between the two that bracket it, and the ratios of their CPU time, wall time and links.
Usage: bench/equal_error.py SWEEP_DIR"""
import csv
import math
import os
import sys

rows = list(csv.DictReader(open(os.path.join(sys.argv[1], "sweep.csv"))))
vi = sorted([r for r in rows if r["method"] == "hierarchical"], key=lambda r: -float(r["rms_weighted"]))
imp = [r for r in rows if r["method"] == "importance"]
print("| importance --error | error (w) | balance | CPU s | links | view-independent at that error: CPU s | links | CPU ratio | wall ratio | links ratio |")
print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for r in imp:
    e = float(r["rms_weighted"])
    for a, b in zip(vi, vi[1:]):
        ea, eb = float(a["rms_weighted"]), float(b["rms_weighted"])
        if eb <= e <= ea:
            t = math.log(ea / e) / math.log(ea / eb)
            at = lambda key: float(a[key]) * (float(b[key]) / float(a[key])) ** t
            cpu, wall, links = at("cpu_seconds"), at("seconds"), at("links")
            print(f"| {r['error']} | {100 * e:.2f}% | {float(r['absorbed_over_emitted']):.3f} | {float(r['cpu_seconds']):.1f} | "
                  f"{int(r['links']):,} | {cpu:.1f} | {int(links):,} | {cpu / float(r['cpu_seconds']):.2f}× | "
                  f"{wall / float(r['seconds']):.2f}× | {float(r['links']) / links:.2f} |")
            break
    else:
        print(f"| {r['error']} | {100 * e:.2f}% | {float(r['absorbed_over_emitted']):.3f} | {float(r['cpu_seconds']):.1f} | "
              f"{int(r['links']):,} | outside the view-independent runs' range | | | | |")
