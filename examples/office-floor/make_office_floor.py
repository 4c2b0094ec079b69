#!/usr/bin/env python3
"""Writes "office floor": a generated building for walkrad's hierarchical radiosity tests and benchmarks.

Layout (metres, y up): a wing is a corridor along +x (2 m wide) with rooms of 5 x 4 m on both sides, each
entered by a doorway of 1.0 x 2.1 m; ceilings at 2.7 m, walls 0.1 m thick. Larger buildings have several
wings side by side along +z, joined at their west ends (x < 0) by a spine corridor along +z. Rooms fill the
wings slot by slot (south, north), so room k keeps its place, furniture and random seed for every --rooms:
doubling the building adds rooms and keeps the ones that were there.

Conventions the solver relies on:
- Every surface is a planar convex quad, written as two consecutive triangles (0,1,2)(0,2,3), counter-clockwise
  seen from its front (the side that receives and emits light); the glTF reader merges each pair back.
- Each room and corridor is a box of faces that face into it (floor up, ceiling down, walls inwards). A doorway
  is a hole in the faces on both sides of a wall, joined by its reveal (two jambs, a head, a threshold): the
  building is closed, and a wall between two spaces is two faces back to back, 0.1 m apart.
- Furniture is boxes with outward faces. A face that rests on something (the floor, a table top, a shelf side
  or board, a seat) is left out, so nothing interpenetrates and no two polygons overlap in one plane.
- Lights: 0.6 x 0.6 x 0.01 m panels 1 cm below the ceiling, their bottom emitting (radiance 8, warm, in
  rooms; 6, cool, in corridors) and the rest a closed white housing. Every reflectance is below 0.9.

Usage: make_office_floor.py [--rooms N] [--detail D] [--out DIR]
Writes into DIR (default: beside this script) office-floor.glb (office-floor-N.glb, -N-walkthrough.json,
-N-rooms.json when N != 8), office-floor-walkthrough.json (a camera path at eye height that enters only two
rooms, "A" = room-00 and "B" = room-01, through the middle of their doorways, and never faces another doorway)
and office-floor-rooms.json (each room's and corridor's inside bounds, and whether the walkthrough visits it).
--detail scales the number of books, which carry most of the polygons (about 6,500 triangles a room at 1).
The output is deterministic: the same arguments give the same bytes.
"""
import argparse
import json
import math
import os
import random
import struct

T, H = 0.1, 2.7                      # wall thickness, ceiling height
ROOM_W, ROOM_D, CORR_W = 5.0, 4.0, 2.0
DOOR_U, DOOR_W, DOOR_H = 0.6, 1.0, 2.1  # doorway from u = 0.6 to 1.6 along the room's door wall
PITCH = ROOM_W + T                   # room slots along x
WING = 2 * ROOM_D + CORR_W + 3 * T   # wings along z
EYE = 1.6

MATERIALS = [  # name, base colour (diffuse reflectance), emission (factor, strength)
    ("wall", (0.7, 0.7, 0.7)), ("floor", (0.45, 0.4, 0.33)), ("ceiling", (0.8, 0.8, 0.8)),
    ("wood", (0.5, 0.34, 0.2)), ("shelf", (0.62, 0.52, 0.38)), ("metal", (0.35, 0.35, 0.37)),
    ("fabric", (0.2, 0.3, 0.55)), ("book-red", (0.6, 0.12, 0.1)), ("book-blue", (0.12, 0.2, 0.5)),
    ("book-green", (0.15, 0.42, 0.2)), ("book-yellow", (0.72, 0.6, 0.2)), ("book-cream", (0.82, 0.78, 0.65)),
    ("book-black", (0.08, 0.08, 0.08)), ("housing", (0.8, 0.8, 0.8)),
    ("light-warm", (0.8, 0.8, 0.8), ((1.0, 0.92, 0.8), 8.0)), ("light-cool", (0.8, 0.8, 0.8), ((0.9, 0.95, 1.0), 6.0)),
]
M = {m[0]: i for i, m in enumerate(MATERIALS)}
BOOKS = [i for m, i in M.items() if m.startswith("book-")]


# --- Quads and boxes ----------------------------------------------------------------------------------------------

def rect(axis, c, lo, hi, sign):
    """The rectangle coordinate[axis] = c spanning lo..hi on the other two axes (lo, hi: 3-tuples whose axis
    component is ignored), facing +axis (sign > 0) or -axis; [] when it has no area."""
    i, j = (axis + 1) % 3, (axis + 2) % 3   # e_i x e_j = e_axis
    if hi[i] - lo[i] < 1e-9 or hi[j] - lo[j] < 1e-9:
        return []
    quad = []
    for a, b in ((lo[i], lo[j]), (hi[i], lo[j]), (hi[i], hi[j]), (lo[i], hi[j])):
        p = [0.0, 0.0, 0.0]
        p[axis], p[i], p[j] = c, a, b
        quad.append(tuple(p))
    return [quad if sign > 0 else quad[::-1]]


def panels(axis, c, lo, hi, sign, max_aspect=3.0):
    """rect, cut across its longer side into pieces no longer than max_aspect times their width."""
    i, j = (axis + 1) % 3, (axis + 2) % 3
    di, dj = hi[i] - lo[i], hi[j] - lo[j]
    if min(di, dj) < 1e-9:
        return []
    k = i if di >= dj else j
    n = max(1, math.ceil(max(di, dj) / (max_aspect * min(di, dj)) - 1e-9))
    out = []
    for s in range(n):
        a, b = list(lo), list(hi)
        a[k], b[k] = lo[k] + (hi[k] - lo[k]) * s / n, lo[k] + (hi[k] - lo[k]) * (s + 1) / n
        out += rect(axis, c, a, b, sign)
    return out


def box(lo, hi, skip=()):
    """A box lo..hi with outward faces; skip names the faces left out ("-y": the bottom, "+x", ...)."""
    out = []
    for axis, name in enumerate("xyz"):
        if "-" + name not in skip:
            out += rect(axis, lo[axis], lo, hi, -1)
        if "+" + name not in skip:
            out += rect(axis, hi[axis], lo, hi, +1)
    return out


def turned(k, ox, oz):
    """k quarter turns about +y, then a shift by (ox, 0, oz): a rotation, so windings stay counter-clockwise."""
    c, s = [(1, 0), (0, 1), (-1, 0), (0, -1)][k % 4]
    return lambda p: (ox + c * p[0] + s * p[2], p[1], oz - s * p[0] + c * p[2])


def moved(items, f):
    return [(m, [f(p) for p in q]) for m, q in items]


def tagged(material, quads):
    return [(material, q) for q in quads]


# --- Furniture, each piece in its own frame (see its docstring), placed with turned() -----------------------------

def table(x0, x1, z0, z1, height=0.75, top=0.03, leg=0.05):
    """A wooden top on four legs standing on the floor; the legs' ends touch the floor and the top: left out."""
    out = tagged(M["wood"], box((x0, height - top, z0), (x1, height, z1)))
    for lx in (x0 + leg, x1 - 2 * leg):
        for lz in (z0 + leg, z1 - 2 * leg):
            out += tagged(M["metal"], box((lx, 0, lz), (lx + leg, height - top, lz + leg), skip=("-y", "+y")))
    return out


def chair(seat=0.44, height=0.45, back=0.9, leg=0.03):
    """A chair centred on the origin, facing -z: four legs, a seat, a back standing on the seat's rear edge."""
    h, out = seat / 2, []
    for lx in (-h + 0.02, h - 0.02 - leg):
        for lz in (-h + 0.02, h - 0.02 - leg):
            out += tagged(M["metal"], box((lx, 0, lz), (lx + leg, height - 0.04, lz + leg), skip=("-y", "+y")))
    out += tagged(M["fabric"], box((-h, height - 0.04, -h), (h, height, h)))
    out += tagged(M["fabric"], box((-h, height, h - 0.04), (h, back, h), skip=("-y",)))
    return out


def books(rng, x0, x1, y, depth, clear, detail):
    """Books standing (now and then a stack lying) on a board whose top is at y, between x0 and x1, front at
    z = 0.02; bottoms left out. Gaps of at least 3 mm keep neighbours apart."""
    out, x = [], x0 + 0.005
    while True:
        colour = rng.choice(BOOKS)
        if rng.random() < 0.06:        # a gap
            x += rng.uniform(0.05, 0.15)
            continue
        if rng.random() < 0.05:        # a stack of 2-5 books lying flat, each resting on the one below
            w, d, yy = rng.uniform(0.15, 0.24), rng.uniform(0.12, depth - 0.04), y
            if x + w > x1 - 0.005:
                break
            for _ in range(rng.randint(2, 5)):
                t = rng.uniform(0.02, 0.05) / detail
                if yy + t > y + clear - 0.03:
                    break
                out += tagged(rng.choice(BOOKS), box((x, yy, 0.02), (x + w, yy + t, 0.02 + d), skip=("-y",)))
                yy += t
            x += w + rng.uniform(0.003, 0.01)
            continue
        w = rng.uniform(0.018, 0.05) / detail
        if x + w > x1 - 0.005:
            break
        h = rng.uniform(0.17, min(0.31, clear - 0.03))
        d = rng.uniform(0.14, depth - 0.04)
        out += tagged(colour, box((x, y, 0.02), (x + w, y + h, 0.02 + d), skip=("-y",)))
        x += w + rng.uniform(0.003, 0.008)
    return out


def shelf(rng, detail, width=1.2, depth=0.35, height=2.0, levels=5, board=0.02):
    """A bookcase: x 0..width, z 0..depth with its open front at z = 0 facing -z; two sides standing on the
    floor, boards between them (ends touch the sides: left out), books on the five lower boards."""
    out = tagged(M["shelf"], box((0, 0, 0), (board, height, depth), skip=("-y",)))
    out += tagged(M["shelf"], box((width - board, 0, 0), (width, height, depth), skip=("-y",)))
    step = (height - 0.1 - board) / levels
    for k in range(levels + 1):
        y = 0.08 + k * step
        out += tagged(M["shelf"], box((board, y, 0), (width - board, y + board, depth), skip=("-x", "+x")))
        if k < levels:
            out += books(rng, board, width - board, y + board, depth, step - board, detail)
    return out


def light(x, z, material, size=0.6, gap=0.01, thick=0.01):
    """A panel hanging `gap` below the ceiling: its bottom emits, the rest is a closed white housing, so
    that light reaching its back is reflected, not lost to a one-sided surface."""
    lo, hi = (x - size / 2, H - gap - thick, z - size / 2), (x + size / 2, H - gap, z + size / 2)
    return tagged(M[material], rect(1, lo[1], lo, hi, -1)) + tagged(M["housing"], box(lo, hi, skip=("-y",)))


def furnish(rng, detail):
    """A room's contents in room coordinates: u (x) 0..5 along the door wall, v (z) 0..4 from the door wall
    (doorway at u 0.6..1.6) to the back wall. Five bookcases 2 cm off the walls, a table with six chairs, a desk."""
    out = []
    for u0 in (0.25, 1.9, 3.55):                                  # three bookcases on the back wall
        out += moved(shelf(rng, detail), turned(0, u0, ROOM_D - 0.02 - 0.35))
    for v1 in (1.5, 2.85):                                        # two on the side wall u = 5
        out += moved(shelf(rng, detail), turned(1, ROOM_W - 0.02 - 0.35, v1))
    out += table(1.6, 3.4, 1.5, 2.4)
    for u, v, k in ((2.05, 1.2, 2), (2.95, 1.2, 2), (2.05, 2.7, 0), (2.95, 2.7, 0), (1.3, 1.95, 3), (3.7, 1.95, 1)):
        out += moved(chair(), turned(k, u, v))
    out += table(0.05, 0.75, 2.3, 3.5)                              # a desk on the wall u = 0, its chair
    out += moved(chair(), turned(1, 1.05, 2.9))
    out += light(1.5, 2.0, "light-warm") + light(3.5, 2.0, "light-warm")
    return out


# --- The building: spaces, walls with doorways, layout ------------------------------------------------------------

WALL = {"-x": 0, "+x": 1, "-z": 2, "+z": 3}  # a wall's coordinate in a space's box (x0, x1, z0, z1)


def space(name, x0, x1, z0, z1):
    return {"name": name, "box": (x0, x1, z0, z1), "openings": {"-x": [], "+x": [], "-z": [], "+z": []}, "items": []}


def shell(sp):
    """Floor, ceiling and the four walls of a space, facing into it, with holes for its openings."""
    x0, x1, z0, z1 = sp["box"]
    out = tagged(M["floor"], panels(1, 0.0, (x0, 0, z0), (x1, 0, z1), +1))
    out += tagged(M["ceiling"], panels(1, H, (x0, 0, z0), (x1, 0, z1), -1))
    for wall, (axis, c, a0, a1, sign) in (("-x", (0, x0, z0, z1, +1)), ("+x", (0, x1, z0, z1, -1)),
                                          ("-z", (2, z0, x0, x1, +1)), ("+z", (2, z1, x0, x1, -1))):
        along, cursor, pieces = 2 - axis, a0, []
        for o0, o1, h in sorted(sp["openings"][wall]):
            pieces += [(cursor, o0, 0.0), (o0, o1, h)]          # wall up to the opening, lintel above it
            cursor = o1
        for b0, b1, y0 in pieces + [(cursor, a1, 0.0)]:
            lo, hi = [0.0, y0, 0.0], [0.0, H, 0.0]
            lo[along], hi[along] = b0, b1
            out += tagged(M["wall"], panels(axis, c, lo, hi, sign))
    return out


def connect(a, wall_a, b, wall_b, o0, o1, h):
    """A doorway o0..o1 (along the wall), h high, from space a's wall to space b's facing wall: holes in both
    and the reveal between them (two jambs, a head, a threshold, facing into the opening), in a's mesh."""
    axis, along = (0, 2) if wall_a[1] == "x" else (2, 0)
    g0, g1 = sorted((a["box"][WALL[wall_a]], b["box"][WALL[wall_b]]))
    a["openings"][wall_a].append((o0, o1, h))
    b["openings"][wall_b].append((o0, o1, h))
    lo, hi = [0.0, 0.0, 0.0], [0.0, h, 0.0]
    lo[axis], hi[axis], lo[along], hi[along] = g0, g1, o0, o1
    a["items"] += tagged(M["wall"], rect(along, o0, lo, hi, +1) + rect(along, o1, lo, hi, -1) + rect(1, h, lo, hi, -1))
    a["items"] += tagged(M["floor"], rect(1, 0.0, lo, hi, +1))


def layout(n):
    """(wings, rooms per side of a wing): near square, room k in wing k // (2 s), slot (k // 2) % s."""
    wings = max(1, int(math.sqrt(n / 4)))
    return wings, math.ceil(n / (2 * wings))


def room_frame(k, per_side):
    """Room k's frame: room (u, y, v) -> world. South rooms (even k) turn half round, so that both kinds have
    their door wall at v = 0 and doors on opposite sides of a corridor do not face each other."""
    w, i, north = k // (2 * per_side), (k // 2) % per_side, k % 2
    b, x0 = w * WING, i * PITCH
    return turned(0, x0, b + ROOM_D + 2 * T + CORR_W) if north else turned(2, x0 + ROOM_W, b + ROOM_D)


def build(n, detail):
    wings, per_side = layout(n)
    length = per_side * PITCH - T
    corridors = [space(f"corridor-{w}", 0.0, length, w * WING + ROOM_D + T, w * WING + ROOM_D + T + CORR_W)
                 for w in range(wings)]
    for c in corridors:
        for i in range(per_side):
            c["items"] += light(i * PITCH + ROOM_W / 2, c["box"][2] + CORR_W / 2, "light-cool")
    spaces = list(corridors)
    if wings > 1:
        spine = space("spine", -T - CORR_W, -T, corridors[0]["box"][2], corridors[-1]["box"][3])
        for c in corridors:
            connect(c, "-x", spine, "+x", c["box"][2], c["box"][3], DOOR_H)
        for s in range(2 * wings - 1):
            spine["items"] += light(-T - CORR_W / 2, corridors[0]["box"][2] + CORR_W / 2 + s * WING / 2, "light-cool")
        spaces.append(spine)
    rooms = []
    for k in range(n):
        f = room_frame(k, per_side)
        (xa, _, za), (xb, _, zb) = f((0, 0, 0)), f((ROOM_W, 0, ROOM_D))
        room = space(f"room-{k:02d}", min(xa, xb), max(xa, xb), min(za, zb), max(za, zb))
        room["frame"] = f
        d0, d1 = sorted((f((DOOR_U, 0, 0))[0], f((DOOR_U + DOOR_W, 0, 0))[0]))
        corridor = corridors[k // (2 * per_side)]
        connect(room, "-z" if k % 2 else "+z", corridor, "+z" if k % 2 else "-z", d0, d1, DOOR_H)
        room["items"] += moved(furnish(random.Random(1000 + k), detail), f)
        rooms.append(room)
    spaces = rooms + spaces
    for sp in spaces:
        sp["items"] = shell(sp) + sp["items"]
    return rooms, spaces


# --- The walkthrough ----------------------------------------------------------------------------------------------

def walkthrough(rooms):
    """Keyframes (time, position, target): from the corridor into room A through the middle of its doorway,
    a look round (never back at the doorway), backing out, along the corridor facing away from the other
    doorways, then into room B the same way. Room coordinates: the corridor's centre line is v = -1.1."""
    def at(room, u, v, y=EYE):
        return room["frame"]((u, y, v))
    mid, corr = DOOR_U + DOOR_W / 2, -T - CORR_W / 2

    def visit(r, t):
        return [(t, at(r, mid, corr - 0.5), at(r, mid, 2.0, 1.3)),             # corridor, facing the doorway
                (t + 2, at(r, mid, -0.6), at(r, mid, 3.0, 1.3)),
                (t + 3, at(r, mid, 0.05), at(r, mid, 3.5, 1.2)),                 # just through it
                (t + 4.5, at(r, mid + 0.05, 1.0), at(r, 1.2, 4.0, 1.1)),         # back wall bookcases
                (t + 6.5, at(r, mid + 0.1, 1.0), at(r, 4.5, 2.2, 1.0)),          # side wall bookcases
                (t + 8.5, at(r, mid + 0.1, 1.1), at(r, 3.0, 4.0, 1.0)),          # table
                (t + 10, at(r, mid + 0.05, 0.9), at(r, mid, 4.0, 1.2))]
    keys = visit(rooms[0], 0.0)
    if len(rooms) > 1:
        a, b = rooms[0], rooms[1]
        keys += [(11.5, at(a, mid, 0.05), at(a, mid, 4.0, 1.3)),               # backing out, still facing A
                 (13.0, at(a, mid, corr), at(a, mid, 3.0, 1.4)),
                 (14.5, at(a, mid + 0.4, corr), at(a, mid + 4.0, corr - 0.5, 1.5)),  # turned west, towards B
                 (17.0, at(b, mid + 0.6, corr), at(b, mid - 3.5, corr + 0.5, 1.5))]
        keys += visit(b, 18.5)[1:]
    return keys


def camera_rotation(pos, target):
    """The quaternion (x, y, z, w) turning a glTF camera (looking along -z) towards target: yaw, then pitch."""
    d = [t - p for t, p in zip(target, pos)]
    yaw, pitch = math.atan2(-d[0], -d[2]), math.atan2(d[1], math.hypot(d[0], d[2]))
    cy, sy, cp, sp = math.cos(yaw / 2), math.sin(yaw / 2), math.cos(pitch / 2), math.sin(pitch / 2)
    return [round(v, 9) for v in (cy * sp, sy * cp, -sy * sp, cy * cp)]


# --- Output -------------------------------------------------------------------------------------------------------

def f32(v):
    return struct.unpack("<f", struct.pack("<f", v))[0]


def gltf(spaces, first_key):
    """One mesh (and node) per space, one primitive per material, shared vertices within a primitive."""
    blob, views, accessors, meshes, triangles = bytearray(), [], [], [], 0

    def view(data, target):
        blob.extend(b"\0" * (-len(blob) % 4))
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(views) - 1

    for sp in spaces:
        by_material = {}
        for m, q in sp["items"]:
            by_material.setdefault(m, []).append(q)
        primitives = []
        for m in sorted(by_material):
            ids, idx = {}, []
            for q in by_material[m]:
                c = [ids.setdefault(tuple(round(x, 6) + 0.0 for x in p), len(ids)) for p in q]
                idx += [c[0], c[1], c[2], c[0], c[2], c[3]] if len(c) == 4 else c
            verts = [tuple(f32(x) for x in p) for p in ids]
            pos = view(b"".join(struct.pack("<3f", *p) for p in verts), 34962)
            accessors.append({"bufferView": pos, "componentType": 5126, "count": len(verts), "type": "VEC3",
                              "min": [min(p[i] for p in verts) for i in range(3)],
                              "max": [max(p[i] for p in verts) for i in range(3)]})
            wide = len(verts) > 65535
            ind = view(struct.pack(f"<{len(idx)}{'I' if wide else 'H'}", *idx), 34963)
            accessors.append({"bufferView": ind, "componentType": 5125 if wide else 5123, "count": len(idx),
                              "type": "SCALAR"})
            primitives.append({"attributes": {"POSITION": len(accessors) - 2}, "indices": len(accessors) - 1,
                               "material": m})
            triangles += len(idx) // 3
        meshes.append({"name": sp["name"], "primitives": primitives})
    nodes = [{"name": m["name"], "mesh": i} for i, m in enumerate(meshes)]
    _, pos, target = first_key
    nodes.append({"name": "camera", "camera": 0, "translation": r6(pos),
                  "rotation": camera_rotation(pos, target)})
    materials = []
    for name, rgb, *emission in MATERIALS:
        mat = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1.0], "metallicFactor": 0.0}}
        if emission:
            (factor, strength), = emission
            mat["emissiveFactor"] = list(factor)
            mat["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        materials.append(mat)
    doc = {
        "asset": {"version": "2.0", "generator": "walkrad examples/office-floor/make_office_floor.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"name": "office floor", "nodes": list(range(len(nodes)))}],
        "nodes": nodes, "meshes": meshes, "materials": materials,
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": math.radians(60), "aspectRatio": 1.5, "znear": 0.05}}],
        "accessors": accessors, "bufferViews": views, "buffers": [{"byteLength": len(blob)}],
    }
    return doc, bytes(blob), triangles


def write_glb(path, doc, blob):
    """Binary glTF: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded with zeros."""
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(text) + 8 + len(blob)))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(blob), b"BIN\0") + blob)
    return 12 + 8 + len(text) + 8 + len(blob)


def r6(p):
    return [round(x, 6) + 0.0 for x in p]


def bounds(sp):
    x0, x1, z0, z1 = sp["box"]
    return {"name": sp["name"], "min": r6((x0, 0, z0)), "max": r6((x1, H, z1))}


def write_json(path, value):
    with open(path, "w") as f:
        json.dump(value, f, indent=1)
        f.write("\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rooms", type=int, default=8, help="number of rooms (default 8)")
    ap.add_argument("--detail", type=float, default=1.0, help="book density: 1 gives ~6,500 triangles a room")
    ap.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)), help="output folder")
    args = ap.parse_args()
    if args.rooms < 1 or not 0.05 <= args.detail <= 4:
        ap.error("--rooms must be at least 1 and --detail within [0.05, 4]")
    os.makedirs(args.out, exist_ok=True)
    stem = os.path.join(args.out, "office-floor" if args.rooms == 8 else f"office-floor-{args.rooms}")
    rooms, spaces = build(args.rooms, args.detail)
    keys = walkthrough(rooms)
    doc, blob, triangles = gltf(spaces, keys[0])
    size = write_glb(stem + ".glb", doc, blob)
    write_json(stem + "-walkthrough.json", {"format": "walkrad-walkthrough", "version": 1, "path": {
        "frames": 240, "yfov_deg": 60, "aspect": 1.5,
        "keyframes": [{"time": t, "position": r6(p), "target": r6(q)} for t, p, q in keys]}})
    write_json(stem + "-rooms.json", {
        "scene": os.path.basename(stem) + ".glb", "walkthrough": os.path.basename(stem) + "-walkthrough.json",
        "rooms": [dict(bounds(r), visited=i < 2) for i, r in enumerate(rooms)],
        "corridors": [bounds(sp) for sp in spaces[len(rooms):]]})
    lights = sum(1 for sp in spaces for m, _ in sp["items"] if MATERIALS[m][0].startswith("light"))
    print(f"wrote {stem}.glb: {len(rooms)} rooms, {triangles} triangles, {lights} lights, {size} bytes")


if __name__ == "__main__":
    main()
