#!/usr/bin/env python3
"""Plots and report.md for a `walkrad sweep` folder (written there by the sweep, which runs it; run it
again by hand with: python3 plot_sweep.py SWEEP_DIR). Needs python3-matplotlib (Debian)."""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker  # noqa: E402

folder = sys.argv[1] if len(sys.argv) > 1 else "."
doc = json.load(open(os.path.join(folder, "sweep.json")))
runs = doc["runs"]
ref = doc["reference"]
LABELS = {"classic": "classic (element size)", "southwell": "classic, progressive refinement (element size)",
          "hemicube": "classic, hemicube form factors (element size)",
          "hierarchical": "hierarchical, view-independent (requested error)",
          "importance": "hierarchical, importance-driven (requested error)"}
STYLE = {"classic": ("tab:gray", "s"), "southwell": ("tab:brown", "D"), "hemicube": ("tab:olive", "P"),
         "hierarchical": ("tab:blue", "o"),
         "importance": ("tab:red", "^")}
# Variants without an effect (sweep --without): "importance-no-gather" and the like, dashed.
methods = []
for r in runs:
    if r["method"] != "measured" and r["method"] not in methods:
        methods.append(r["method"])
for m in methods:
    base = m.split("-no-")[0]
    LABELS.setdefault(m, LABELS.get(base, base) + ", without " + m.split("-no-")[-1] if "-no-" in m else m)
    STYLE.setdefault(m, (STYLE.get(base, ("tab:purple", "v"))[0], "x"))
CLASSIC = ("classic", "southwell", "hemicube")  # by element size, not requested error


def of(method):
    return [r for r in runs if r["method"] == method]


def pct(x):
    return 100.0 * x


def bias(r):
    return "" if r.get("bias") is None else f"{100.0 * r['bias']:+.1f}%"


def percent(x):
    return "" if x is None else f"{100.0 * x:.2f}%"


def plain_numbers(axis):
    axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}" if f"{v:.1g}"[0] in "235" else ""))


# Error against time, log-log, one curve per method; the reference's own 95% error bar as a band.
panels = [("rms_weighted", ref["ci"]["rms_weighted"], "at the sample points (importance-weighted)")]
if ref["images"]:
    panels.append(("image_rms_weighted", ref["image_ci"]["rms_weighted"], "in the images from the viewpoints"))
fig, axes = plt.subplots(1, len(panels), figsize=(5.5 * len(panels), 4.2), squeeze=False)
axes = axes[0]
for ax, (key, ci, title) in zip(axes, panels):
    for m in methods:
        rs = sorted(of(m), key=lambda r: r["cpu_seconds"])
        colour, marker = STYLE[m]
        ax.plot([r["cpu_seconds"] for r in rs], [pct(r[key]) for r in rs], marker=marker, color=colour, label=LABELS[m])
        for r in rs:
            tag = f"{r['error']:g}" if r["error"] is not None else f"{r['element_size']:.3g} m"
            ax.annotate(tag, (r["cpu_seconds"], pct(r[key])), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.axhspan(1e-3, pct(ci), color="tab:green", alpha=0.15, label="reference's 95% error bar")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("bake time (CPU s: user + system; steadier than wall time on a shared machine)", fontsize=8)
    ax.set_ylabel("relative RMS error of B (%)")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    values = [pct(r[key]) for r in runs if r[key] > 0] + [pct(ci)]
    ax.set_ylim(min(values) / 1.5, max(values) * 1.5)
    plain_numbers(ax.yaxis)
    plain_numbers(ax.xaxis)
axes[0].legend(fontsize=8)
fig.suptitle(os.path.basename(doc["scene"]) + ": error against time", fontsize=11)
fig.tight_layout()
fig.savefig(os.path.join(folder, "error_vs_time.png"), dpi=90)

# Links and memory against the requested error (hierarchical methods) and against element size (classic).
fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
for ax, key, label in [(axes[0], "links", "links (classic: facing pairs)"), (axes[1], "peak_rss_mib", "peak memory (MiB)")]:
    for m in methods:
        if m in CLASSIC:
            continue
        rs = sorted(of(m), key=lambda r: r["error"])
        colour, marker = STYLE[m]
        ax.plot([r["error"] for r in rs], [r[key] for r in rs], marker=marker, color=colour, label=LABELS[m])
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.invert_xaxis()
    ax.set_xlabel("requested error (smaller: finer)")
    ax.set_ylabel(label)
    ax.grid(True, which="both", alpha=0.3)
    if key == "peak_rss_mib":
        plain_numbers(ax.yaxis)
    if any(m in methods for m in CLASSIC):
        top = ax.twiny()
        for m in [m for m in CLASSIC if m in methods]:
            rs = sorted(of(m), key=lambda r: -r["element_size"])
            colour, marker = STYLE[m]
            top.plot([r["element_size"] for r in rs], [r[key] for r in rs], marker=marker, color=colour, label=LABELS[m])
        top.set_xscale("log")
        top.invert_xaxis()
        plain_numbers(top.xaxis)
        top.set_xlabel("classic: element size (m)", color=STYLE["classic"][0])
        top.legend(fontsize=8, loc="lower right")
axes[0].legend(fontsize=8, loc="upper left")
fig.suptitle(os.path.basename(doc["scene"]) + ": links and memory", fontsize=11)
fig.tight_layout()
fig.savefig(os.path.join(folder, "cost_vs_error.png"), dpi=90)


def time_at(method, key, error, clock):
    """The time `method` needs for `error`: log-log interpolation between its two runs (by requested error) whose errors
    bracket it; None when no two runs do."""
    rs = sorted(of(method), key=lambda r: -r["error"])
    for a, b in zip(rs, rs[1:]):
        if min(a[key], b[key]) <= error <= max(a[key], b[key]) and a[key] != b[key]:
            f = math.log(error / a[key]) / math.log(b[key] / a[key])
            return math.exp(math.log(a[clock]) + f * math.log(b[clock] / a[clock]))
    return None


lines = [f"# Accuracy sweep: {os.path.basename(doc['scene'])}", "",
         f"Command: `{doc['command']}`", "",
         f"Scene: {doc['input_polygons']} input polygons; walkthrough: {doc['viewpoints']} viewpoints.", "",
         f"Reference (Monte Carlo path tracer, diffuse, next-event estimation): {ref['points']} rays over "
         f"{ref['views']} viewpoints, {ref['measured_points']} on non-emitting surfaces, {ref['samples']} paths each, "
         f"{ref['seconds']:.1f} s; 95% error bar (relative RMS of 1.96σ): {pct(ref['ci']['rms']):.2f}% plain, "
         f"{pct(ref['ci']['rms_weighted']):.2f}% weighted. Images: {ref['image_samples']} paths per pixel, error bar "
         f"{percent(ref['image_ci']['rms'])}.", ""]
if doc.get("unavailable"):
    lines += ["Not measured: " + "; ".join(doc["unavailable"]) + ".", ""]
lines += ["| run | time (s) | CPU (s) | elements | links | rays | peak MiB | output KiB | RMS | RMS (w) | estimated | max | max (w) | bias (w) | image RMS (w) | absorbed/emitted |",
          "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
for r in runs:
    lines.append(f"| {r['name']} | {r['seconds']:.2f} | {r['cpu_seconds']:.2f} | {r['elements']} | {r['links']} | {r['rays']} | "
                 f"{r['peak_rss_mib']:.0f} | {r['output_bytes'] / 1024:.0f} | {pct(r['rms']):.2f}% | {pct(r['rms_weighted']):.2f}% | {percent(r['estimated_error'])} | "
                 f"{pct(r['max']):.1f}% | {pct(r['max_weighted']):.1f}% | {bias(r)} | {percent(r['image_rms_weighted'])} | "
                 f"{r['absorbed_over_emitted']:.3f} |")
lines += ["", "![error against time](error_vs_time.png)", "", "![links and memory](cost_vs_error.png)", ""]
if "importance" in methods and "hierarchical" in methods:
    lines += ["Equal error in what the walkthrough sees (importance-weighted RMS at the sample points): for each "
              "importance-driven run, the time the view-independent method needs for the same error, interpolated "
              "(log-log) between the two view-independent runs whose errors bracket it; wall time and CPU time "
              "(user + system, steadier on a shared machine).", "",
              "| importance run | error | wall (s) | CPU (s) | view-independent wall (s) | CPU (s) | wall ratio | CPU ratio |",
              "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for r in sorted(of("importance"), key=lambda r: -r["error"]):
        wall = time_at("hierarchical", "rms_weighted", r["rms_weighted"], "seconds")
        cpu = time_at("hierarchical", "rms_weighted", r["rms_weighted"], "cpu_seconds")
        if wall is None:
            lines.append(f"| {r['name']} | {pct(r['rms_weighted']):.2f}% | {r['seconds']:.2f} | {r['cpu_seconds']:.2f} | "
                         "not bracketed by the view-independent runs | | | |")
        else:
            lines.append(f"| {r['name']} | {pct(r['rms_weighted']):.2f}% | {r['seconds']:.2f} | {r['cpu_seconds']:.2f} | "
                         f"{wall:.2f} | {cpu:.2f} | {wall / r['seconds']:.2f} | {cpu / r['cpu_seconds']:.2f} |")
    lines.append("")
for im in ref["images"]:
    lines += [f"![reference, viewpoint {im['view']}]({im['file']})"]
open(os.path.join(folder, "report.md"), "w").write("\n".join(lines) + "\n")
