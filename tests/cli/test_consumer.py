#!/usr/bin/env python3
"""The example consuming project (examples/consumer) bakes its level through walkrad_add_bake, and
re-bakes only when it should: after touching the scene or changing a setting, not after touching an
unrelated source file, not on a plain rebuild. Usage: test_consumer.py WALKRAD SOURCE_DIR WORK_DIR"""
import os
import shutil
import subprocess
import sys
import time

walkrad, source, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
project = os.path.join(work, "consumer")
shutil.copytree(os.path.join(source, "examples/consumer"), project)
scene = os.path.join(work, "level.gltf")  # a copy, so the test can touch it
shutil.copy(os.path.join(source, "examples/cornell-box/cornell-box.gltf"), scene)
build = os.path.join(work, "build")


def run(*args):
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        sys.exit(f"FAIL: {' '.join(args)} exited {r.returncode}")
    return r.stdout


def build_and_report():
    out = run("cmake", "--build", build)
    return "walkrad: baking" in out


manifest = os.path.join(build, "level.bake/manifest.json")
failures = []
run("cmake", "-S", project, "-B", build, "-G", "Ninja", f"-DWALKRAD_EXECUTABLE={walkrad}", f"-DLEVEL_SCENE={scene}", f"-DWALKRAD_SOURCE_DIR={source}")
if not build_and_report() or not os.path.exists(manifest):
    failures.append("the first build did not bake")
if build_and_report():
    failures.append("a rebuild with nothing changed baked again")
time.sleep(1.1)  # time stamps: make the touches below newer than the outputs
os.utime(os.path.join(project, "main.cpp"))
if build_and_report():
    failures.append("touching an unrelated source file re-baked")
os.utime(scene)
if not build_and_report():
    failures.append("touching the scene did not re-bake")
run("cmake", "-S", project, "-B", build, "-DLEVEL_QUALITY=medium")
if not build_and_report():
    failures.append("changing a setting did not re-bake")
run("cmake", "-S", project, "-B", build)  # configure again, same settings
if build_and_report():
    failures.append("re-configuring with the same settings re-baked")
for f in failures:
    print("FAIL:", f)
if not failures:
    print("consumer: bakes once, again after touching the scene or a setting, not otherwise")
sys.exit(1 if failures else 0)
