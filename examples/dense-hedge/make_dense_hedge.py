#!/usr/bin/env python3
"""Writes "dense hedge", walkrad's example of volumetric visibility, as a binary glTF (.glb)
and the walkthrough that looks at its wall.

An open stage (z up, metres): a 6 x 4 m floor, a 4 x 3 m wall at x = 6 facing the light, and between
them a 1.2 x 1.2 m light panel at x = 0.2 (20 W/m²) and a "hedge": a 1 x 1.6 x 1.6 m box (x 2-3) of
small closed cubes at random places and orientations, 12 triangles each (8,400 cubes: 100,800
triangles by default). The cubes' side is chosen so that the hedge's extinction kappa = A / 4V is
KAPPA (1/m): light crossing its 1 m depth keeps about exp(-KAPPA) of itself, and the wall behind it
gets a soft shadow. The walkthrough is a camera between the hedge and the wall looking at the wall.

With --leaves the objects are flat square leaves (2 triangles each, open sheets: both faces block, so
A counts twice in kappa) instead of cubes.

Usage: make_dense_hedge.py [--cubes N] [--kappa K] [--leaves] [OUT_DIR]   (default 8400 cubes, kappa 1,
this script's folder). Writes dense-hedge.glb and dense-hedge-walkthrough.json. Deterministic.
"""
import argparse
import json
import math
import os
import random
import struct

HEDGE_LO, HEDGE_HI = (2.0, 1.2, 0.7), (3.0, 2.8, 2.3)
MATERIALS = [
    {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.4, 0.4, 0.4, 1.0], "metallicFactor": 0.0}},
    {"name": "wall", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0}},
    {"name": "leaves", "pbrMetallicRoughness": {"baseColorFactor": [0.25, 0.45, 0.2, 1.0], "metallicFactor": 0.0}},
    {"name": "panel", "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0},
     "emissiveFactor": [1.0, 1.0, 1.0], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 20.0}}},
]
FLOOR, WALL, LEAVES, PANEL = range(4)


def rotation(rng):
    """A uniformly random rotation matrix (Shoemake's quaternion from three uniforms)."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    x, y, z, w = a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2), b * math.sin(2 * math.pi * u3), b * math.cos(2 * math.pi * u3)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def cube(centre, side, r):
    """8 shared corners and 12 outward triangles of a rotated cube (one connected closed object)."""
    h = side / 2
    corners = []
    for i in range(8):
        local = (h if i & 1 else -h, h if i & 2 else -h, h if i & 4 else -h)
        corners.append(tuple(centre[k] + sum(r[k][m] * local[m] for m in range(3)) for k in range(3)))
    # Faces counter-clockwise seen from outside (right-handed local frame; rotations keep handedness).
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    triangles = []
    for a, b, c, d in faces:
        triangles += [(a, b, c), (a, c, d)]
    return corners, triangles


def leaf(centre, side, r):
    """A flat square of side `side` in the rotated frame's xy plane: 4 corners, 2 triangles."""
    h = side / 2
    corners = [tuple(centre[k] + r[k][0] * x + r[k][1] * y for k in range(3)) for x, y in ((-h, -h), (h, -h), (h, h), (-h, h))]
    return corners, [(0, 1, 2), (0, 2, 3)]


def quad(a, b, c, d):
    return [a, b, c, d], [(0, 1, 2), (0, 2, 3)]


def write(out_dir, cubes, kappa, leaves=False):
    volume = math.prod(HEDGE_HI[k] - HEDGE_LO[k] for k in range(3))
    # kappa = A / 4V with A = 6 side² per cube, or 2 side² per leaf (both faces of an open sheet block).
    side = math.sqrt(4 * kappa * volume / ((2 if leaves else 6) * cubes))
    rng = random.Random(20261122)
    leaves_pos, leaves_idx = [], []
    for _ in range(cubes):
        centre = [HEDGE_LO[k] + side + (HEDGE_HI[k] - HEDGE_LO[k] - 2 * side) * rng.random() for k in range(3)]
        corners, triangles = (leaf if leaves else cube)(centre, side, rotation(rng))
        base = len(leaves_pos)
        leaves_pos += corners
        leaves_idx += [base + i for t in triangles for i in t]
    parts = [("floor", FLOOR, *quad((0, 0, 0), (6, 0, 0), (6, 4, 0), (0, 4, 0))),
             ("wall", WALL, *quad((6, 0, 0), (6, 0, 3), (6, 4, 3), (6, 4, 0))),
             ("panel", PANEL, *quad((0.2, 1.4, 0.9), (0.2, 2.6, 0.9), (0.2, 2.6, 2.1), (0.2, 1.4, 2.1))),
             ("hedge", LEAVES, leaves_pos, [tuple(leaves_idx[i:i + 3]) for i in range(0, len(leaves_idx), 3)])]
    # Counter-clockwise seen from the side they face: the floor +z, the wall -x (the light), the panel +x.
    blob = bytearray()
    gltf = {"asset": {"version": "2.0", "generator": "walkrad examples/dense-hedge/make_dense_hedge.py"},
            "scene": 0, "scenes": [{"nodes": []}], "materials": MATERIALS, "meshes": [], "accessors": [],
            "bufferViews": [], "nodes": [], "buffers": [], "extensionsUsed": ["KHR_materials_emissive_strength"]}
    for name, material, positions, triangles in parts:
        pos_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
        idx_bytes = b"".join(struct.pack("<3I", *t) for t in triangles)
        for data, target in ((pos_bytes, 34962), (idx_bytes, 34963)):
            gltf["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
            blob.extend(data)
            blob.extend(b"\0" * (-len(blob) % 4))
        floats = [struct.unpack("<3f", struct.pack("<3f", *p)) for p in positions]
        n = len(gltf["accessors"])
        gltf["accessors"].append({"bufferView": len(gltf["bufferViews"]) - 2, "componentType": 5126, "count": len(positions),
                                  "type": "VEC3", "min": [min(p[k] for p in floats) for k in range(3)],
                                  "max": [max(p[k] for p in floats) for k in range(3)]})
        gltf["accessors"].append({"bufferView": len(gltf["bufferViews"]) - 1, "componentType": 5125,
                                  "count": 3 * len(triangles), "type": "SCALAR"})
        gltf["meshes"].append({"name": name, "primitives": [{"attributes": {"POSITION": n}, "indices": n + 1, "material": material}]})
        gltf["scenes"][0]["nodes"].append(len(gltf["nodes"]))
        gltf["nodes"].append({"name": name, "mesh": len(gltf["meshes"]) - 1})
    gltf["buffers"].append({"byteLength": len(blob)})
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(blob))
    glb += struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(blob), 0x004E4942) + bytes(blob)
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "dense-hedge.glb"), "wb") as f:
        f.write(glb)
    # A camera between the hedge and the wall, 1.5 m from the wall, seeing all of it (90° vertical).
    walkthrough = {"format": "walkrad-walkthrough", "version": 1,
                   "path": {"frames": 2, "yfov_deg": 90, "aspect": 1.3333,
                            "keyframes": [{"time": 0.0, "position": [4.5, 2.0, 1.5], "target": [6.0, 2.0, 1.5]},
                                          {"time": 1.0, "position": [4.5, 2.0, 1.5], "target": [6.0, 2.0, 1.5]}]}}
    with open(os.path.join(out_dir, "dense-hedge-walkthrough.json"), "w") as f:
        json.dump(walkthrough, f, indent=1)
        f.write("\n")
    return side, (2 if leaves else 12) * cubes


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cubes", "--objects", dest="cubes", type=int, default=8400, help="number of cubes (or leaves)")
    parser.add_argument("--kappa", type=float, default=1.0)
    parser.add_argument("--leaves", action="store_true", help="flat square leaves instead of cubes")
    parser.add_argument("out_dir", nargs="?", default=os.path.dirname(os.path.abspath(__file__)))
    args = parser.parse_args()
    side, triangles = write(args.out_dir, args.cubes, args.kappa, args.leaves)
    kind = "leaves" if args.leaves else "cubes"
    print(f"dense-hedge.glb: {args.cubes} {kind} of {side * 100:.2f} cm ({triangles} triangles), kappa {args.kappa} 1/m")


if __name__ == "__main__":
    main()
