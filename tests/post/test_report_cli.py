#!/usr/bin/env python3
"""`fluidbed report` on short real runs of both models (issue 5, acceptance 3): every figure is written and not
blank, and summary.md's Table 2 and detachment times are the bubble.csv values.
argv[1]: the fluidbed binary, argv[2]: the repository root."""
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def run(cmd):
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:
        fail(f"{' '.join(cmd)} exited {res.returncode}\n{res.stdout}\n{res.stderr}")


def main():
    binary, repo = sys.argv[1], sys.argv[2]
    small = ["--set", "domain.width=0.12", "--set", "domain.height=0.3", "--set", "inlet.jet[0].centre=0.07",
             "--set", "output.interval=0.01", "--set", "output.checkpoint_interval=0", "--quiet"]
    with tempfile.TemporaryDirectory() as tmp:
        dem = os.path.join(tmp, "dem")
        run([binary, "run", os.path.join(repo, "cases/gera1998/dem.toml"), "--out", dem, "--end-time", "0.06",
             "--set", "particles.count=600", "--set", "particles.fill_height=0.3", "--set", "settle.cache=",
             "--set", "settle.max_time=0.4", "--set", "bubble.u_mf=1.8"] + small)
        tfm = os.path.join(tmp, "tfm")
        run([binary, "run", os.path.join(repo, "cases/gera1998/tfm.toml"), "--out", tfm, "--end-time", "0.06",
             "--set", "tfm.packed_height=0.15"] + small)
        out = os.path.join(tmp, "report")
        run([binary, "report", dem, tfm, "--out", out])

        import matplotlib.image as mpimg
        for name in ["voidage.png", "layers_particles.png", "layers_tracers.png", "nose_height.png",
                     "rise_velocity.png", "throughflow_ratio.png", "equivalent_diameter.png",
                     "rise_vs_correlation.png", "pressure_drop.png", "mixing_index.png"]:
            path = os.path.join(out, "figures", name)
            if not os.path.isfile(path):
                fail(f"missing figure {name}")
            if not float(np.var(mpimg.imread(path)[..., :3])) > 0.0:
                fail(f"blank figure {name}")

        summary = open(os.path.join(out, "summary.md")).read()
        checked = 0
        for t in [0.2, 0.3, 0.4, 0.5]:
            line = next((ln for ln in summary.splitlines() if ln.startswith(f"| {t} |")), None)
            if line is None:
                fail(f"Table 2 has no row for t = {t}")
            cells = [c.strip() for c in line.strip().strip("|").split("|")][1:]
            for r, folder in enumerate([dem, tfm]):
                rows = list(csv.reader(open(os.path.join(folder, "bubble.csv"))))[1:]
                k = int(np.argmin([abs(float(row[0]) - t) for row in rows]))
                got = cells[3 * r:3 * r + 3]
                if rows[k][3] == "":
                    if not all(g.startswith("–") for g in got):
                        fail(f"Table 2 at t = {t}, run {r}: {got} but bubble.csv has no bubble")
                else:
                    want = [f"{float(rows[k][3]):.2f} [{float(rows[k][0]):.3f}]", f"{float(rows[k][2]):.2f}",
                            f"{float(rows[k][4]):.2f}"]
                    if got != want:
                        fail(f"Table 2 at t = {t}, run {r}: {got} != {want}")
                checked += 1
        print(f"report of two real runs: 10 figures, {checked} Table 2 cells match bubble.csv")
        print("1 passed, 0 failed")


if __name__ == "__main__":
    main()
