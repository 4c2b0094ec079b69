#!/usr/bin/env python3
"""Checkpoints of the solve (--checkpoint DIR and --resume; pipeline/bake/src/checkpoint_file.h):
the Cornell box's default bake, killed (SIGKILL) right after its 3rd or 5th refinement round, resumed in
one process or over 2 ranks, or stopped by --max-seconds and resumed, gives chunks and a manifest
byte-identical to a bake that ran through (with --solver jacobi too, killed over 2 ranks); a bake with --checkpoint is itself unchanged and removes its
checkpoint once written; a checkpoint from another build, scene or setting, or a damaged one, is refused
with exit code 3, naming the file and the difference, and nothing is written.
Usage: test_checkpoint.py WALKRAD SOURCE_DIR WORK_DIR"""
import json
import os
import shutil
import subprocess
import sys

walkrad, source, work = (os.path.abspath(a) for a in sys.argv[1:4])
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
mpirun = ["mpirun", "--oversubscribe", "--bind-to", "none", "-np", "2"]
scene = os.path.join(source, "examples/cornell-box/cornell-box.gltf")
failures = []


def bake(out, *extra, ranks=1, kill_after=None, scene_file=scene):
    cmd = [walkrad, "bake", scene_file, "-o", out, "-q", "--threads", "2" if ranks == 1 else "1", *extra]
    run_env = dict(env, WALKRAD_TEST_KILL_AFTER_ROUND=str(kill_after)) if kill_after else env
    return subprocess.run((mpirun if ranks > 1 else []) + cmd, capture_output=True, text=True, env=run_env, timeout=600)


def files(folder):
    return sorted(f for f in os.listdir(folder) if f.endswith(".glb")) + ["manifest.json"]


def same(a, b):
    return files(a) == files(b) and all(open(os.path.join(a, f), "rb").read() == open(os.path.join(b, f), "rb").read()
                                        for f in files(a))


plain = os.path.join(work, "plain")
if bake(plain).returncode != 0:
    sys.exit("FAIL: the plain bake failed")


def round_seconds(out):
    report = json.load(open(os.path.join(out, "report.json")))
    solve = sum(p["seconds"] for p in report["phases"] if p["name"] == "solve")
    return [r["seconds"] for r in report["solver"]["rounds"]], solve


# Each round's wall time in report.json: positive, within the solve phase's.
seconds, solve = round_seconds(plain)
if not seconds or any(t is None or t <= 0 for t in seconds) or sum(seconds) > solve + 1e-3:
    failures.append(f"report.json's round seconds {seconds} against a solve of {solve} s")

# Checkpointing alone changes nothing, and the checkpoint goes once the bake is written.
through, cp = os.path.join(work, "through"), os.path.join(work, "cp-through")
r = bake(through, "--checkpoint", cp)
if r.returncode != 0 or not same(plain, through) or os.path.exists(os.path.join(cp, "solve.checkpoint")):
    failures.append(f"a bake with --checkpoint: exit {r.returncode}, same {r.returncode == 0 and same(plain, through)}, "
                    f"checkpoint left {os.path.exists(os.path.join(cp, 'solve.checkpoint'))}")

# Killed, then resumed: (kill in, after round, resume in).
for kill_ranks, round_, resume_ranks in ((1, 3, 1), (2, 3, 1), (1, 5, 2)):
    name = f"killed-{kill_ranks}-{round_}-{resume_ranks}"
    out, cp = os.path.join(work, name), os.path.join(work, "cp-" + name)
    r = bake(out, "--checkpoint", cp, ranks=kill_ranks, kill_after=round_)
    if r.returncode == 0 or os.path.exists(out) or not os.path.exists(os.path.join(cp, "solve.checkpoint")):
        failures.append(f"{name}: the killed bake: exit {r.returncode}, output {os.path.exists(out)}")
        continue
    if round_ == 3:
        shutil.copy(os.path.join(cp, "solve.checkpoint"), os.path.join(work, "round-3.checkpoint"))
    r = bake(out, "--checkpoint", cp, "--resume", ranks=resume_ranks)
    ok = r.returncode == 0 and same(plain, out)
    resumed = json.load(open(os.path.join(out, "report.json")))["solver"]["resumed_after_round"] if r.returncode == 0 else None
    print(f"{name}: killed after round {round_} ({kill_ranks} rank(s)), resumed ({resume_ranks}) after round {resumed}: "
          f"{'byte-identical' if ok else 'DIFFERS'}")
    if not ok or resumed != round_ or os.path.exists(os.path.join(cp, "solve.checkpoint")):
        failures.append(f"{name}: resumed: exit {r.returncode}, same {ok}, resumed after {resumed}: {r.stderr.strip()[-300:]}")
    else:  # the rounds read back have no time of this process; the rest have theirs
        seconds, _ = round_seconds(out)
        if any(t is not None for t in seconds[:round_]) or any(t is None or t <= 0 for t in seconds[round_:]):
            failures.append(f"{name}: resumed: round seconds {seconds}")

# With --solver jacobi a bake over several ranks divides its links, but not under --checkpoint (the file
# holds every link): killed over 2 ranks after round 3 and resumed in one process, it is still the Jacobi
# bake of one process, which the divided one is too (test_ranks.py).
jacobi_plain, out, cp = (os.path.join(work, n) for n in ("jacobi-plain", "jacobi-killed", "cp-jacobi"))
r0 = bake(jacobi_plain, "--solver", "jacobi")
r1 = bake(out, "--solver", "jacobi", "--checkpoint", cp, ranks=2, kill_after=3)
r2 = bake(out, "--solver", "jacobi", "--checkpoint", cp, "--resume")
ok = r0.returncode == 0 and r1.returncode != 0 and r2.returncode == 0 and same(jacobi_plain, out)
print(f"jacobi, killed over 2 ranks after round 3, resumed in one process: {'byte-identical' if ok else 'DIFFERS'}")
if not ok:
    failures.append(f"jacobi killed and resumed: exits {r0.returncode}, {r1.returncode}, {r2.returncode}: {r2.stderr.strip()[-300:]}")

# A bake stopped by its own time cap (exit 6, between rounds) goes on with --resume from the last round
# it saved (none if it stopped before one: the same bake either way).
out, cp = os.path.join(work, "capped"), os.path.join(work, "cp-capped")
r = bake(out, "--checkpoint", cp, "--max-seconds", "0.5")
saved_round = os.path.exists(os.path.join(cp, "solve.checkpoint"))
r2 = bake(out, "--checkpoint", cp, "--resume")
print(f"stopped by --max-seconds 0.5: exit {r.returncode}, a checkpoint {'left' if saved_round else 'not yet written'}; "
      f"resumed: exit {r2.returncode}, {'byte-identical' if r2.returncode == 0 and same(plain, out) else 'DIFFERS'}")
if r.returncode != 6 or r2.returncode != 0 or not same(plain, out):
    failures.append(f"--max-seconds then --resume: exit {r.returncode} then {r2.returncode}: {r2.stderr.strip()[-300:]}")

# --resume with an empty folder starts from the beginning.
out = os.path.join(work, "fresh")
r = bake(out, "--checkpoint", os.path.join(work, "cp-empty"), "--resume")
if r.returncode != 0 or not same(plain, out):
    failures.append(f"--resume without a checkpoint: exit {r.returncode}")


def refused(name, expect, *extra, checkpoint_bytes=None, scene_file=scene):
    cp, out = os.path.join(work, "cp-" + name), os.path.join(work, name)
    os.makedirs(cp, exist_ok=True)
    path = os.path.join(cp, "solve.checkpoint")
    open(path, "wb").write(checkpoint_bytes)
    r = bake(out, "--checkpoint", cp, "--resume", *extra, scene_file=scene_file)
    print(f"{name}: exit {r.returncode}: {r.stderr.strip()}")
    if r.returncode != 3 or path not in r.stderr or expect not in r.stderr or os.path.exists(out) or not os.path.exists(path):
        failures.append(f"{name}: exit {r.returncode}, output {os.path.exists(out)}: {r.stderr.strip()[-300:]}")


saved = open(os.path.join(work, "round-3.checkpoint"), "rb").read()
refused("other-setting", "other settings: error", "--error", "0.05", checkpoint_bytes=saved)
other_scene = os.path.join(work, "cornell-copy.gltf")
open(other_scene, "w").write(open(scene).read() + "\n")  # the same scene, other bytes: its hash differs
refused("other-scene", "another scene", checkpoint_bytes=saved, scene_file=other_scene)
at = saved.index(b"executable ") + len(b"executable ")
refused("other-build", "resumes only in the build that wrote it", checkpoint_bytes=saved[:at] + b"0" * 16 + saved[at + 16:])
refused("truncated", "damaged checkpoint", checkpoint_bytes=saved[:len(saved) // 2])
flipped = bytearray(saved)
flipped[-1000] ^= 1
refused("flipped-bit", "damaged checkpoint", checkpoint_bytes=bytes(flipped))

# A folder that cannot be made (its parent is a file): exit 5 before the solve, nothing written.
out = os.path.join(work, "nowhere")
r = bake(out, "--checkpoint", os.path.join(plain, "manifest.json", "cp"))
if r.returncode != 5 or os.path.exists(out) or "cannot write checkpoints there" not in r.stderr:
    failures.append(f"an unwritable --checkpoint folder: exit {r.returncode}: {r.stderr.strip()[-300:]}")

# Wrong use: --resume needs --checkpoint; the classic method has no rounds to save.
for args in (["--resume"], ["--checkpoint", os.path.join(work, "cp-classic"), "--method", "classic"]):
    r = bake(os.path.join(work, "misuse"), *args)
    if r.returncode != 2:
        failures.append(f"{' '.join(args)}: exit {r.returncode} (expected 2)")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
