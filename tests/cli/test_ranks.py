#!/usr/bin/env python3
"""A bake over several ranks (walkrad/core/ranks.h): the Cornell box (defaults) and a 1-room
office-floor level (draft) baked with mpirun at 1, 2 and 3 ranks (one thread each) give chunks and a manifest byte-identical
to the plain bake's, with Gauss-Seidel (links on every rank) and with Jacobi sweeps (links divided among
the ranks, each holding fewer), report the ranks and the bytes they exchanged, and leave no scratch folder; rank 1
needs neither the scene nor the walkthrough (rank 0 sends what it read); a rank past --max-memory-mb
ends the bake with exit code 6; a scene
no rank can read ends every rank with the reader's exit code and writes nothing; ranks running different
builds are refused.
Usage: test_ranks.py WALKRAD SOURCE_DIR WORK_DIR"""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

walkrad, source, work = (os.path.abspath(a) for a in sys.argv[1:4])
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
mpirun = ["mpirun", "--oversubscribe", "--bind-to", "none"]
failures = []

office = os.path.join(work, "office")
subprocess.run([sys.executable, os.path.join(source, "examples/office-floor/make_office_floor.py"), "--rooms", "1",
                "--detail", "0.05", "--out", office], check=True, stdout=subprocess.DEVNULL)
# Its path sampled at 60 viewpoints, not 240: the same rooms looked at, a quarter of the chunk
# visibility rays (a CI budget; what is divided among ranks is the same).
path_file = os.path.join(office, "office-floor-1-walkthrough.json")
with open(path_file) as f:
    walk = json.load(f)
walk["path"]["frames"] = 60
with open(path_file, "w") as f:
    json.dump(walk, f)
# Each scene: (the folder the bakes run in, the arguments relative to it). The office level's 2-rank bake
# runs its rank 1 in an empty folder, where the scene's and the walkthrough's relative paths lead nowhere
# (another host): rank 0 reads the files and sends what it read.
scenes = {"cornell": (source, ["examples/cornell-box/cornell-box.gltf"]),
          # At the draft error: the same code as the default's, a seventh of its links (a CI budget).
          "office": (office, ["office-floor-1.glb", "--views", "office-floor-1-walkthrough.json", "--quality", "draft"])}
empty = os.path.join(work, "empty-host")
os.makedirs(empty)


def files(folder):
    return sorted(os.path.basename(p) for p in glob.glob(os.path.join(folder, "chunk-*.glb"))) + ["manifest.json"]


def same(a, b):
    return all(open(os.path.join(a, f), "rb").read() == open(os.path.join(b, f), "rb").read() for f in files(a)) and files(a) == files(b)


scratch_before = set(glob.glob(os.path.join(tempfile.gettempdir(), "walkrad-rank-*")))
for name, (folder, args) in scenes.items():
    plain = os.path.join(work, name + "-plain")
    subprocess.run([walkrad, "bake", *args, "-o", plain, "-q", "--threads", "1"], check=True, stdout=subprocess.DEVNULL,
                   cwd=folder)
    for n in (1, 2, 3):
        out = os.path.join(work, f"{name}-{n}")
        bake_args = [walkrad, "bake", *args, "-o", out, "-q", "--threads", "1"]
        elsewhere = name == "office" and n == 2
        command = mpirun + (["-np", "1", *bake_args, ":", "-np", "1", "-wdir", empty, *bake_args] if elsewhere
                            else ["-np", str(n), *bake_args])
        r = subprocess.run(command, capture_output=True, text=True, env=env, cwd=folder, timeout=600)
        if r.returncode != 0:
            failures.append(f"{name}, {n} ranks{' (rank 1 without the files)' if elsewhere else ''}: exit {r.returncode}: "
                            f"{r.stderr.strip()[-300:]}")
            continue
        report = json.load(open(os.path.join(out, "report.json")))
        counts, shares = report["counts"], report["ranks"]
        exchanged = shares["bytes_exchanged"]
        if shares["count"] != n or len(shares["per_rank"]) != n or not 1 <= shares["balance"] < 2 or \
                sum(r["items"] for r in shares["per_rank"]) == 0:
            failures.append(f"{name}, {n} ranks: report's ranks {shares}")
        # Every round reports what it exchanged (the link evaluation's all-gather: nothing with one rank).
        per_round = [r["bytes_exchanged"] for r in report["solver"]["rounds"]]
        if (n > 1) != (sum(per_round) > 0) or sum(per_round) > exchanged:
            failures.append(f"{name}, {n} ranks: rounds' bytes {per_round} against {exchanged} in all")
        # Each rank's links and rays add up to the bake's; each reports its own peak memory.
        per = shares["per_rank"]
        if sum(r["rays"] for r in per) != counts["visibility_rays"] or sum(r["links"] for r in per) < counts["links"] or \
                (n > 1 and min(r["links"] for r in per) == 0) or min(r["peak_memory_mb"] for r in per) <= 0:
            failures.append(f"{name}, {n} ranks: per-rank links, rays or memory do not add up: {per}, "
                            f"{counts['links']} links, {counts['visibility_rays']} rays")
        print(f"{name}, {n} ranks: {counts['links']} links, {exchanged} bytes exchanged")
        if not same(plain, out):
            failures.append(f"{name}, {n} ranks: the bake differs from one process's")
        if (n > 1) != (exchanged > 0):
            failures.append(f"{name}, {n} ranks: report says {exchanged} bytes exchanged")

# Links divided among ranks (walkrad/hierarchical/link_owners.h): with Jacobi sweeps each rank keeps
# only its receivers' links, to the end of the bake (the final gather and the vertices read them on
# their rank). The bakes at 1, 2 and 3 ranks are one process's with --solver jacobi, byte for byte; each
# rank holds fewer links than one process, the office level's ranks about as many each, and at 2 ranks
# its links' peak memory over the whole bake (a count of bytes, not a measurement: the same every run;
# noted in each round and after the mesh) is at most 0.65 of one process's (settling hidden links takes it above 0.6).
for name, (folder, args) in scenes.items():
    args = [*args, "--solver", "jacobi"]
    plain = os.path.join(work, name + "-jacobi-plain")
    subprocess.run([walkrad, "bake", *args, "-o", plain, "-q", "--threads", "1"], check=True, stdout=subprocess.DEVNULL,
                   cwd=folder)
    whole = json.load(open(os.path.join(plain, "report.json")))
    whole_mb, links = whole["solver"]["link_mb_peak"], whole["counts"]["links"]
    for n in (2, 3):
        out = os.path.join(work, f"{name}-jacobi-{n}")
        r = subprocess.run(mpirun + ["-np", str(n), walkrad, "bake", *args, "-o", out, "-q", "--threads", "1"],
                           capture_output=True, text=True, env=env, cwd=folder, timeout=600)
        if r.returncode != 0:
            failures.append(f"{name} (jacobi), {n} ranks: exit {r.returncode}: {r.stderr.strip()[-300:]}")
            continue
        report = json.load(open(os.path.join(out, "report.json")))
        per = report["ranks"]["per_rank"]
        held, peaks = [p["links_held"] for p in per], [p["link_mb_peak"] for p in per]
        print(f"{name} (jacobi), {n} ranks: links held {held} of {links}, link MiB at the peak {[round(p, 1) for p in peaks]} "
              f"against {whole_mb:.1f}")
        if not report["solver"]["links_divided"] or whole["solver"]["links_divided"]:
            failures.append(f"{name} (jacobi), {n} ranks: links_divided {report['solver']['links_divided']}")
        # Every link is held somewhere (cluster receivers' on every rank), no rank holds them all.
        if sum(held) < links or max(held) >= links or report["counts"]["links"] != links:
            failures.append(f"{name} (jacobi), {n} ranks: links held {held} against {links}")
        # The polygons are dealt again each round by their links (link_owners.h: rebalance_links): the
        # office level's many polygons fall within 10% of the mean (the Cornell box's 17 cannot).
        if name == "office" and max(held) > 1.1 * sum(held) / n:
            failures.append(f"{name} (jacobi), {n} ranks: links held {held}: not balanced")
        # Link memory, the largest rank's against one process's (each the capacity of the round's new-link
        # list plus the held lists, at its largest): 0.51 when hidden links were still refined; since they are
        # settled (Solver::settled_hidden) one process peaks at 27.5 MiB instead of 32.8 while the largest
        # rank's stays at 16.6 MiB: 0.60.
        if n == 2 and name == "office" and max(peaks) > 0.65 * whole_mb:
            failures.append(f"{name} (jacobi), 2 ranks: link memory {peaks} MiB against {whole_mb:.1f} for one process")
        if not same(plain, out):
            failures.append(f"{name} (jacobi), {n} ranks: the bake differs from one process's")

# The IES room (profiles, a spot light) with its rank 1 in the empty folder too.
folder, args = os.path.join(source, "examples/ies-room"), ["ies-room.gltf"]
plain, out = os.path.join(work, "ies-room-plain"), os.path.join(work, "ies-room-one-reader")
subprocess.run([walkrad, "bake", *args, "-o", plain, "-q", "--threads", "1"], check=True, stdout=subprocess.DEVNULL, cwd=folder)
bake_args = ["bake", *args, "-o", out, "-q", "--threads", "1"]
r = subprocess.run(mpirun + ["-np", "1", walkrad, *bake_args, ":", "-np", "1", "-wdir", empty, walkrad, *bake_args],
                   capture_output=True, text=True, env=env, cwd=folder, timeout=600)
ok = r.returncode == 0 and same(plain, out)
print(f"ies-room, rank 1 without the files: exit {r.returncode}, {'byte-identical' if ok else 'DIFFERS'}")
if not ok:
    failures.append(f"ies-room, rank 1 without the files: exit {r.returncode}: {r.stderr.strip()[-300:]}")
left = set(glob.glob(os.path.join(tempfile.gettempdir(), "walkrad-rank-*"))) - scratch_before
if left:
    failures.append("scratch folders left: " + ", ".join(sorted(left)))

# A scene no rank can read: every rank stops with the reader's exit code (2, bad input), nothing written.
missing = os.path.join(work, "missing")
r = subprocess.run(mpirun + ["-np", "2", walkrad, "bake", os.path.join(work, "no-such-scene.gltf"), "-o", missing, "-q"],
                   capture_output=True, text=True, env=env, timeout=120)
print(f"unreadable scene, 2 ranks: exit {r.returncode}")
if r.returncode == 0 or os.path.exists(missing):
    failures.append(f"an unreadable scene over 2 ranks: exit {r.returncode}, output {'written' if os.path.exists(missing) else 'absent'}")
if "no-such-scene.gltf" not in r.stderr:
    failures.append("the error does not name the scene: " + r.stderr.strip()[-300:])

# --max-memory-mb bounds each rank: over it, the bake ends with exit code 6 and a message, nothing written.
capped = os.path.join(work, "capped")
r = subprocess.run(mpirun + ["-np", "2", walkrad, "bake", *scenes["office"][1], "-o", capped, "-q", "--threads", "1",
                             "--max-memory-mb", "60"], capture_output=True, text=True, env=env, cwd=office, timeout=600)
print(f"memory cap, 2 ranks: exit {r.returncode}")
if r.returncode != 6 or os.path.exists(capped) or "past --max-memory-mb 60" not in r.stderr:
    failures.append(f"a memory cap over 2 ranks: exit {r.returncode}, output {os.path.exists(capped)}: {r.stderr.strip()[-300:]}")

# Ranks running different builds (a copy of walkrad whose version string is changed, started beside
# walkrad itself by mpirun's MPMD syntax): refused before any work, rank 0 naming both builds.
other = os.path.join(work, "walkrad-other-build")
binary = open(walkrad, "rb").read()
version = json.load(open(os.path.join(work, "cornell-plain", "manifest.json")))["tool"].split()[-1].encode()
changed = version[:-1] + (b"9" if version[-1:] != b"9" else b"8")
if binary.count(version + b"\0") != 1:
    failures.append(f"the version string {version} is not in {walkrad} once")
else:
    open(other, "wb").write(binary.replace(version + b"\0", changed + b"\0"))
    os.chmod(other, 0o755)
    mixed = os.path.join(work, "mixed")
    args = ["bake", os.path.join(source, scenes["cornell"][1][0]), "-o", mixed, "-q", "--threads", "1"]
    r = subprocess.run(mpirun + ["-np", "1", walkrad, *args, ":", "-np", "1", other, *args], capture_output=True, text=True,
                       env=env, timeout=120)
    print(f"two builds, 2 ranks: exit {r.returncode}")
    if r.returncode != 2 or os.path.exists(mixed) or "rank 1 runs another build" not in r.stderr or \
            changed.decode() not in r.stderr:
        failures.append(f"two builds over 2 ranks: exit {r.returncode}, output {os.path.exists(mixed)}: {r.stderr.strip()[-400:]}")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
