#!/usr/bin/env python3
"""A bake killed midway (SIGKILL: no chance to clean up) leaves the previous output intact and readable;
the next bake clears the dead bake's staging folder. Usage: test_interrupt.py WALKRAD SOURCE_DIR WORK_DIR"""
import glob
import os
import shutil
import signal
import subprocess
import sys
import time

walkrad, source, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
scene = os.path.join(source, "examples/cornell-box/cornell-box.gltf")
out = os.path.join(work, "cornell.bake")
quick = [walkrad, "bake", scene, "-o", out, "-q", "--quality", "draft"]
subprocess.run(quick, check=True, stdout=subprocess.DEVNULL)
before = {p: open(p, "rb").read() for p in glob.glob(os.path.join(out, "*"))}

# A long bake into the same folder, killed once it is solving (its staging folder exists).
slow = subprocess.Popen([walkrad, "bake", scene, "-o", out, "-q", "--error", "0.001"], stdout=subprocess.DEVNULL)
staging = os.path.join(work, f".cornell.bake.staging-{slow.pid}")
deadline = time.monotonic() + 60
while not os.path.isdir(staging) and time.monotonic() < deadline and slow.poll() is None:
    time.sleep(0.05)
time.sleep(1.0)
failures = []
if slow.poll() is not None:
    failures.append(f"the long bake ended by itself (exit {slow.returncode}) before it could be killed")
slow.send_signal(signal.SIGKILL)
slow.wait()

after = {p: open(p, "rb").read() for p in glob.glob(os.path.join(out, "*"))}
if after != before:
    failures.append("the previous output changed: " + ", ".join(sorted(set(before) ^ set(after))) or "contents differ")
r = subprocess.run([walkrad, "inspect", out], capture_output=True, text=True)
if r.returncode != 0:
    failures.append(f"the previous output is not readable: {r.stderr.strip()}")

subprocess.run(quick, check=True, stdout=subprocess.DEVNULL)  # the next bake sweeps the dead one's folder
left = glob.glob(os.path.join(work, ".cornell.bake.staging-*"))
if left:
    failures.append("staging folders left after the next bake: " + ", ".join(left))

for f in failures:
    print("FAIL:", f)
print("killed bake: previous output intact" if not failures else "")
sys.exit(1 if failures else 0)
