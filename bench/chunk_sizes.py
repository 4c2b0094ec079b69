#!/usr/bin/env python3
"""Output size: walkrad's Draco chunks against the same bake uncompressed, and against what gltfpack
(meshoptimizer's glTF packer, npm gltfpack 1.3.0 in bench/tools) makes of the uncompressed chunks, with its
default quantisation and with -cc (EXT_meshopt_compression). Also how far the Draco bake is from the plain one
(walkrad diff). Prints the table for docs/performance.md.

Usage: bench/chunk_sizes.py [BUILD_DIR]   (bakes Cornell and office-floor, 8 rooms, at the default error)"""
import glob
import json
import os
import subprocess
import sys

build = sys.argv[1] if len(sys.argv) > 1 else "build"
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
walkrad = os.path.join(build, "pipeline/walkrad")
out = os.path.join(build, "bench-sizes")
tools = os.path.join(root, "bench/tools")
gltfpack = os.path.join(tools, "node_modules/.bin/gltfpack")
if not os.path.exists(gltfpack):
    subprocess.run(["npm", "ci", "--no-audit", "--no-fund", "--prefix", tools], check=True, stdout=subprocess.DEVNULL)
os.makedirs(out, exist_ok=True)

office = os.path.join(out, "office")
if not os.path.exists(os.path.join(office, "office-floor.glb")):
    subprocess.run([sys.executable, os.path.join(root, "examples/office-floor/make_office_floor.py"), "--out", office],
                   check=True, stdout=subprocess.DEVNULL)
scenes = {
    "Cornell box": (os.path.join(root, "examples/cornell-box/cornell-box.gltf"), []),
    "office-floor, 8 rooms": (os.path.join(office, "office-floor.glb"),
                                       ["--views", os.path.join(office, "office-floor-walkthrough.json")]),
}


def folder_bytes(folder, pattern="chunk-*.glb"):
    return sum(os.path.getsize(p) for p in glob.glob(os.path.join(folder, pattern)))


print("| scene | triangles | uncompressed | walkrad Draco | ratio | gltfpack | gltfpack -cc | Draco vs plain (walkrad diff) |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
for name, (scene, args) in scenes.items():
    tag = name.split(",")[0].split(" ")[0].lower()
    plain, draco = os.path.join(out, tag + "-plain"), os.path.join(out, tag + "-draco")
    subprocess.run([walkrad, "bake", scene, "-o", plain, "-q", "--no-compression", *args], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([walkrad, "bake", scene, "-o", draco, "-q", *args], check=True, stdout=subprocess.DEVNULL)
    packed = {}
    for flag in ["", "-cc"]:
        target = os.path.join(out, tag + "-gltfpack" + flag)
        os.makedirs(target, exist_ok=True)
        for chunk in glob.glob(os.path.join(plain, "chunk-*.glb")):
            cmd = [gltfpack, "-i", chunk, "-o", os.path.join(target, os.path.basename(chunk))] + ([flag] if flag else [])
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        packed[flag] = folder_bytes(target)
    triangles = sum(c["triangles"] for c in json.load(open(os.path.join(draco, "manifest.json")))["chunks"])
    diff = subprocess.run([walkrad, "diff", plain, draco], capture_output=True, text=True).stdout.strip().splitlines()[-1]
    diff = diff.split(": ", 2)[-1]
    p, d = folder_bytes(plain), folder_bytes(draco)
    print(f"| {name} | {triangles:,} | {p:,} | {d:,} | {p / d:.1f}× | {packed['']:,} | {packed['-cc']:,} | {diff} |")
