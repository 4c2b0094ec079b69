#!/usr/bin/env python3
"""`walkrad bake` on bad input: a distinct exit code, a message naming the file and the fault, and no
output folder (nor a leftover staging folder). Usage: test_bad_input.py WALKRAD SOURCE_DIR WORK_DIR"""
import json
import os
import shutil
import subprocess
import sys

walkrad, source, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
cornell = os.path.join(source, "examples/cornell-box/cornell-box.gltf")
failures = []


def expect(name, args, code, *parts):
    out = os.path.join(work, name + ".bake")
    r = subprocess.run([walkrad, "bake", *args, "-o", out, "--quiet"], capture_output=True, text=True)
    problems = []
    if r.returncode != code:
        problems.append(f"exit code {r.returncode}, expected {code}")
    for part in parts:
        if part not in r.stderr:
            problems.append(f"stderr lacks {part!r}")
    leftovers = [f for f in os.listdir(work) if f.endswith(".bake") or ".staging-" in f]
    if leftovers:
        problems.append(f"left output behind: {leftovers}")
    print(f"{'ok  ' if not problems else 'FAIL'} {name}: exit {r.returncode}: {r.stderr.strip()}")
    for p in problems:
        failures.append(f"{name}: {p}")


# A missing scene.
missing = os.path.join(work, "no-such-scene.gltf")
expect("missing-file", [missing], 3, missing, "cannot open")

# A truncated .glb: half of a valid one.
glb = os.path.join(work, "cornell.glb")
subprocess.run([sys.executable, os.path.join(source, "examples/cornell-box/make_cornell_box.py"), glb], check=True,
               capture_output=True)
with open(glb, "rb") as f:
    data = f.read()
truncated = os.path.join(work, "truncated.glb")
with open(truncated, "wb") as f:
    f.write(data[: len(data) // 2])
expect("truncated-glb", [truncated], 3, truncated, "invalid glTF")

# A walkthrough with a misspelt field.
views = os.path.join(work, "bad-views.json")
with open(views, "w") as f:
    json.dump({"format": "walkrad-walkthrough", "version": 1,
               "viewpoints": [{"position": [0.278, 0.273, -0.8], "target": [0.278, 0.273, 0], "fov": 40}]}, f)
expect("walkthrough-wrong-field", [cornell, "--views", views], 3, views, "/viewpoints/0/fov", "unknown field")

# A scene without any emitter.
dark = os.path.join(work, "dark.gltf")
with open(cornell) as f:
    doc = json.load(f)
for m in doc["materials"]:
    m.pop("emissiveFactor", None)
with open(dark, "w") as f:
    json.dump(doc, f)
expect("no-emitter", [dark], 3, dark, "no emitter")

# Bad arguments.
expect("bad-arguments", [cornell, "--rays", "0"], 2)

print(f"{5 - len(set(f.split(':')[0] for f in failures))} passed, {len(set(f.split(':')[0] for f in failures))} failed")
if failures:
    print("\n".join(failures))
    sys.exit(1)
