#!/usr/bin/env python3
"""The example consuming project (examples/consumer) bakes its level through walkrad_add_bake, and
re-bakes only when it should: after touching the scene, a file the scene refers to (an IES profile, known
from the bake's depfile) or changing a setting; not after touching an unrelated source file or a file
beside the scene that it does not use, not on a plain rebuild. With Ninja and with Makefiles.
Usage: test_consumer.py WALKRAD SOURCE_DIR WORK_DIR"""
import os
import shutil
import subprocess
import sys
import time

walkrad, source, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
project = os.path.join(work, "consumer")
shutil.copytree(os.path.join(source, "examples/consumer"), project)
# A copy of a scene that refers to two IES profiles, so the test can touch them.
level = os.path.join(work, "level")
shutil.copytree(os.path.join(source, "examples/ies-room"), level)
scene = os.path.join(level, "ies-room.gltf")
profile = os.path.join(level, "downlight.ies")
unused = os.path.join(level, "make_ies_room.py")


def run(*args):
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        sys.exit(f"FAIL: {' '.join(args)} exited {r.returncode}")
    return r.stdout


def build_and_report(build):
    out = run("cmake", "--build", build)
    return "walkrad: baking" in out


failures = []
for generator in ("Ninja", "Unix Makefiles"):
    build = os.path.join(work, "build-" + generator.split()[-1].lower())
    manifest = os.path.join(build, "level.bake/manifest.json")

    def check(rebakes, what):
        if build_and_report(build) != rebakes:
            failures.append(f"{generator}: {what}")

    run("cmake", "-S", project, "-B", build, "-G", generator, f"-DWALKRAD_EXECUTABLE={walkrad}", f"-DLEVEL_SCENE={scene}",
        f"-DWALKRAD_SOURCE_DIR={source}")
    check(True, "the first build did not bake")
    if not os.path.exists(manifest):
        failures.append(f"{generator}: the first build wrote no manifest")
    check(False, "a rebuild with nothing changed baked again")
    time.sleep(1.1)  # time stamps: make the touches below newer than the outputs
    os.utime(os.path.join(project, "main.cpp"))
    check(False, "touching an unrelated source file re-baked")
    os.utime(unused)
    check(False, "touching a file beside the scene that it does not use re-baked")
    os.utime(scene)
    check(True, "touching the scene did not re-bake")
    time.sleep(1.1)
    os.utime(profile)
    check(True, "touching an IES profile the scene refers to did not re-bake")
    check(False, "a rebuild after the profile's re-bake baked again")
    run("cmake", "-S", project, "-B", build, "-DLEVEL_QUALITY=medium")
    check(True, "changing a setting did not re-bake")
    run("cmake", "-S", project, "-B", build)  # configure again, same settings
    check(False, "re-configuring with the same settings re-baked")
for f in failures:
    print("FAIL:", f)
if not failures:
    print("consumer: bakes once, again after touching the scene, a profile it uses or a setting, not otherwise (Ninja, Makefiles)")
sys.exit(1 if failures else 0)
