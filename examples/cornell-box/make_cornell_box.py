#!/usr/bin/env python3
"""Writes the Cornell box (../shared/design/cornell-box.md: Cornell's published geometry) as glTF 2.0.

Units: the published millimetres divided by 1000 (glTF is in metres), y up. Each published quad is
two triangles (0,1,2)(0,2,3) in the published order, which faces into the box; the blocks' sides are
built from their tops down to y = 0 and oriented outwards. The light emits radiance (17, 12, 4):
emissiveFactor (1, 12/17, 4/17) with KHR_materials_emissive_strength 17. The camera is the published
one (35 mm lens on 25 mm film, from (278, 273, -800) looking along +z).

Usage: make_cornell_box.py [OUT.gltf | OUT.glb]   (default: cornell-box.gltf beside this script)
The output is deterministic: a test regenerates it and compares it with the committed file.
"""
import argparse
import base64
import json
import math
import os
import struct

MM = 0.001

WHITE, RED, GREEN, LIGHT = 0, 1, 2, 3
MATERIALS = [
    {"name": "white", "pbrMetallicRoughness": {"baseColorFactor": [0.73, 0.73, 0.73, 1.0], "metallicFactor": 0.0}},
    {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.63, 0.065, 0.05, 1.0], "metallicFactor": 0.0}},
    {"name": "green", "pbrMetallicRoughness": {"baseColorFactor": [0.14, 0.45, 0.091, 1.0], "metallicFactor": 0.0}},
    {"name": "light", "pbrMetallicRoughness": {"baseColorFactor": [0.78, 0.78, 0.78, 1.0], "metallicFactor": 0.0},
     "emissiveFactor": [1.0, 12.0 / 17.0, 4.0 / 17.0],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 17.0}}},
]

ROOM = [
    ("light", LIGHT, [(343, 548.7, 227), (343, 548.7, 332), (213, 548.7, 332), (213, 548.7, 227)]),
    ("floor", WHITE, [(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)]),
    ("ceiling", WHITE, [(556, 548.8, 0), (556, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)]),
    ("back wall", WHITE, [(549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2)]),
    ("right wall", GREEN, [(0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)]),
    ("left wall", RED, [(552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2), (556, 548.8, 0)]),
]
BLOCKS = [
    ("short block", [(130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)]),
    ("tall block", [(423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)]),
]


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def block_quads(top):
    """The top and four sides of a block, each facing outwards."""
    centre = tuple(sum(v[i] for v in top) / 4 for i in range(3))
    quads = [top]
    for k in range(4):
        a, b = top[k], top[(k + 1) % 4]
        side = [a, (a[0], 0, a[2]), (b[0], 0, b[2]), b]
        normal = cross(sub(side[1], side[0]), sub(side[2], side[0]))
        if dot(normal, sub(side[0], centre)) < 0:
            side.reverse()
        quads.append(side)
    return quads


def write_glb(path, doc, blob):
    """Binary glTF: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded with zeros."""
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, total))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(blob), b"BIN\0") + blob)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "cornell-box.gltf"),
                    help="OUT.gltf or OUT.glb (default: cornell-box.gltf beside this script)")
    out = ap.parse_args().out
    surfaces = list(ROOM)
    for name, top in BLOCKS:
        for i, quad in enumerate(block_quads(top)):
            surfaces.append((f"{name} {'top' if i == 0 else 'side ' + str(i)}", WHITE, quad))

    blob = bytearray()
    views, accessors, meshes, nodes = [], [], [], []
    for name, material, quad in surfaces:
        pos = [tuple(round(c * MM, 7) for c in v) for v in quad]
        offset = len(blob)
        for p in pos:
            blob += struct.pack("<3f", *p)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": 48, "target": 34962})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": 4, "type": "VEC3",
                          "min": [min(p[i] for p in pos) for i in range(3)],
                          "max": [max(p[i] for p in pos) for i in range(3)]})
        offset = len(blob)
        blob += struct.pack("<6H", 0, 1, 2, 0, 2, 3)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": 12, "target": 34963})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": 6, "type": "SCALAR"})
        meshes.append({"name": name, "primitives": [
            {"attributes": {"POSITION": len(accessors) - 2}, "indices": len(accessors) - 1, "material": material}]})
        nodes.append({"name": name, "mesh": len(meshes) - 1})

    yfov = 2 * math.atan(12.5 / 35.0)
    nodes.append({"name": "camera", "camera": 0, "translation": [0.278, 0.273, -0.8],
                  "rotation": [0.0, 1.0, 0.0, 0.0]})  # glTF cameras look along -z: turn to +z
    doc = {
        "asset": {"version": "2.0", "generator": "walkrad examples/cornell-box/make_cornell_box.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"name": "Cornell box", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": MATERIALS,
        "cameras": [{"type": "perspective", "perspective": {"yfov": yfov, "aspectRatio": 1.0, "znear": 0.01}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob)}],
    }
    if out.endswith(".glb"):
        write_glb(out, doc, bytes(blob))
    else:
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()
        with open(out, "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")
    print(f"wrote {out}: {len(surfaces)} quads")


if __name__ == "__main__":
    main()
