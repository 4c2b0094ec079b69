#!/usr/bin/env python3
"""`walkrad bake` on bad input: a distinct exit code, a message naming the file and the fault, and no
output folder (nor a leftover staging folder); a cap reached leaves a previous output as it was; `walkrad-view`
refuses a manifest that names a file outside its folder. Usage:
test_bad_input.py WALKRAD SOURCE_DIR WORK_DIR [WALKRAD_VIEW]"""
import base64
import hashlib
import json
import os
import shutil
import struct
import subprocess
import sys

walkrad, source, work = sys.argv[1:4]
walkrad_view = sys.argv[4] if len(sys.argv) > 4 else None
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
cornell = os.path.join(source, "examples/cornell-box/cornell-box.gltf")
failures = []
cases = []


def expect(name, args, code, *parts):
    out = os.path.join(work, name + ".bake")
    run_case(name, [walkrad, "bake", *args, "-o", out, "--quiet"], code, parts)


def run_case(name, command, code, parts):
    cases.append(name)
    r = subprocess.run(command, capture_output=True, text=True, timeout=300)
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
expect("truncated-glb", [truncated], 3, truncated, "GLB header", "differs from the file size")

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
expect("southwell-hierarchical", [cornell, "--solver", "southwell"], 2, "--solver", "classic method")
expect("hemicube-hierarchical", [cornell, "--form-factors", "hemicube"], 2, "--form-factors", "classic method")
expect("gather-classic", [cornell, "--method", "classic", "--effect", "gather=on"], 2, "--effect", "hierarchical")
expect("discontinuities-without-gather", [cornell, "--effect", "gather=off", "--effect", "discontinuities=on"], 2,
       "--effect", "discontinuities", "final gather")

# A buffer outside the scene's folder: refused (the bytes could be any file's), naming the flag that admits
# a wider folder; a folder that does not exist is a bad argument.
with open(cornell) as f:
    doc = json.load(f)
payload = base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1])
with open(os.path.join(work, "outside.bin"), "wb") as f:
    f.write(payload)
doc["buffers"][0]["uri"] = "../outside.bin"
os.makedirs(os.path.join(work, "scene"))
escaping = os.path.join(work, "scene", "escaping.gltf")
with open(escaping, "w") as f:
    json.dump(doc, f)
expect("buffer-outside-folder", [escaping], 3, escaping, "outside.bin", "lies outside the input folder", "--input-folder")
expect("input-folder-missing", [cornell, "--input-folder", os.path.join(work, "no-such-folder")], 2, "--input-folder")

# A .glb whose header claims 4 GB: refused at once, naming the header.
lying = os.path.join(work, "lying.glb")
with open(lying, "wb") as f:
    f.write(data[:8] + struct.pack("<I", 0xFFFFFFF0) + data[12:20])
expect("lying-glb", [lying], 3, lying, "GLB header", "differs from the file size 20")

# Walkthroughs: NaN is not JSON; a path of 10^9 frames is a limit.
nan_views = os.path.join(work, "nan-views.json")
with open(nan_views, "w") as f:
    f.write('{"format": "walkrad-walkthrough", "version": 1, "viewpoints": [{"position": [NaN, 0, 0], '
            '"target": [0, 0, 1], "yfov_deg": 40}]}')
expect("walkthrough-nan", [cornell, "--views", nan_views], 3, nan_views, "not valid JSON")
long_path = os.path.join(work, "long-path.json")
with open(long_path, "w") as f:
    json.dump({"format": "walkrad-walkthrough", "version": 1,
               "path": {"frames": 10 ** 9, "yfov_deg": 40,
                        "keyframes": [{"time": 0, "position": [0.278, 0.273, -0.8], "target": [0.278, 0.273, 0]},
                                      {"time": 10, "position": [0.3, 0.273, -0.8], "target": [0.278, 0.273, 0]}]}}, f)
expect("walkthrough-huge-path", [cornell, "--views", long_path], 6, long_path, "/path/frames", "exceeds the limit")


def with_extra_triangle(name, corners, material=None):
    """The Cornell box plus one more triangle (its own buffer), optionally with its own material."""
    d = json.loads(json.dumps(doc_original))
    blob = struct.pack("<9f", *[c for v in corners for c in v])
    d["buffers"].append({"byteLength": len(blob),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()})
    d["bufferViews"].append({"buffer": len(d["buffers"]) - 1, "byteLength": len(blob)})
    d["accessors"].append({"bufferView": len(d["bufferViews"]) - 1, "componentType": 5126, "count": 3, "type": "VEC3"})
    prim = {"attributes": {"POSITION": len(d["accessors"]) - 1}}
    if material is not None:
        d["materials"].append(material)
        prim["material"] = len(d["materials"]) - 1
    d["meshes"].append({"primitives": [prim]})
    d["nodes"].append({"mesh": len(d["meshes"]) - 1})
    d["scenes"][d.get("scene", 0)]["nodes"].append(len(d["nodes"]) - 1)
    path = os.path.join(work, name + ".gltf")
    with open(path, "w") as f:
        json.dump(d, f)
    return path, len(d["accessors"]) - 1, len(d["materials"]) - 1


with open(cornell) as f:
    doc_original = json.load(f)
# Non-finite coordinates and reflectance outside [0, 1]: exit 3 naming the accessor or the material.
nan_scene, accessor, _ = with_extra_triangle("nan-vertex", [(0.1, 0.1, 0.1), (float("nan"), 0.2, 0.1), (0.1, 0.2, 0.2)])
expect("nan-vertex", [nan_scene], 3, nan_scene, f"accessors[{accessor}] (POSITION)", "vertex 1 is not finite")
bright, _, mat = with_extra_triangle("bright", [(0.1, 0.1, 0.1), (0.2, 0.1, 0.1), (0.1, 0.2, 0.1)],
                                     {"pbrMetallicRoughness": {"baseColorFactor": [1.2, 0.5, 0.5, 1]}})
expect("reflectance-above-1", [bright], 3, bright, f"materials[{mat}]", "baseColorFactor must lie in [0, 1]")
bad_mgf = os.path.join(work, "bad.mgf")
with open(bad_mgf, "w") as f:
    f.write("m lamp =\n\ted -3\n")
expect("mgf-negative-emission", [bad_mgf], 3, bad_mgf, "line 2", "emittance must not be negative")

# `walkrad web`: a folder that is no bake, and a viewer folder without a built viewer (exit 3, naming it).
not_a_bake = os.path.join(work, "not-a-bake")
os.makedirs(not_a_bake, exist_ok=True)
run_case("web-not-a-bake", [walkrad, "web", not_a_bake], 3, [not_a_bake, "no manifest.json"])
run_case("web-no-viewer", [walkrad, "web", not_a_bake, "--viewer", os.path.join(work, "no-viewer")], 3,
         [os.path.join(work, "no-viewer"), "no built web viewer here"])
shutil.rmtree(not_a_bake)

# A zero-area triangle (a repeated vertex): a warning naming the file and the count; the rest is baked.
flat, _, _ = with_extra_triangle("flat", [(0.1, 0.1, 0.1), (0.2, 0.1, 0.1), (0.2, 0.1, 0.1)])
flat_out = os.path.join(work, "flat-ok")
cases.append("degenerate-dropped")
r = subprocess.run([walkrad, "bake", flat, "-o", flat_out, "--quiet", "--quality", "draft"], capture_output=True, text=True)
ok = r.returncode == 0 and f"warning: {flat}: 1 zero-area triangles dropped" in r.stderr and \
    os.path.isfile(os.path.join(flat_out, "manifest.json"))
print(f"{'ok  ' if ok else 'FAIL'} degenerate-dropped: exit {r.returncode}: {r.stderr.strip()}")
if not ok:
    failures.append("degenerate-dropped: expected exit 0, the warning and a bake")

# A cap reached: exit 6, and the previous output is left byte for byte.
previous = flat_out


def digest(folder):
    return {n: hashlib.sha256(open(os.path.join(folder, n), "rb").read()).hexdigest() for n in sorted(os.listdir(folder))}


before = digest(previous)
for name, cap in (("max-seconds", ["--max-seconds", "0.05"]), ("max-memory", ["--max-memory-mb", "1"])):
    cases.append(name)
    r = subprocess.run([walkrad, "bake", cornell, "-o", previous, "--quiet", *cap], capture_output=True, text=True)
    problems = []
    if r.returncode != 6:
        problems.append(f"exit code {r.returncode}, expected 6")
    if cornell not in r.stderr or "no output written" not in r.stderr:
        problems.append("stderr does not name the scene and say nothing was written")
    if digest(previous) != before:
        problems.append("the previous output changed")
    if [f for f in os.listdir(work) if ".staging-" in f]:
        problems.append("a staging folder was left behind")
    print(f"{'ok  ' if not problems else 'FAIL'} {name}: exit {r.returncode}: {r.stderr.strip()}")
    failures += [f"{name}: {p}" for p in problems]

# A bake that asks for more than the memory cap allows stops before or within the round that would
# pass it: exit 6, a message naming the setting, nothing written, and its peak memory near the cap
# (the Cornell box at --error 0.001 grows to gigabytes).
cases.append("memory-predicted")
capped = os.path.join(work, "capped-bake")
err_path = os.path.join(work, "capped-bake.stderr")
with open(err_path, "w") as err_file:
    p = subprocess.Popen([walkrad, "bake", cornell, "-o", capped, "--quiet", "--error", "0.001", "--max-memory-mb", "300",
                          "--threads", "2"], stdout=subprocess.DEVNULL, stderr=err_file)
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
err = open(err_path).read()
peak_mib = usage.ru_maxrss / 1024
problems = []
if p.returncode != 6:
    problems.append(f"exit code {p.returncode}, expected 6")
if "--max-memory-mb 300" not in err or "no output written" not in err:
    problems.append("stderr does not name --max-memory-mb and say nothing was written")
if os.path.exists(capped):
    problems.append("an output folder was written")
# Under AddressSanitizer the process keeps up to 256 MiB of freed blocks in quarantine and pads every
# allocation with red zones: memory the bake neither sees nor predicts, so the peak says nothing there.
if peak_mib > 300 * 1.25 and not os.environ.get("WALKRAD_SANITIZED"):
    problems.append(f"peak memory {peak_mib:.0f} MiB, more than a quarter past the cap")
print(f"{'ok  ' if not problems else 'FAIL'} memory-predicted: exit {p.returncode}, peak {peak_mib:.0f} MiB: {err.strip()}")
failures += [f"memory-predicted: {p}" for p in problems]

# The runtime refuses a manifest naming a chunk outside its folder, before opening anything.
if walkrad_view:
    escape = os.path.join(work, "escape-bake")
    os.makedirs(escape)
    with open(os.path.join(previous, "manifest.json")) as f:
        manifest = json.load(f)
    manifest["chunks"][0]["file"] = "../../etc/passwd"
    with open(os.path.join(escape, "manifest.json"), "w") as f:
        json.dump(manifest, f)
    run_case("manifest-outside-folder", [walkrad_view, escape, "--frames", os.path.join(work, "escape-frames")], 3,
             [os.path.join(escape, "manifest.json"), "/chunks/0/file", "plain file name"])
    shutil.rmtree(escape)
shutil.rmtree(previous)

failed = set(f.split(":")[0] for f in failures)
print(f"{len(cases) - len(failed)} passed, {len(failed)} failed")
if failures:
    print("\n".join(failures))
    sys.exit(1)
