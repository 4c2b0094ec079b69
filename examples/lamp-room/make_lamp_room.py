#!/usr/bin/env python3
"""Writes "lamp room", walkrad's example of the effects a scene can call for, as glTF 2.0.

A closed 5 x 4 x 3 m room (z up, metres) lit only by punctual lights (KHR_lights_punctual): a 20 W/sr
bulb inside a translucent lampshade (KHR_materials_diffuse_transmission: factor 0.5, reflectance
0.3) on a table, and a spot light on the wall shining down at the floor (20 and 30 degree cones).
A camera looks in from a corner. With --empty: the bare room and the bulb only, a convex enclosure
(no visibility rays needed), which shows what the effect plan saves.

Usage: make_lamp_room.py [--empty] [OUT.gltf]   (default: lamp-room.gltf or lamp-room-empty.gltf beside this
script). Deterministic.
"""
import argparse
import base64
import json
import math
import os
import struct

WALL, FLOOR, TABLE, SHADE = 0, 1, 2, 3
MATERIALS = [
    {"name": "wall", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.68, 1.0], "metallicFactor": 0.0}},
    {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.35, 0.25, 1.0], "metallicFactor": 0.0}},
    {"name": "table", "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.2, 0.12, 1.0], "metallicFactor": 0.0}},
    # rho = (1 - 0.5) x 0.6 = 0.3, tau = 0.5 x (1, 0.9, 0.7): a warm translucent shade.
    {"name": "shade", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1.0], "metallicFactor": 0.0},
     "extensions": {"KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.5,
                                                           "diffuseTransmissionColorFactor": [1.0, 0.9, 0.7]}}},
]


def box(lo, hi, inward):
    """The six faces of an axis-aligned box as quads (counter-clockwise seen from the side they face)."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    outward = [(4, 5, 6, 7), (0, 3, 2, 1), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    quads = [[c[i] for i in q] for q in outward]
    return [list(reversed(q)) for q in quads] if inward else quads


def mesh_of(quads):
    positions, indices = [], []
    for q in quads:
        base = len(positions)
        positions.extend(q)
        indices.extend([base, base + 1, base + 2, base, base + 2, base + 3])
    return positions, indices


def write(path, empty):
    room = box((0, 0, 0), (5, 4, 3), inward=True)
    parts = [("floor", FLOOR, [room[1]]), ("walls", WALL, [q for i, q in enumerate(room) if i != 1])]
    if not empty:
        parts.append(("table", TABLE, box((1.6, 1.6, 0), (2.6, 2.4, 0.75), inward=False)))
        parts.append(("shade", SHADE, box((1.9, 1.8, 0.85), (2.3, 2.2, 1.25), inward=False)))
    blob = bytearray()
    gltf = {"asset": {"version": "2.0", "generator": "walkrad examples/lamp-room/make_lamp_room.py"},
            "materials": MATERIALS, "meshes": [], "accessors": [], "bufferViews": [], "nodes": [],
            "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_diffuse_transmission"]}
    for name, material, quads in parts:
        positions, indices = mesh_of(quads)
        pos_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
        idx_bytes = b"".join(struct.pack("<I", i) for i in indices)
        for data, target in ((pos_bytes, 34962), (idx_bytes, 34963)):
            gltf["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
            blob.extend(data)
        lo = [min(p[k] for p in positions) for k in range(3)]
        hi = [max(p[k] for p in positions) for k in range(3)]
        n = len(gltf["accessors"])
        gltf["accessors"].append({"bufferView": len(gltf["bufferViews"]) - 2, "componentType": 5126, "count": len(positions),
                                  "type": "VEC3", "min": lo, "max": hi})
        gltf["accessors"].append({"bufferView": len(gltf["bufferViews"]) - 1, "componentType": 5125, "count": len(indices),
                                  "type": "SCALAR"})
        gltf["meshes"].append({"name": name, "primitives": [{"attributes": {"POSITION": n}, "indices": n + 1, "material": material}]})
        gltf["nodes"].append({"name": name, "mesh": len(gltf["meshes"]) - 1})
    lights = [{"name": "bulb", "type": "point", "color": [1.0, 0.95, 0.85], "intensity": 20.0}]
    gltf["nodes"].append({"name": "bulb", "translation": [2.1, 2.0, 1.05], "extensions": {"KHR_lights_punctual": {"light": 0}}})
    if not empty:
        lights.append({"name": "spot", "type": "spot", "color": [0.9, 0.95, 1.0], "intensity": 40.0,
                       "spot": {"innerConeAngle": math.radians(20), "outerConeAngle": math.radians(30)}})
        # On the wall x = 5 at 2.5 m, pointing down and into the room: -Z of the node towards (-1, 0, -1.5).
        d = (-1.0, 0.0, -1.5)
        length = math.sqrt(sum(x * x for x in d))
        d = tuple(x / length for x in d)
        # Rotation taking -Z to d: about the axis (-Z) x d by the angle between them.
        axis = (0.0 * d[2] - (-1.0) * d[1], (-1.0) * d[0] - 0.0 * d[2], 0.0)
        s = math.sqrt(sum(x * x for x in axis))
        angle = math.acos(max(-1.0, min(1.0, -d[2])))
        q = [axis[0] / s * math.sin(angle / 2), axis[1] / s * math.sin(angle / 2), axis[2] / s * math.sin(angle / 2), math.cos(angle / 2)]
        gltf["nodes"].append({"name": "spot", "translation": [4.9, 1.0, 2.5], "rotation": q,
                              "extensions": {"KHR_lights_punctual": {"light": 1}}})
    gltf["extensions"] = {"KHR_lights_punctual": {"lights": lights}}
    # The camera in a corner at eye height, looking at the lamp (glTF cameras look along -Z, +Y up).
    gltf["cameras"] = [{"type": "perspective", "perspective": {"yfov": 1.0, "aspectRatio": 1.5, "znear": 0.05, "zfar": 20.0}}]
    eye, target = (4.6, 3.6, 1.6), (2.1, 2.0, 0.9)
    f = [t - e for t, e in zip(target, eye)]
    fl = math.sqrt(sum(x * x for x in f))
    f = [x / fl for x in f]
    r = [f[1] * 1 - f[2] * 0, f[2] * 0 - f[0] * 1, 0.0]  # forward x up(0,0,1)
    rl = math.sqrt(sum(x * x for x in r))
    r = [x / rl for x in r]
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    back = [-x for x in f]
    m = [[r[0], u[0], back[0]], [r[1], u[1], back[1]], [r[2], u[2], back[2]]]
    w = math.sqrt(max(0.0, 1 + m[0][0] + m[1][1] + m[2][2])) / 2
    quat = [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w), (m[1][0] - m[0][1]) / (4 * w), w]
    gltf["nodes"].append({"name": "camera", "camera": 0, "translation": list(eye), "rotation": quat})
    gltf["scenes"] = [{"nodes": list(range(len(gltf["nodes"])))}]
    gltf["scene"] = 0
    gltf["buffers"] = [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode("ascii")}]
    with open(path, "w") as f_out:
        json.dump(gltf, f_out, indent=1)
        f_out.write("\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", help="OUT.gltf (default: lamp-room.gltf, or lamp-room-empty.gltf, beside this script)")
    ap.add_argument("--empty", action="store_true", help="the room without its lamp")
    a = ap.parse_args()
    empty = a.empty
    here = os.path.dirname(os.path.abspath(__file__))
    out = a.out or os.path.join(here, "lamp-room-empty.gltf" if empty else "lamp-room.gltf")
    write(out, empty)


if __name__ == "__main__":
    main()
