"""Checks the example tests share (test_ies_room.py, test_daylit_room.py): failures collected, not raised, so
that one run reports every fault."""
import glob
import json
import os
import struct
import subprocess

from png_pixels import read_png


class Checks:
    def __init__(self, source):
        self.failures = []
        self.validate = ["node", os.path.join(source, "tools/validator/validate.mjs"), "--max-warnings", "0"]

    def check(self, ok, message):
        if not ok:
            self.failures.append(message)

    def validator_accepts(self, path, what):
        """The Khronos validator, 0 errors and 0 warnings, on a file or every chunk of a bake folder."""
        r = subprocess.run(self.validate + [path], capture_output=True, text=True)
        print(r.stdout, end="")
        self.check(r.returncode == 0, f"the validator refused {what}: " + r.stdout + r.stderr)

    def frames_lit(self, view, bake, frames, count):
        """walkrad-view plays the bake headless: `count` frames, none nearly black."""
        subprocess.run([view, bake, "--headless", "--frames", frames, "--width", "240", "--height", "160"], check=True)
        pngs = sorted(glob.glob(os.path.join(frames, "*.png")))
        self.check(len(pngs) == count, f"{len(pngs)} frames, not {count}")
        for png in pngs:
            width, height, bpp, rows = read_png(png)
            mean = sum(sum(row) for row in rows) / (width * height * bpp)
            print(f"frame {os.path.basename(png)}: {width}x{height}, mean {mean:.1f}/255")
            self.check(mean > 20, f"{os.path.basename(png)} is nearly black (mean {mean:.1f}/255)")

    def done(self):
        for f in self.failures:
            print("FAIL:", f)
        return 1 if self.failures else 0


def glb(path):
    """A .glb's JSON and its binary chunk."""
    blob = open(path, "rb").read()
    (json_length,) = struct.unpack("<I", blob[12:16])
    return json.loads(blob[20:20 + json_length]), blob[20 + json_length + 8:]


def emitted(bake):
    return json.load(open(os.path.join(bake, "report.json")))["energy_audit"]["emitted_w"]
