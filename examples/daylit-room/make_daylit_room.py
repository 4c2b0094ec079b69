#!/usr/bin/env python3
"""Writes "daylit room", walkrad's example of a room lit by day: the sun and a clear sky through windows.

A 7 x 5 x 3 m room (glTF's y up, metres; x east, z south) standing on a 24 x 24 m ground, with no lamp:
- a 3 x 1.5 m window in the south wall (z = 5) and a 1.2 x 1.5 m window in the east wall (x = 7), sills
  at 0.9 m, glazed: one pane of clear glass each (KHR_materials_transmission 1, roughness 0,
  KHR_materials_ior 1.5), which passes 92% of the light at normal incidence and less at grazing;
- the sun (KHR_lights_punctual, directional): 60,000 W/m^2 read one for one from lux, 35 degrees high in
  the south-west, so that a patch of sun falls through the south window onto the floor;
- the sky: the CIE clear sky with the sun where the light is (the scene's extras "walkrad:sky":
  "cie-clear:3000", zenith radiance 3,000 W/(m^2 sr));
- a table and a bookcase inside; walls, floor and ceiling of plain diffuse colours. The walls are
  single quads facing in, the roof a quad facing up over the ceiling facing down; the outside walls face
  out, so the ground sees a building.
A walkthrough (daylit-room-walkthrough.json) looks from the door's corner at the sunlit floor, then at
the east window. Deterministic.

Usage: make_daylit_room.py [OUT_DIR]   (default: beside this script: daylit-room.gltf,
daylit-room-walkthrough.json)
"""
import argparse
import base64
import json
import math
import os
import struct

W, D, H = 7.0, 5.0, 3.0  # x, z, y
SILL, TOP = 0.9, 2.4
SOUTH = (2.0, 5.0)  # x range of the south window
EAST = (1.9, 3.1)   # z range of the east window


def rect(axis, c, a0, a1, b0, b1, facing):
    """The axis-aligned rectangle coordinate[axis] = c over [a0, a1] x [b0, b1] on the next two axes in
    cyclic order (x: y, z; y: z, x; z: x, y), facing +axis (facing > 0) or -axis."""
    i, j = (axis + 1) % 3, (axis + 2) % 3

    def at(a, b):
        p = [0.0, 0.0, 0.0]
        p[axis], p[i], p[j] = c, a, b
        return tuple(p)
    q = [at(a0, b0), at(a1, b0), at(a1, b1), at(a0, b1)]
    return q if facing > 0 else [q[0], q[3], q[2], q[1]]


def wall_with_window(axis, c, facing, length, lo, hi):
    """A wall of height H and `length` along the axis after y (z for x walls, x for z walls), with a window
    over [lo, hi] between SILL and TOP: four quads around it."""
    if axis == 0:  # x = c: spans y (a), z (b)
        return [rect(0, c, 0, SILL, 0, length, facing), rect(0, c, TOP, H, 0, length, facing),
                rect(0, c, SILL, TOP, 0, lo, facing), rect(0, c, SILL, TOP, hi, length, facing)]
    # z = c: spans x (a), y (b)
    return [rect(2, c, 0, length, 0, SILL, facing), rect(2, c, 0, length, TOP, H, facing),
            rect(2, c, 0, lo, SILL, TOP, facing), rect(2, c, hi, length, SILL, TOP, facing)]


def box(lo, hi):
    """A closed box, faces out."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    return [rect(0, x0, y0, y1, z0, z1, -1), rect(0, x1, y0, y1, z0, z1, +1),
            rect(1, y0, z0, z1, x0, x1, -1), rect(1, y1, z0, z1, x0, x1, +1),
            rect(2, z0, x0, x1, y0, y1, -1), rect(2, z1, x0, x1, y0, y1, +1)]


def quaternion_from_to(a, b):
    """The shortest rotation taking unit a to unit b, as (x, y, z, w)."""
    c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    w = 1 + sum(x * y for x, y in zip(a, b))
    n = math.sqrt(w * w + sum(x * x for x in c))
    return [c[0] / n, c[1] / n, c[2] / n, w / n]


def write(out_dir):
    materials = [
        {"name": "wall", "pbrMetallicRoughness": {"baseColorFactor": [0.78, 0.76, 0.72, 1.0], "metallicFactor": 0.0}},
        {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.33, 0.22, 1.0], "metallicFactor": 0.0}},
        {"name": "ceiling", "pbrMetallicRoughness": {"baseColorFactor": [0.85, 0.85, 0.85, 1.0], "metallicFactor": 0.0}},
        {"name": "wood", "pbrMetallicRoughness": {"baseColorFactor": [0.35, 0.24, 0.16, 1.0], "metallicFactor": 0.0}},
        {"name": "books", "pbrMetallicRoughness": {"baseColorFactor": [0.55, 0.20, 0.15, 1.0], "metallicFactor": 0.0}},
        {"name": "ground", "pbrMetallicRoughness": {"baseColorFactor": [0.25, 0.28, 0.18, 1.0], "metallicFactor": 0.0}},
        {"name": "facade", "pbrMetallicRoughness": {"baseColorFactor": [0.60, 0.55, 0.50, 1.0], "metallicFactor": 0.0}},
        {"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0,
                                                   "roughnessFactor": 0.0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.5}}},
    ]
    inside = (wall_with_window(2, D, -1, W, *SOUTH) + wall_with_window(0, W, -1, D, *EAST) +
              [rect(2, 0, 0, W, 0, H, +1), rect(0, 0, 0, H, 0, D, +1)])
    outside = (wall_with_window(2, D, +1, W, *SOUTH) + wall_with_window(0, W, +1, D, *EAST) +
               [rect(2, 0, 0, W, 0, H, -1), rect(0, 0, 0, H, 0, D, -1), rect(1, H, 0, D, 0, W, +1)])
    # Window reveals are left out: the walls have no thickness.
    # Around the building's footprint, not under it (the floor is there).
    ground = [rect(1, 0, -9.5, 0, -8.5, 15.5, +1), rect(1, 0, D, 14.5, -8.5, 15.5, +1),
              rect(1, 0, 0, D, -8.5, 0, +1), rect(1, 0, 0, D, W, 15.5, +1)]
    parts = [("floor", 1, [rect(1, 0, 0, D, 0, W, +1)]), ("ceiling", 2, [rect(1, H, 0, D, 0, W, -1)]),
             ("walls", 0, inside), ("facade", 6, outside), ("ground", 5, ground),
             ("table", 3, box((2.6, 0.0, 1.8), (4.2, 0.75, 2.7))),
             ("bookcase", 4, box((0.05, 0.0, 0.6), (0.45, 2.0, 2.4))),
             ("panes", 7, [rect(2, D, SOUTH[0], SOUTH[1], SILL, TOP, -1), rect(0, W, SILL, TOP, EAST[0], EAST[1], -1)])]
    blob = bytearray()
    gltf = {"asset": {"version": "2.0", "generator": "walkrad examples/daylit-room/make_daylit_room.py"},
            "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior"], "materials": materials, "meshes": [], "accessors": [],
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
    # The sun 35 degrees high, from the south-west (+z is south, -x west): it shines along -(towards).
    elevation, azimuth = math.radians(35), math.radians(40)  # azimuth from south towards west
    towards = [-math.cos(elevation) * math.sin(azimuth), math.sin(elevation), math.cos(elevation) * math.cos(azimuth)]
    gltf["extensions"] = {"KHR_lights_punctual": {"lights": [{"name": "sun", "type": "directional", "intensity": 60000.0,
                                                              "color": [1.0, 0.96, 0.9]}]}}
    gltf["nodes"].append({"name": "sun", "rotation": quaternion_from_to([0, 0, -1], [-x for x in towards]),
                          "extensions": {"KHR_lights_punctual": {"light": 0}}})
    gltf["scenes"] = [{"nodes": list(range(len(gltf["nodes"]))), "extras": {"walkrad:sky": "cie-clear:3000"}}]
    gltf["scene"] = 0
    gltf["buffers"] = [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode("ascii")}]
    with open(os.path.join(out_dir, "daylit-room.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    walk = {"format": "walkrad-walkthrough", "version": 1,
            "path": {"frames": 3, "yfov_deg": 75, "aspect": 1.5, "keyframes": [
                {"time": 0.0, "position": [0.8, 1.6, 0.8], "target": [3.5, 0.2, 4.2]},
                {"time": 0.5, "position": [2.0, 1.6, 1.0], "target": [6.8, 1.0, 2.5]},
                {"time": 1.0, "position": [5.5, 1.6, 1.0], "target": [3.0, 0.5, 4.8]}]}}
    with open(os.path.join(out_dir, "daylit-room-walkthrough.json"), "w") as f:
        json.dump(walk, f, indent=1)
        f.write("\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out_dir", nargs="?", default=os.path.dirname(os.path.abspath(__file__)),
                    help="folder for daylit-room.gltf and its walkthrough (default: beside this script)")
    out = ap.parse_args().out_dir
    os.makedirs(out, exist_ok=True)
    write(out)


if __name__ == "__main__":
    main()
