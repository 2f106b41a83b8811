#!/usr/bin/env python3
"""Statistics of a settled bed from a particle CSV (id,x,y,vx,vy,omega,species[,...]): height, packing fraction,
voidage of the monolayer, coordination number and the largest overlaps. Used for docs/verification-dem.md
("The paper's packed bed").

Usage: bed_stats.py PARTICLES.csv [--width 0.6] [--diameter 0.004] [--columns 30]
All particles are taken to have the given diameter (the paper's single species).
"""
import argparse
import csv
import math

import numpy as np


def load(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return np.array([float(r["x"]) for r in rows]), np.array([float(r["y"]) for r in rows])


def contacts(x, y, d):
    """Pairs (i < j) closer than d, found through a cell grid of side d, and their overlaps."""
    cx = np.floor(x / d).astype(np.int64)
    cy = np.floor(y / d).astype(np.int64)
    cells = {}
    for i, key in enumerate(zip(cx.tolist(), cy.tolist())):
        cells.setdefault(key, []).append(i)
    pairs, overlaps = [], []
    for (a, b), members in cells.items():
        for da in (-1, 0, 1):
            for db in (-1, 0, 1):
                other = cells.get((a + da, b + db))
                if other is None:
                    continue
                for i in members:
                    for j in other:
                        if j <= i:
                            continue
                        dist = math.hypot(x[j] - x[i], y[j] - y[i])
                        if dist < d:
                            pairs.append((i, j))
                            overlaps.append(d - dist)
    return pairs, np.array(overlaps)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv")
    ap.add_argument("--width", type=float, default=0.6)
    ap.add_argument("--diameter", type=float, default=0.004)
    ap.add_argument("--columns", type=int, default=30)
    a = ap.parse_args()
    x, y = load(a.csv)
    d, r, w = a.diameter, 0.5 * a.diameter, a.width
    n = len(x)
    # Bed height: mean over columns of the highest particle top.
    col = np.minimum((x / w * a.columns).astype(int), a.columns - 1)
    tops = [np.max(y[col == c] + r) for c in range(a.columns) if np.any(col == c)]
    height = float(np.mean(tops))
    disc = math.pi * r * r
    phi_all = n * disc / (w * height)
    # Interior: a band of 5 d away from the walls, the floor and the surface.
    m = 5 * d
    inner = (x > m) & (x < w - m) & (y > m) & (y < height - m)
    area_in = (w - 2 * m) * (height - 2 * m)
    phi_in = np.count_nonzero(inner) * disc / area_in
    eps_in = 1.0 - np.count_nonzero(inner) * (math.pi * d ** 3 / 6.0) / (area_in * d)
    pairs, ov = contacts(x, y, d)
    coordination = 2.0 * len(pairs) / n
    wall_ov = np.concatenate([r - x, r - (w - x), r - y])
    wall_ov = wall_ov[wall_ov > 0.0]
    print(f"particles                       {n}")
    print(f"bed height (mean top of {a.columns} columns) {height:.4f} m")
    print(f"2D packing fraction whole/interior {phi_all:.3f} / {phi_in:.3f}")
    print(f"monolayer voidage (depth d), interior {eps_in:.3f}")
    print(f"mean coordination number        {coordination:.2f}")
    print(f"largest particle-particle overlap {ov.max() * 1e3:.3f} mm = {ov.max() / d * 100:.1f}% of d")
    if wall_ov.size:
        print(f"largest particle-wall overlap   {wall_ov.max() * 1e3:.3f} mm = {wall_ov.max() / d * 100:.1f}% of d")


if __name__ == "__main__":
    main()
