#!/usr/bin/env python3
"""Summary of a run of cases/pseudo2d/dem.toml: the pressure drop against the bed's weight per area and the bed
height after the start-up, against the source's expanded bed (about 0.05 m at 2 U_mf, README.md).

Usage: post.py RUN_DIR [T_FROM=0.15]
Weight per area: N m g / (width x depth) of the particles in the run (monitor.csv solids_mass_kg at the first row).
"""
import csv
import os
import statistics
import sys

WIDTH, DEPTH, G = 0.0432, 0.01, 9.81


def column(rows, name, t_from):
    return [float(r[name]) for r in rows if float(r["time_s"]) >= t_from and r.get(name, "") != ""]


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    run = sys.argv[1]
    t_from = float(sys.argv[2]) if len(sys.argv) == 3 else 0.15
    mon = list(csv.DictReader(open(os.path.join(run, "monitor.csv"), newline="")))
    bub = list(csv.DictReader(open(os.path.join(run, "bubble.csv"), newline="")))
    weight = float(mon[0]["solids_mass_kg"]) * G / (WIDTH * DEPTH)
    dp = column(mon, "pressure_drop_Pa", t_from)
    h = column(bub, "bed_height_m", t_from)
    print(f"samples from t = {t_from} s: {len(dp)} pressure drops, {len(h)} bed heights")
    print(f"bed weight per area     {weight:.1f} Pa")
    if dp:
        print(f"pressure drop           mean {statistics.mean(dp):.1f} Pa ({statistics.mean(dp) / weight - 1:+.1%}),"
              f" min {min(dp):.1f}, max {max(dp):.1f}, std {statistics.pstdev(dp):.1f} Pa")
    if h:
        print(f"bed height              mean {statistics.mean(h):.4f} m, min {min(h):.4f}, max {max(h):.4f} m"
              f" (source, experiment: about 0.05 m)")
    lost = [r for r in mon if r.get("particles_lost", "") not in ("", "0")]
    print(f"particles lost          {lost[-1]['particles_lost'] if lost else 0}")


if __name__ == "__main__":
    main()
