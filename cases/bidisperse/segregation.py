#!/usr/bin/env python3
"""Segregation index of a bidisperse bed over time from a run's particles/*.csv (output.particles_csv = true).

S = (mean height of species FLOTSAM - mean height of species JETSAM) / bed height, the bed height being the mean
top of the highest particle in each of 8 vertical strips (as fluidbed's bed_height). S is about 0 for a mixed bed
and 0.5 for one fully separated into two layers of equal volume.

Usage: segregation.py OUT_DIR [FIGURE.png] [--jetsam 0] [--flotsam 1]
"""
import argparse
import glob
import os

import numpy as np


def index(path, jetsam, flotsam, width):
    with open(path) as f:
        header = f.readline().strip().split(",")
    a = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    col = {n: k for k, n in enumerate(header)}
    x, y, s = a[:, col["x"]], a[:, col["y"]], a[:, col["species"]].astype(int)
    r = 0.5 * a[:, col["diameter"]] if "diameter" in col else np.zeros_like(y)
    strips = np.clip((x / width * 8).astype(int), 0, 7)
    top = np.array([np.max((y + r)[strips == k]) if np.any(strips == k) else 0.0 for k in range(8)]).mean()
    return (y[s == flotsam].mean() - y[s == jetsam].mean()) / top, top


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("figure", nargs="?")
    ap.add_argument("--jetsam", type=int, default=0)
    ap.add_argument("--flotsam", type=int, default=1)
    args = ap.parse_args()
    width = None
    for line in open(os.path.join(args.out, "case.toml")):
        if line.strip().startswith("width") and width is None:
            width = float(line.split("=")[1].split("#")[0])
    times, s_values, tops = [], [], []
    settled = os.path.join(args.out, "settled.csv")
    files = sorted(glob.glob(os.path.join(args.out, "particles", "*.csv")))
    interval = None
    for line in open(os.path.join(args.out, "case.toml")):
        if line.strip().startswith("interval") and interval is None:
            interval = float(line.split("=")[1].split("#")[0])
    for k, f in enumerate(files):
        s, top = index(f, args.jetsam, args.flotsam, width)
        times.append(k * interval)
        s_values.append(s)
        tops.append(top)
        print(f"t = {k * interval:5.2f} s  S = {s:6.3f}  bed height {top:.4f} m")
    if os.path.exists(settled):
        s, top = index(settled, args.jetsam, args.flotsam, width)
        print(f"settled bed: S = {s:.3f}, height {top:.4f} m")
    if args.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5, 3.2))
        ax.plot(times, s_values, "o-", ms=3)
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("segregation index S")
        ax.set_title("S = (mean y flotsam - mean y jetsam) / H", fontsize=10)
        fig.tight_layout()
        fig.savefig(args.figure, dpi=120)


if __name__ == "__main__":
    main()
