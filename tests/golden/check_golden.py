#!/usr/bin/env python3
"""Golden-file test: the Cornell box baked with fixed settings agrees with the committed bake in
tests/golden/cornell-box (walkrad diff, relative radiosity tolerance 1e-3), and diff does notice a bake
made with other settings. WALKRAD_UPDATE_GOLDEN=1 rewrites the golden bake instead (review the change,
then commit it). Usage: check_golden.py WALKRAD SOURCE_DIR WORK_DIR"""
import glob
import os
import shutil
import subprocess
import sys

walkrad, source, work = sys.argv[1:4]
golden = os.path.join(source, "tests/golden/cornell-box")
settings = ["--quality", "draft", "--threads", "2"]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
fresh = os.path.join(work, "cornell-box")
# Run from the source folder so that the manifest names the scene by a relative path.
subprocess.run([walkrad, "bake", "examples/cornell-box/cornell-box.gltf", "-o", fresh, "-q", *settings], cwd=source,
               check=True, stdout=subprocess.DEVNULL)

if os.environ.get("WALKRAD_UPDATE_GOLDEN") == "1":
    shutil.rmtree(golden, ignore_errors=True)
    os.makedirs(golden)
    for f in ["manifest.json", *[os.path.basename(p) for p in glob.glob(os.path.join(fresh, "chunk-*.glb"))]]:
        shutil.copy(os.path.join(fresh, f), golden)
    print(f"updated {golden}: review with `git diff --stat`, then commit")
    sys.exit(0)

r = subprocess.run([walkrad, "diff", golden, fresh, "--tolerance", "1e-3"], capture_output=True, text=True)
print(r.stdout, end="")
if r.returncode != 0:
    print(f"FAIL: the bake differs from the golden one (exit {r.returncode}); if the change is intended, rerun with "
          "WALKRAD_UPDATE_GOLDEN=1 and commit tests/golden")
    sys.exit(1)

# diff must be able to fail: a finer bake differs.
other = os.path.join(work, "cornell-box-finer")
subprocess.run([walkrad, "bake", "examples/cornell-box/cornell-box.gltf", "-o", other, "-q", "--quality", "medium"],
               cwd=source, check=True, stdout=subprocess.DEVNULL)
r = subprocess.run([walkrad, "diff", golden, other], capture_output=True, text=True)
if r.returncode != 7:
    print(f"FAIL: diff of a bake of another quality returned {r.returncode}, expected 7 (another quality):\n{r.stdout}")
    sys.exit(1)
print("golden: same within tolerance; a bake of another quality differs (exit 7)")
