#!/usr/bin/env python3
"""What the requested error delivers, measured by `walkrad sweep` against its path-traced reference
(never against another bake). Prints the tables for docs/accuracy.md.

- Cornell box (its camera): --errors 0.4,0.2,0.1,0.05, importance-driven and view-independent;
  reference 1,024 points × 131,072 paths.
- office-floor with 2, 4, 8 and 16 rooms (--detail 0.05), the walkthrough in the same two rooms:
  the default error (0.1), importance-driven, and view-independent up to 8 rooms; reference 1,024 points × 65,536 paths.

- The furnace (a closed unit cube, every face emitting, ρ = 0.5, 0.9, 0.99), default settings: wall
  time, peak memory (/usr/bin/time), elements and links. Its accuracy is a test (HierarchicalFurnace).

References are cached in OUT/<scene>-ref (sweep --reference) and reused by later runs.

Usage: bench/error_control.py [BUILD_DIR] [OUT] [PARTS]   (default build, build/bench-error,
       furnace,cornell,office; e.g. PARTS=office:2/4 for two sizes only, office-importance:2/4/8/16
       for the importance-driven bakes only)"""
import csv
import json
import os
import subprocess
import sys

build = sys.argv[1] if len(sys.argv) > 1 else "build"
out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(build, "bench-error")
parts = (sys.argv[3] if len(sys.argv) > 3 else "furnace,cornell,office").split(",")
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
walkrad = os.path.join(build, "pipeline/walkrad")
os.makedirs(out, exist_ok=True)


def sweep(name, scene, views, errors, methods, paths):
    ref = os.path.join(out, name + "-ref")
    if not os.path.exists(os.path.join(ref, "reference.bin")):
        subprocess.run([walkrad, "sweep", scene, *views, "-o", ref, "--methods", "importance", "--errors", "0.4",
                        "--points", "1024", "--samples", str(paths), "--image-width", "0", "--threads", "2",
                        "--no-plots"], check=True, stdout=subprocess.DEVNULL)
    target = os.path.join(out, name)
    subprocess.run([walkrad, "sweep", scene, *views, "-o", target, "--reference", ref, "--methods", methods,
                    "--errors", errors, "--points", "1024", "--samples", str(paths), "--image-width", "0",
                    "--threads", "2", "--no-plots"], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(target, "sweep.json")) as f:
        return json.load(f), target


def agreement(target, a, b):
    """Weighted relative RMS difference between two bakes at the sweep's points (bake-points.csv,
    weights from reference-points.csv): how far the importance-driven bake is from the view-independent one."""
    with open(os.path.join(target, "reference-points.csv")) as f:
        weights = [float(row["weight"]) for row in csv.DictReader(f)]
    num = den = 0.0
    with open(os.path.join(target, "bake-points.csv")) as f:
        for row in csv.DictReader(f):
            w = weights[int(row["point"])]
            x, y = float(row[a]), float(row[b])
            if x == x and y == y:  # both read (nan otherwise)
                num += w * (x - y) ** 2
                den += w * y * y
    return (num / den) ** 0.5 if den > 0 else float("nan")


def table(title, result):
    ref = result["reference"]
    print(f"\n{title} (reference error bar {100 * ref['ci']['rms_weighted']:.2f}% weighted)\n")
    print("| run | wall (s) | CPU (s) | peak MiB | elements | links | RMS (w) | bias | estimated | absorbed / emitted |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in result["runs"]:
        print(f"| {r['name']} | {r['seconds']:.2f} | {r['cpu_seconds']:.2f} | {r['peak_rss_mib']:.0f} | {r['elements']} | "
              f"{r['links']} | {100 * r['rms_weighted']:.2f}% | {100 * r['bias']:+.2f}% | "
              f"{100 * r['estimated_error']:.2f}% | {r['absorbed_over_emitted']:.3f} |")


# The unit cube's faces, counter-clockwise seen from inside (MGF: the front is counter-clockwise).
CUBE_FACES = ["000 100 110 010", "001 011 111 101", "000 001 101 100", "010 110 111 011", "000 010 011 001",
              "100 101 111 110"]


def furnace(rho):
    path = os.path.join(out, f"furnace-{rho}.mgf")
    with open(path, "w") as f:
        f.write(f"m glow =\n\tc\n\trd {rho}\n\tc\n\ted 100\nm glow\n")
        for name in sorted({v for face in CUBE_FACES for v in face.split()}):
            f.write(f"v v{name} =\n\tp {name[0]} {name[1]} {name[2]}\n")
        for face in CUBE_FACES:
            f.write("f " + " ".join("v" + v for v in face.split()) + "\n")
    bake_dir = path[:-4] + ".bake"
    r = subprocess.run(["/usr/bin/time", "-f", "%e %M", walkrad, "bake", path, "-o", bake_dir, "-q"], check=True,
                       capture_output=True, text=True)
    seconds, kib = r.stderr.strip().splitlines()[-1].split()
    with open(os.path.join(bake_dir, "report.json")) as f:
        c = json.load(f)["counts"]
    print(f"| {rho} | {float(seconds):.2f} | {int(kib) / 1024:.0f} | {c['elements']} | {c['links']} |")


for part in parts:
    if part == "furnace":
        print("Furnace, default settings\n\n| ρ | wall (s) | peak MiB | elements | links |\n| ---: | ---: | ---: | ---: | ---: |")
        for rho in (0.5, 0.9, 0.99):
            furnace(rho)
    if part == "cornell":
        r, target = sweep("cornell", os.path.join(root, "examples/cornell-box/cornell-box.gltf"), [], "0.4,0.2,0.1,0.05",
                  "importance,hierarchical", 131072)
        table("Cornell box", r)
        print(f"\nimportance-0.1 against hierarchical-0.1 at the same points: "
              f"{100 * agreement(target, 'importance-0.1', 'hierarchical-0.1'):.2f}% weighted RMS difference")
        for run in r["runs"]:
            if run["name"] == "importance-0.1":
                print("\nimportance-0.1 by surface: " + "; ".join(
                    f"{s['surface']} {100 * s['rms_weighted']:.2f}%" for s in run["surfaces"]))
    elif part.startswith("office"):
        sizes = [int(x) for x in (part.split(":")[1] if ":" in part else "2/4/8/16").split("/")]
        for rooms in sizes:
            scene_dir = os.path.join(out, f"office-{rooms}-scene")
            subprocess.run([sys.executable, os.path.join(root, "examples/office-floor/make_office_floor.py"), "--rooms",
                            str(rooms), "--detail", "0.05", "--out", scene_dir], check=True, stdout=subprocess.DEVNULL)
            suffix = "" if rooms == 8 else f"-{rooms}"
            scene = os.path.join(scene_dir, f"office-floor{suffix}.glb")
            views = ["--views", os.path.join(scene_dir, f"office-floor{suffix}-walkthrough.json")]
            # The view-independent bake of 16 rooms takes over a quarter of an hour here; office-importance:
            # the importance-driven bakes only.
            both = rooms <= 8 and not part.startswith("office-importance")
            r, target = sweep(f"office-{rooms}", scene, views, "0.1", "importance,hierarchical" if both else "importance", 65536)
            table(f"office-floor, {rooms} rooms", r)
            if both:
                print(f"\nimportance-0.1 against hierarchical-0.1 at the same points: "
                      f"{100 * agreement(target, 'importance-0.1', 'hierarchical-0.1'):.2f}% weighted RMS difference")
