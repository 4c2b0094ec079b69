#!/usr/bin/env python3
"""A/B timing of walkrad builds on one bake: runs `walkrad bake SCENE ARGS...` with each binary in turn,
ROUNDS times (A, B, A, B, ...: the shared machine's drift falls on both alike), and prints each run, the
medians of wall and user CPU time, each binary's median over the first's, and whether every binary
wrote the same bake (the folders byte for byte, less report.json, which holds times).

With --pinned (two binaries): each round runs both at once, one thread each, each pinned to its own core
(taskset), the cores swapped every round; the ratio is taken per core. On the shared 2-core machine one
core ran 20-35% slower than the other for either binary, so runs one after another compare cores as much
as builds; pinned pairs compare like with like.

Usage: bench/ab_bake.py --rounds 3 --bin A=/tmp/walkrad-old --bin B=build/pipeline/walkrad \\
           -- ../shared/scenes/mgf/office3/office.mgf --threads 2
       bench/ab_bake.py --pinned --rounds 2 --bin A=/tmp/walkrad-old --bin B=build/pipeline/walkrad -- SCENE
Keep a copy of the old binary before rebuilding (cp build/pipeline/walkrad /tmp/walkrad-old)."""
import argparse
import filecmp
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time


def same_tree(a, b):
    """True when the two folders hold the same files with the same bytes (report.json aside)."""
    cmp = filecmp.dircmp(a, b, ignore=["report.json"])
    stack = [cmp]
    while stack:
        c = stack.pop()
        if c.left_only or c.right_only or c.funny_files:
            return False
        _, mismatch, errors = filecmp.cmpfiles(c.left, c.right, c.common_files, shallow=False)
        if mismatch or errors:
            return False
        stack.extend(c.subdirs.values())
    return True


def pinned(bins, args, rounds, work):
    """Both binaries at once, one thread each, pinned to cores 0 and 1, swapped every round."""
    per_core = {}  # core -> name -> [user seconds]
    for r in range(rounds):
        procs = []
        for k, (name, path) in enumerate(bins):
            core = (k + r) % 2
            out = os.path.join(work, f"{name}-{r}.bake")
            procs.append((name, core, subprocess.Popen(["taskset", "-c", str(core), path, "bake", *args, "-o", out, "-q",
                                                        "--threads", "1"], stdout=subprocess.DEVNULL,
                                                       stderr=subprocess.PIPE, text=True)))
        for name, core, proc in procs:
            _, status, usage = os.wait4(proc.pid, 0)
            if os.waitstatus_to_exitcode(status) != 0:
                sys.exit(f"{name} failed (exit {os.waitstatus_to_exitcode(status)}): {proc.stderr.read().strip()[-400:]}")
            per_core.setdefault(core, {}).setdefault(name, []).append(usage.ru_utime)
            print(f"round {r + 1} {name} on core {core}: {usage.ru_utime:.2f} s user", flush=True)
    (first, _), (second, _) = bins
    print(f"\n| core | {first} user (s) | {second} user (s) | {second} / {first} |")
    print("| ---: | ---: | ---: | ---: |")
    for core in sorted(per_core):
        t = per_core[core]
        if first in t and second in t:
            u1, u2 = statistics.median(t[first]), statistics.median(t[second])
            print(f"| {core} | {u1:.2f} | {u2:.2f} | {u2 / u1:.3f} |")
    identical = all(same_tree(os.path.join(work, f"{first}-0.bake"), os.path.join(work, f"{n}-{r}.bake"))
                    for n, _ in bins for r in range(rounds))
    print(f"\nbakes byte-identical (less report.json): {'yes' if identical else 'NO'}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", action="append", required=True, help="NAME=PATH of a walkrad binary (two or more)")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--pinned", action="store_true", help="two binaries at once, one thread each, pinned to cores 0 and 1, swapped each round")
    ap.add_argument("bake_args", nargs=argparse.REMAINDER, help="-- SCENE [bake options]")
    a = ap.parse_args()
    bins = [b.split("=", 1) for b in a.bin]
    args = a.bake_args[1:] if a.bake_args[:1] == ["--"] else a.bake_args
    if len(bins) < 2 or not args:
        ap.error("two --bin NAME=PATH and a scene after -- are needed")
    if a.pinned and len(bins) != 2:
        ap.error("--pinned compares two binaries")
    work = tempfile.mkdtemp(prefix="walkrad-ab-")
    times = {name: [] for name, _ in bins}
    try:
        if a.pinned:
            pinned(bins, args, a.rounds, work)
            return
        for r in range(a.rounds):
            for name, path in bins:
                out = os.path.join(work, f"{name}-{r}.bake")
                start = time.monotonic()
                proc = subprocess.Popen([path, "bake", *args, "-o", out, "-q"], stdout=subprocess.DEVNULL,
                                        stderr=subprocess.PIPE, text=True)
                _, status, usage = os.wait4(proc.pid, 0)
                wall = time.monotonic() - start
                err = proc.stderr.read()
                if os.waitstatus_to_exitcode(status) != 0:
                    sys.exit(f"{name} failed (exit {os.waitstatus_to_exitcode(status)}): {err.strip()[-400:]}")
                times[name].append((wall, usage.ru_utime, usage.ru_maxrss / 1024))
                print(f"round {r + 1} {name}: {wall:.2f} s wall, {usage.ru_utime:.2f} s user, "
                      f"{usage.ru_maxrss / 1024:.0f} MiB", flush=True)
        first = bins[0][0]
        identical = all(same_tree(os.path.join(work, f"{first}-0.bake"), os.path.join(work, f"{n}-{r}.bake"))
                        for n, _ in bins for r in range(a.rounds))
        base_wall = statistics.median(t[0] for t in times[first])
        base_user = statistics.median(t[1] for t in times[first])
        print(f"\n| binary | median wall (s) | median user (s) | wall / {first} | user / {first} | peak MiB |")
        print("| --- | ---: | ---: | ---: | ---: | ---: |")
        for name, _ in bins:
            wall = statistics.median(t[0] for t in times[name])
            user = statistics.median(t[1] for t in times[name])
            peak = max(t[2] for t in times[name])
            print(f"| {name} | {wall:.2f} | {user:.2f} | {wall / base_wall:.3f} | {user / base_user:.3f} | {peak:.0f} |")
        print(f"\nbakes byte-identical (less report.json): {'yes' if identical else 'NO'}")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
