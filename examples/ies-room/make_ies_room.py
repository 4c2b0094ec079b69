#!/usr/bin/env python3
"""Writes "IES room", walkrad's example of luminaires described by IES LM-63 photometric files.

A closed 6 x 4 x 2.8 m room (z up, metres) lit only by three luminaires (glTF EXT_lights_ies):
- two recessed downlights in the ceiling, aimed straight down: downlight.ies, type C, rotationally
  symmetric, I(g) = 1200 cos^4 g cd inside a 60 degree cut-off and a little spill beside it;
- a wall-washer near the wall x = 6, tilted 20 degrees towards it: wall-washer.ies, type C,
  bilateral (horizontal 0-180), throwing towards C = 0 (its +X, turned to face the wall) and
  little behind: I(g, C) = 900 sin(2g)^2 (0.35 + 0.65 max(0, cos C)) + 40 cd.
The profiles are written here from these formulas (LM-63-2002, CR LF line ends); no third-party data.
A camera in a corner looks at the lit wall. Deterministic.

Usage: make_ies_room.py [OUT_DIR]   (default: beside this script: ies-room.gltf, downlight.ies,
wall-washer.ies)
"""
import argparse
import base64
import json
import math
import os
import struct


def profile(lines, vertical, horizontal, candela):
    """LM-63-2002 text: keywords, TILT=NONE, the photometric block, the angles and the candela."""
    out = ["IESNA:LM-63-2002"] + lines + ["TILT=NONE",
           # lamps, lumens per lamp (-1: absolute), multiplier, #vertical, #horizontal, type C, metres, w l h
           "1 -1 1 %d %d 1 2 0.2 0.2 0" % (len(vertical), len(horizontal)),
           "1 1 20"]  # ballast factor, ballast-lamp factor, input watts
    def rows(values):  # LM-63-2002 keeps lines under 256 characters: ten values a line
        return [" ".join(values[k:k + 10]) for k in range(0, len(values), 10)]
    out += rows(["%g" % a for a in vertical])
    out += rows(["%g" % a for a in horizontal])
    for h in horizontal:
        out += rows(["%.2f" % candela(v, h) for v in vertical])
    return "\r\n".join(out) + "\r\n"


def downlight(g, c):
    r = math.radians(g)
    if g <= 60:
        return 1200 * math.cos(r) ** 4 + 15
    return 15 if g <= 90 else 0.0


def wall_washer(g, c):
    if g > 90:
        return 0.0
    r, h = math.radians(g), math.radians(c)
    return 900 * math.sin(2 * r) ** 2 * (0.35 + 0.65 * max(0.0, math.cos(h))) + 40


PROFILES = {
    "downlight.ies": profile(["[TEST] walkrad examples/ies-room", "[MANUFAC] formula: 1200 cos^4 g, 60 degree cut-off",
                              "[LUMCAT] DL-1", "[LUMINAIRE] recessed downlight"],
                             [2.5 * k for k in range(73)], [0], downlight),
    "wall-washer.ies": profile(["[TEST] walkrad examples/ies-room", "[MANUFAC] formula: 900 sin^2 2g (0.35 + 0.65 cos+ C)",
                                "[LUMCAT] WW-1", "[LUMINAIRE] wall-washer"],
                               [2.5 * k for k in range(73)], [15 * k for k in range(13)], wall_washer),
}


def box(lo, hi, inward):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    outward = [(4, 5, 6, 7), (0, 3, 2, 1), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    quads = [[c[i] for i in q] for q in outward]
    return [list(reversed(q)) for q in quads] if inward else quads


def quaternion(m):
    """Unit quaternion (x, y, z, w) of a rotation matrix given by rows."""
    t = m[0][0] + m[1][1] + m[2][2]
    if t > 0:
        s = 2 * math.sqrt(1 + t)
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4]
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
    q = [0.0] * 4
    q[i] = s / 4
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    q[3] = (m[k][j] - m[j][k]) / s
    return q


def frame(forward, up):
    """The rotation taking glTF's -Z to `forward` and +Y towards `up` (columns: X, Y, Z = -forward)."""
    n = lambda v: [x / math.sqrt(sum(y * y for y in v)) for x in v]
    z = n([-x for x in forward])
    x = n([up[1] * z[2] - up[2] * z[1], up[2] * z[0] - up[0] * z[2], up[0] * z[1] - up[1] * z[0]])
    y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]]
    return quaternion([[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]])


def write(out_dir):
    for name, text in PROFILES.items():
        with open(os.path.join(out_dir, name), "w", newline="") as f:
            f.write(text)
    materials = [
        {"name": "wall", "pbrMetallicRoughness": {"baseColorFactor": [0.75, 0.74, 0.70, 1.0], "metallicFactor": 0.0}},
        {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.40, 0.32, 0.25, 1.0], "metallicFactor": 0.0}},
        {"name": "ceiling", "pbrMetallicRoughness": {"baseColorFactor": [0.85, 0.85, 0.85, 1.0], "metallicFactor": 0.0}},
        {"name": "bench", "pbrMetallicRoughness": {"baseColorFactor": [0.30, 0.22, 0.15, 1.0], "metallicFactor": 0.0}},
    ]
    room = box((0, 0, 0), (6, 4, 2.8), inward=True)
    parts = [("floor", 1, [room[1]]), ("ceiling", 2, [room[0]]), ("walls", 0, room[2:]),
             ("bench", 3, box((2.2, 1.4, 0), (3.8, 2.0, 0.45), inward=False))]
    blob = bytearray()
    gltf = {"asset": {"version": "2.0", "generator": "walkrad examples/ies-room/make_ies_room.py"},
            "extensionsUsed": ["EXT_lights_ies"], "materials": materials, "meshes": [], "accessors": [],
            "bufferViews": [], "nodes": []}
    for name, material, quads in parts:
        positions = [p for q in quads for p in q]
        indices = [i for k in range(len(quads)) for i in (4 * k, 4 * k + 1, 4 * k + 2, 4 * k, 4 * k + 2, 4 * k + 3)]
        for data, target in ((b"".join(struct.pack("<3f", *p) for p in positions), 34962),
                             (b"".join(struct.pack("<I", i) for i in indices), 34963)):
            gltf["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
            blob.extend(data)
        n = len(gltf["accessors"])
        gltf["accessors"].append({"bufferView": n, "componentType": 5126, "count": len(positions), "type": "VEC3",
                                  "min": [min(p[k] for p in positions) for k in range(3)],
                                  "max": [max(p[k] for p in positions) for k in range(3)]})
        gltf["accessors"].append({"bufferView": n + 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"})
        gltf["meshes"].append({"name": name, "primitives": [{"attributes": {"POSITION": n}, "indices": n + 1, "material": material}]})
        gltf["nodes"].append({"name": name, "mesh": len(gltf["meshes"]) - 1})
    gltf["extensions"] = {"EXT_lights_ies": {"lights": [{"uri": "downlight.ies", "name": "downlight"},
                                                        {"uri": "wall-washer.ies", "name": "wall-washer"}]}}
    # Downlights 2 cm under the ceiling, aimed down (-Z of the node = -z of the room: no rotation).
    for k, (x, y) in enumerate(((1.8, 2.0), (3.6, 2.0))):
        gltf["nodes"].append({"name": "downlight-%d" % (k + 1), "translation": [x, y, 2.78],
                              "extensions": {"EXT_lights_ies": {"light": 0, "color": [1.0, 0.9, 0.75]}}})
    # The wall-washer 0.8 m from the wall x = 6, aimed 20 degrees off down towards it; its +X (C = 0)
    # towards the wall.
    a = math.radians(20)
    gltf["nodes"].append({"name": "wall-washer", "translation": [5.2, 2.0, 2.7],
                          "rotation": frame([math.sin(a), 0, -math.cos(a)], [0, 1, 0]),
                          "extensions": {"EXT_lights_ies": {"light": 1, "multiplier": 1.5, "color": [0.85, 0.9, 1.0]}}})
    gltf["cameras"] = [{"type": "perspective", "perspective": {"yfov": 1.1, "aspectRatio": 1.5, "znear": 0.05, "zfar": 30.0}}]
    eye, target = [0.4, 0.4, 1.6], [6.0, 2.4, 1.1]
    gltf["nodes"].append({"name": "camera", "camera": 0, "translation": eye,
                          "rotation": frame([t - e for t, e in zip(target, eye)], [0, 0, 1])})
    gltf["scenes"] = [{"nodes": list(range(len(gltf["nodes"])))}]
    gltf["scene"] = 0
    gltf["buffers"] = [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode("ascii")}]
    with open(os.path.join(out_dir, "ies-room.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out_dir", nargs="?", default=os.path.dirname(os.path.abspath(__file__)),
                    help="folder for ies-room.gltf and its IES files (default: beside this script)")
    out = ap.parse_args().out_dir
    os.makedirs(out, exist_ok=True)
    write(out)


if __name__ == "__main__":
    main()
