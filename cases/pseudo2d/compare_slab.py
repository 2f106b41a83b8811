#!/usr/bin/env python3
"""Compare the paper's 2D CFD-DEM run with its 3D one-diameter slab (slab1d.toml): settled voidage, pressure drop
and bubble detachment time (issue 12, acceptance item 4).

Usage: compare_slab.py RUN_2D RUN_3D [--depth 0.004] [--diameter 0.004] [--width 0.6]
Both run folders need particles/000000.csv (output.particles_csv = true), monitor.csv and bubble.csv.

Voidage: 1 - (sum of sphere volumes with centres in 0.02 m < y < 0.40 m) / (width x 0.38 m x depth), with depth
the 2D model's coupling.depth and the slab's domain.depth, both one diameter: one definition for both runs, below
the bed surface (0.52 m) and above the floor's ordered layers.
"""
import argparse
import csv
import math
import os


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def bed_voidage(run, width, depth, d, y0=0.02, y1=0.40):
    ps = rows(os.path.join(run, "particles", "000000.csv"))
    n = sum(1 for p in ps if y0 < float(p["y"]) < y1)
    return 1.0 - n * math.pi * d ** 3 / 6.0 / (width * (y1 - y0) * depth), len(ps)


def detachment(run):
    was_attached = False
    for r in rows(os.path.join(run, "bubble.csv")):
        if r["attached"] == "1":
            was_attached = True
        elif was_attached and r["attached"] == "0":
            return float(r["time_s"])
    return None


def pressure(run):
    return {round(float(r["time_s"]), 9): float(r["pressure_drop_Pa"])
            for r in rows(os.path.join(run, "monitor.csv")) if r["pressure_drop_Pa"] != ""}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_2d")
    ap.add_argument("run_3d")
    ap.add_argument("--depth", type=float, default=0.004)
    ap.add_argument("--diameter", type=float, default=0.004)
    ap.add_argument("--width", type=float, default=0.6)
    a = ap.parse_args()

    e2, n2 = bed_voidage(a.run_2d, a.width, a.depth, a.diameter)
    e3, n3 = bed_voidage(a.run_3d, a.width, a.depth, a.diameter)
    print(f"particles            2D {n2}  3D {n3}")
    print(f"settled bed voidage  2D {e2:.6f}  3D {e3:.6f}  difference {e3 - e2:+.2e}")
    p2, p3 = pressure(a.run_2d), pressure(a.run_3d)
    common = sorted(set(p2) & set(p3))
    if common:
        t0 = common[0]
        worst = max(common, key=lambda t: abs(p3[t] - p2[t]))
        print(f"pressure drop t={t0:g} s  2D {p2[t0]:.2f} Pa  3D {p3[t0]:.2f} Pa  difference {p3[t0] - p2[t0]:+.3g} Pa"
              f" ({(p3[t0] - p2[t0]) / p2[t0]:+.2%})")
        print(f"largest pressure-drop difference over {len(common)} samples: {p3[worst] - p2[worst]:+.3g} Pa at t = {worst:g} s")
    d2, d3 = detachment(a.run_2d), detachment(a.run_3d)
    fmt = lambda t: "none" if t is None else f"{t:.3f} s"
    diff = "" if d2 is None or d3 is None else f"  difference {d3 - d2:+.3f} s"
    print(f"bubble detachment    2D {fmt(d2)}  3D {fmt(d3)}{diff}")


if __name__ == "__main__":
    main()
