#!/usr/bin/env python3
"""Writes the hand-made seed inputs of tests/fuzz/corpus/ (small, valid files that reach every
branch of each reader). Files copied from the examples and from a Cornell bake are added by
scripts/fuzz.sh --seed; the fuzzers' own finds are merged in by scripts/fuzz.sh.
Usage: make_seeds.py CORPUS_DIR"""
import base64
import json
import os
import struct
import sys

corpus = sys.argv[1]


def write(target, name, data):
    os.makedirs(os.path.join(corpus, target), exist_ok=True)
    with open(os.path.join(corpus, target, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def glb(doc, binary):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    out = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + (8 + len(binary) if binary else 0))
    out += struct.pack("<II", len(text), 0x4E4F534A) + text
    if binary:
        out += struct.pack("<II", len(binary), 0x004E4942) + binary
    return out


# One quad (two triangles, u16 indices), a material with texture-free colour and emission, a camera
# under a TRS node, a second node with a matrix.
positions = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0)
indices = struct.pack("<6H", 0, 1, 2, 0, 2, 3)
blob = positions + indices
doc = {
    "asset": {"version": "2.0"},
    "scene": 0,
    "scenes": [{"nodes": [0, 1, 2]}],
    "nodes": [{"mesh": 0, "translation": [0, 0, 1], "rotation": [0, 0, 0, 1], "scale": [1, 2, 1]},
              {"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 3, 1], "children": [3]},
              {"camera": 0, "translation": [0.5, 0.5, 4]},
              {"mesh": 1}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.01}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]},
               {"primitives": [{"attributes": {"POSITION": 2}, "material": 1, "mode": 4}]}],
    "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.2, 1]}},
                  {"emissiveFactor": [1, 1, 1],
                   "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}],
    "extensionsUsed": ["KHR_materials_emissive_strength"],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                  {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "buffers": [{"byteLength": len(blob)}],
}
write("gltf", "quad.glb", glb(doc, blob))
embedded = json.loads(json.dumps(doc))
embedded["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
write("gltf", "quad-embedded.gltf", json.dumps(embedded, indent=1))
# The same with an EXT_lights_ies luminaire (a profile by data URI, a turned node, multiplier, colour).
ies = "IESNA:LM-63-2002\r\nTILT=NONE\r\n1 -1 1 3 1 1 2 0 0 0\r\n1 1 10\r\n0 45 90\r\n0\r\n100 50 0\r\n"
lit = json.loads(json.dumps(embedded))
lit["extensionsUsed"].append("EXT_lights_ies")
lit["extensions"] = {"EXT_lights_ies": {"lights": [
    {"uri": "data:application/x-ies-lm-63;base64," + base64.b64encode(ies.encode()).decode()}]}}
lit["nodes"].append({"name": "lamp", "translation": [0.5, 0.5, 2], "rotation": [0, 0, 0.3826834, 0.9238795],
                     "extensions": {"EXT_lights_ies": {"light": 0, "multiplier": 2, "color": [1, 0.9, 0.8]}}})
lit["scenes"][0]["nodes"].append(len(lit["nodes"]) - 1)
write("gltf", "quad-ies-light.gltf", json.dumps(lit, indent=1))

# A chunk as write_chunk lays it out: POSITION, NORMAL, COLOR_0, _RADIOSITY, u32 indices.
normals = struct.pack("<12f", *([0, 0, 1] * 4))
colors = struct.pack("<12f", *([0.5, 0.4, 0.3] * 4))
radiosity = struct.pack("<12f", *([2.0, 1.5, 1.0] * 4))
idx32 = struct.pack("<6I", 0, 1, 2, 0, 2, 3)
blob = positions + normals + colors + radiosity + idx32
views = [{"buffer": 0, "byteOffset": 48 * i, "byteLength": 48} for i in range(4)]
views.append({"buffer": 0, "byteOffset": 192, "byteLength": 24})
chunk = {
    "asset": {"version": "2.0"},
    "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "COLOR_0": 2, "_RADIOSITY": 3},
                                "indices": 4}]}],
    "accessors": [{"bufferView": i, "componentType": 5126, "count": 4, "type": "VEC3"} for i in range(4)] +
                 [{"bufferView": 4, "componentType": 5125, "count": 6, "type": "SCALAR"}],
    "bufferViews": views,
    "buffers": [{"byteLength": len(blob)}],
}
write("chunk", "quad-chunk.glb", glb(chunk, blob))

walk = {"format": "walkrad-walkthrough", "version": 1,
        "viewpoints": [{"name": "door", "position": [0.278, 0.273, -0.8], "target": [0.278, 0.273, 0],
                        "up": [0, 1, 0], "yfov_deg": 40, "aspect": 1.5},
                       {"position": [0, 1, 0], "direction": [0, 0, 1], "yfov_deg": 60}]}
write("walkthrough", "viewpoints.json", json.dumps(walk, indent=1))
path = {"format": "walkrad-walkthrough", "version": 1,
        "path": {"frames": 12, "yfov_deg": 50, "aspect": 1.25, "up": [0, 1, 0],
                 "keyframes": [{"time": 0, "position": [0, 1, 0], "target": [0, 1, 1]},
                               {"time": 1, "position": [1, 1, 0], "target": [1, 1, 1]},
                               {"time": 2.5, "position": [2, 1, 1], "target": [3, 1, 1]}]}}
write("walkthrough", "path.json", json.dumps(path, indent=1))

write("mgf", "primitives.mgf", """# every entity kind the reader knows, small
c red =
\tcxy 0.64 0.33
c warm =
\tcct 3000
c mix =
\tcmix 1 red 2 warm
c spec =
\tcspec 400 700 0.1 0.5 0.9 0.5
m white =
\tsides 2
\tc
\trd 0.7
m lamp =
\tc warm
\ted 100
\trd 0.1
m glossy =
\tc mix
\trd 0.4
\trs 0.1 0.05
\tts 0.1 0.05
\ttd 0.1
\tir 1.5 0
v a =
\tp 0 0 0
v b =
\tp 1 0 0
v c =
\tp 1 1 0
v d =
\tp 0 1 0
\tn 0 0 1
v h0 =
\tp 0.25 0.25 0
v h1 =
\tp 0.75 0.25 0
v h2 =
\tp 0.75 0.75 0
o things
m white
fh a b c d - h0 h1 h2
m lamp
xf -t 0 0 2 -rx 180 -a 2 -t 2 0 0
f a b c d
xf
m glossy
xf -s 0.5 -mz -i 2
sph a 0.3
cyl a 0.1 c
cone a 0.2 c 0.1
ring d 0 0.5
torus d 0.1 0.2
prism a b c 0.5
xf
o
ies somefile.ies
unknown entity here
""")
write("mgf", "bad-line.mgf", "v a =\n\tp 0 0 nan\nf a a a\n")

manifest = {"format": "walkrad-bake", "version": 1, "tool": "walkrad 0.1.0",
            "scene": {"file": "scene.gltf", "hash": "0123456789abcdef"},
            "bounds": {"min": [0, 0, 0], "max": [1, 1, 1]}, "exposure": 0.75,
            "chunks": [{"file": "chunk-0000.glb", "bounds": {"min": [0, 0, 0], "max": [1, 1, 1]},
                        "triangles": 2, "bytes": 1024}],
            "viewpoints": [{"name": "v", "position": [0, 0, 2], "forward": [0, 0, -1], "up": [0, 1, 0],
                            "yfov": 0.8, "aspect": 1.5}],
            "settings": {"method": "hierarchical", "error": 0.1}}
write("manifest", "manifest.json", json.dumps(manifest, indent=1))
