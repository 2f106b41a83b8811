#!/usr/bin/env python3
"""`fluidbed report --animate` (issue 15, item 9): a 0.05 s run of a 300-particle CFD-DEM bed with a field and a
particle frame every 0.01 s gives figures/animation-<run>.gif with one frame per field frame (6), each frame
different from the first once the bed moves, and summary.md links it.
Usage (CTest): test_report_animation.py FLUIDBED_BINARY SOURCE_DIR"""
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

binary = sys.argv[1]
case = """case.name = "anim"
case.seed = 7
domain.width = 0.1
domain.height = 0.3
particles.count = 300
particles.fill_height = 0.1
settle.enabled = false
dem.time_step = 1e-4
grid.cell_width = 0.01
coupling.dem_substeps = 2
inlet.velocity = 2.5
output.interval = 0.01
output.checkpoint_interval = 0.0
"""


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


with tempfile.TemporaryDirectory() as tmp:
    path = os.path.join(tmp, "anim.toml")
    open(path, "w").write(case)
    run = os.path.join(tmp, "anim")
    for cmd in ([binary, "run", path, "--out", run, "--end-time", "0.05", "--threads", "1", "--quiet"],
                [binary, "report", run, "--animate", "--out", os.path.join(tmp, "rep")]):
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            fail(f"{' '.join(cmd)}: exit {r.returncode}\n{r.stderr}")
    gif = os.path.join(tmp, "rep", "figures", "animation-anim.gif")
    if not os.path.isfile(gif):
        fail("no animation-anim.gif")
    im = Image.open(gif)
    print(f"frames: exact 6 computed {im.n_frames}")
    if im.n_frames != 6:
        fail("one GIF frame per field frame")
    first = np.asarray(im.convert("RGB"), dtype=float)
    im.seek(5)
    last = np.asarray(im.convert("RGB"), dtype=float)
    if not np.abs(last - first).max() > 0:
        fail("the last frame equals the first")
    if "figures/animation-anim.gif" not in open(os.path.join(tmp, "rep", "summary.md")).read():
        fail("summary.md does not link the animation")
print("report animation: all checks passed")
