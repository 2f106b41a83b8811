#!/usr/bin/env python3
"""The emulsion the gas must cross above a bubble's nose (issue 32, item 3: why the TFM's gas velocity above the
nose falls to about half the CFD-DEM's once the jet closes).

For each run folder (2D, with fields.pvd frames holding the voidage, and bubble.csv) and each instant, on
the frame nearest it: the cells whose centres lie within --half-width of the bubble's nose line (bubble.csv
nose_x_m) and between the nose (nose_height_m) and --depth above it, and of them the emulsion (voidage below
--emulsion): their mean voidage, the 10th percentile, and the Ergun resistance of that mean relative to the
voidage eps_ref, ((1 - eps)^2 / eps^3) / ((1 - eps_ref)^2 / eps_ref^3), which is how much harder a given
superficial flow is to push through it (viscous branch of Eq. 13). Also, over the whole bed below the surface, the
1st percentile of the emulsion voidage (how far the bed compacts anywhere).

Usage: python3 post/nose_cap_voidage.py RUN [RUN ...] [--times 0.3 0.4 0.5] [--half-width 0.05] [--depth 0.1]
       [--emulsion 0.6] [--eps-ref 0.43]
"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report import read_pvd, read_vti  # noqa: E402


def row_at(rows, t):
    best = min(rows, key=lambda r: abs(float(r["time_s"]) - t))
    return best if abs(float(best["time_s"]) - t) < 0.006 else None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--times", nargs="+", type=float, default=[0.3, 0.4, 0.5])
    ap.add_argument("--half-width", type=float, default=0.05)
    ap.add_argument("--depth", type=float, default=0.1)
    ap.add_argument("--emulsion", type=float, default=0.6)
    ap.add_argument("--eps-ref", type=float, default=0.43)
    a = ap.parse_args()
    ergun = lambda e: (1 - e) ** 2 / e ** 3
    print("| run | t (s) | nose (m) | cap: emulsion cells | cap: mean voidage | cap: 10th percentile | cap: Ergun "
          f"resistance / at {a.eps_ref} | bed: 1st percentile of the emulsion voidage |")
    print("|---|---|---|---|---|---|---|---|")
    for run in a.runs:
        name = os.path.basename(os.path.normpath(run))
        frames = read_pvd(os.path.join(run, "fields.pvd"))
        rows = list(csv.DictReader(open(os.path.join(run, "bubble.csv"))))
        for t in a.times:
            r = row_at(rows, t)
            if not frames or r is None or not r["nose_height_m"]:
                print(f"| {name} | {t:g} | no bubble or frame | | | | | |")
                continue
            tf, path = min(frames, key=lambda f: abs(f[0] - t))
            g = read_vti(path)
            eps = g["eps"]
            xc = g["x0"] + (np.arange(g["nx"]) + 0.5) * g["dx"]
            yc = g["y0"] + (np.arange(g["ny"]) + 0.5) * g["dy"]
            nose, nx_ = float(r["nose_height_m"]), float(r["nose_x_m"])
            surface = float(r["bed_height_m"]) if r["bed_height_m"] else yc[-1]
            inx = np.abs(xc - nx_) <= a.half_width
            iny = (yc > nose) & (yc <= nose + a.depth)
            cap = eps[np.ix_(iny, inx)]
            cap = cap[cap < a.emulsion]
            bed = eps[yc < surface][:, :]
            bed = bed[bed < a.emulsion]
            if cap.size == 0:
                print(f"| {name} | {t:g} | {nose:.3f} | 0 | | | | {np.percentile(bed, 1):.4f} |")
                continue
            m = cap.mean()
            print(f"| {name} | {t:g} | {nose:.3f} | {cap.size} | {m:.4f} | {np.percentile(cap, 10):.4f} | "
                  f"{ergun(m) / ergun(a.eps_ref):.2f} | {np.percentile(bed, 1):.4f} |")


if __name__ == "__main__":
    main()
