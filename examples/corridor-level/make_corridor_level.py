#!/usr/bin/env python3
"""Writes "corridor level": rooms in a row along one corridor, lit only inside the rooms, for walkrad's
tests of light that enters a large polygon through a small opening.

Layout (metres, y up): room k spans x in [5k, 5k + 5], z in [0, 4]; the corridor spans x in [0, 5N], z in
[4, 6]; ceilings at 2.7 m. Walls have no thickness: the wall between two rooms is two quads back to back in
one plane, and so is each room's door wall and the corridor's near wall. Each room opens on the corridor by a
doorway of 1.0 x 2.1 m (x in [5k + 2, 5k + 3]). Each room has one 0.6 x 0.6 m ceiling light 1 cm below its
ceiling (radiance --radiance, white, emitting downwards); the corridor has none: it is lit only through the
doorways. The corridor's floor, ceiling and far wall are each one quad along the whole level (80 m at 16
rooms), so that the light of a doorway falls on a polygon many times its size.

Every surface is a planar convex quad facing into its space, written as two triangles (0,1,2)(0,2,3).
Reflectances: walls 0.7, floors 0.5, ceilings 0.8.

The walkthrough (N >= 2: rooms 0 and 1; N = 1: room 0) is a list of viewpoints at eye height in the visited
rooms, among them one through each visited room's doorway into the corridor.

Usage: make_corridor_level.py [--rooms N] [--out DIR]
Writes DIR/corridor-N.glb, DIR/corridor-N-walkthrough.json. Deterministic: the same arguments, the same bytes.
"""
import argparse
import json
import math
import os
import struct

ROOM_W, ROOM_D, CORR_W, H = 5.0, 4.0, 2.0, 2.7
DOOR_X0, DOOR_X1, DOOR_H = 2.0, 3.0, 2.1
LAMP, LAMP_GAP = 0.6, 0.01
EYE = 1.6

WALL, FLOOR, CEILING, LIGHT = 0, 1, 2, 3
MATERIALS = [("wall", 0.7), ("floor", 0.5), ("ceiling", 0.8), ("light", 0.8)]


def quad(axis, c, a0, a1, b0, b1, facing):
    """The rectangle coordinate[axis] = c, spanning [a0, a1] x [b0, b1] on the next two axes in cyclic order
    (x: y, z; y: z, x; z: x, y), facing +axis (facing > 0) or -axis."""
    i, j = (axis + 1) % 3, (axis + 2) % 3
    corners = []
    for a, b in ((a0, b0), (a1, b0), (a1, b1), (a0, b1)):
        p = [0.0, 0.0, 0.0]
        p[axis], p[i], p[j] = c, a, b
        corners.append(tuple(p))
    return corners if facing > 0 else corners[::-1]


def level(n):
    """(material, quad) for every surface of an n-room level."""
    X, Y, Z = 0, 1, 2
    out = []
    length = ROOM_W * n
    for k in range(n):
        x0, x1 = ROOM_W * k, ROOM_W * (k + 1)
        dx0, dx1 = x0 + DOOR_X0, x0 + DOOR_X1
        out += [(FLOOR, quad(Y, 0.0, 0.0, ROOM_D, x0, x1, +1)),
                (CEILING, quad(Y, H, 0.0, ROOM_D, x0, x1, -1)),
                (WALL, quad(Z, 0.0, x0, x1, 0.0, H, +1)),           # back wall
                (WALL, quad(X, x0, 0.0, H, 0.0, ROOM_D, +1)),       # west wall (back to back with room k-1's)
                (WALL, quad(X, x1, 0.0, H, 0.0, ROOM_D, -1)),       # east wall
                # the door wall, seen from the room (facing -z), around the doorway
                (WALL, quad(Z, ROOM_D, x0, dx0, 0.0, H, -1)),
                (WALL, quad(Z, ROOM_D, dx1, x1, 0.0, H, -1)),
                (WALL, quad(Z, ROOM_D, dx0, dx1, DOOR_H, H, -1)),
                # the corridor's side of the door head
                (WALL, quad(Z, ROOM_D, dx0, dx1, DOOR_H, H, +1))]
        cx, cz, a = x0 + ROOM_W / 2, ROOM_D / 2, LAMP / 2
        out.append((LIGHT, quad(Y, H - LAMP_GAP, cz - a, cz + a, cx - a, cx + a, -1)))
    # The corridor: one floor, one ceiling, one far wall along the whole level; its near wall between doors.
    z0, z1 = ROOM_D, ROOM_D + CORR_W
    out += [(FLOOR, quad(Y, 0.0, z0, z1, 0.0, length, +1)),
            (CEILING, quad(Y, H, z0, z1, 0.0, length, -1)),
            (WALL, quad(Z, z1, 0.0, length, 0.0, H, -1)),
            (WALL, quad(X, 0.0, 0.0, H, z0, z1, +1)),
            (WALL, quad(X, length, 0.0, H, z0, z1, -1))]
    edges = [0.0] + [e for k in range(n) for e in (ROOM_W * k + DOOR_X0, ROOM_W * k + DOOR_X1)] + [length]
    for a, b in zip(edges[0::2], edges[1::2]):
        out.append((WALL, quad(Z, z0, a, b, 0.0, H, +1)))
    return out


def walkthrough(n):
    """Viewpoints in rooms 0 and 1: the room's walls, and through its doorway into the corridor."""
    views = []
    for k in range(min(n, 2)):
        x0 = ROOM_W * k
        door = x0 + (DOOR_X0 + DOOR_X1) / 2
        for name, pos, target in (
                ("door", (door, EYE, 1.2), (door, 0.6, ROOM_D + 2.5)),            # through the doorway
                ("back", (x0 + 2.5, EYE, 3.3), (x0 + 2.0, 1.0, 0.0)),
                ("west", (x0 + 4.0, EYE, 2.0), (x0, 1.2, 1.5)),
                ("east", (x0 + 1.0, EYE, 2.5), (x0 + ROOM_W, 1.0, 2.0)),
                ("oblique", (x0 + 1.2, EYE, 0.8), (x0 + DOOR_X1 + 0.4, 0.3, ROOM_D + 1.5))):  # doorway, at a slant
            views.append({"name": f"room{k}-{name}", "position": r6(pos), "target": r6(target), "up": [0, 1, 0],
                          "yfov_deg": 60, "aspect": 1.5})
    return {"format": "walkrad-walkthrough", "version": 1, "viewpoints": views}


def r6(p):
    return [round(x, 6) + 0.0 for x in p]


def gltf(items):
    """One mesh, one primitive per material, vertices shared within a primitive."""
    blob, views, accessors, primitives = bytearray(), [], [], []

    def view(data, target):
        blob.extend(b"\0" * (-len(blob) % 4))
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(views) - 1

    for m in range(len(MATERIALS)):
        ids, idx = {}, []
        for mat, q in items:
            if mat != m:
                continue
            c = [ids.setdefault(tuple(round(x, 6) + 0.0 for x in p), len(ids)) for p in q]
            idx += [c[0], c[1], c[2], c[0], c[2], c[3]]
        if not idx:
            continue
        verts = list(ids)
        pos = view(b"".join(struct.pack("<3f", *p) for p in verts), 34962)
        accessors.append({"bufferView": pos, "componentType": 5126, "count": len(verts), "type": "VEC3",
                          "min": [min(p[i] for p in verts) for i in range(3)],
                          "max": [max(p[i] for p in verts) for i in range(3)]})
        ind = view(struct.pack(f"<{len(idx)}I", *idx), 34963)
        accessors.append({"bufferView": ind, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        primitives.append({"attributes": {"POSITION": len(accessors) - 2}, "indices": len(accessors) - 1,
                           "material": m})
    materials = []
    for name, rho in MATERIALS:
        mat = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [rho, rho, rho, 1.0], "metallicFactor": 0.0}}
        if name == "light":
            mat["emissiveFactor"] = [1.0, 1.0, 1.0]
            mat["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": 8.0}}
        materials.append(mat)
    doc = {
        "asset": {"version": "2.0", "generator": "walkrad examples/corridor-level/make_corridor_level.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0, "scenes": [{"name": "corridor level", "nodes": [0]}],
        "nodes": [{"name": "level", "mesh": 0}], "meshes": [{"name": "level", "primitives": primitives}],
        "materials": materials, "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(blob)}],
    }
    return doc, bytes(blob)


def write_glb(path, doc, blob):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(text) + 8 + len(blob)))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(blob), b"BIN\0") + blob)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rooms", type=int, default=16, help="number of rooms (default 16)")
    ap.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)), help="output folder")
    args = ap.parse_args()
    if args.rooms < 1:
        ap.error("--rooms must be at least 1")
    os.makedirs(args.out, exist_ok=True)
    stem = os.path.join(args.out, f"corridor-{args.rooms}")
    items = level(args.rooms)
    write_glb(stem + ".glb", *gltf(items))
    with open(stem + "-walkthrough.json", "w") as f:
        json.dump(walkthrough(args.rooms), f, indent=1)
        f.write("\n")
    print(f"wrote {stem}.glb: {args.rooms} rooms, {len(items)} quads, a {ROOM_W * args.rooms:g} m corridor")


if __name__ == "__main__":
    main()
