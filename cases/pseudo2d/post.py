#!/usr/bin/env python3
"""Summary of a run of cases/pseudo2d/dem.toml: the pressure drop against the bed's weight per area and the bed
height after the start-up, against the source's expanded bed (about 0.05 m at 2 U_mf, README.md).

Usage: post.py RUN_DIR [T_FROM=0.15] [--png FIGURE.png]
--png draws the pressure drop and the bed height against time (needs matplotlib: /usr/bin/python3 post.py ...).
Weight per area: N m g / (width x depth) of the particles in the run (monitor.csv solids_mass_kg at the first row).
monitor.csv's pressure_drop_Pa is taken between the centres of the bottom and top cell rows, so it misses the
solids in the lowest half cell (2.4 mm); fluid_force_y_N over the bed's weight is the whole bed's support.
Voids: the cells of fields/*.vti (voidage, zlib-compressed appended data) above bubble.threshold (0.8) below the
bed surface (bubble.csv bed_height_m of the same frame).
"""
import csv
import glob
import os
import re
import statistics
import struct
import sys
import zlib

WIDTH, DEPTH, G = 0.0432, 0.01, 9.81


def column(rows, name, t_from):
    return [float(r[name]) for r in rows if float(r["time_s"]) >= t_from and r.get(name, "") != ""]


def vti_voidage(path):
    """(n, voidage list in x-fastest order) of a fluidbed VTI frame: the first appended array, UInt64 headers."""
    raw = open(path, "rb").read()
    head = raw[:raw.index(b"<AppendedData")].decode()
    n = [int(a) for a in re.search(r'WholeExtent="([^"]+)"', head).group(1).split()[1::2]]
    blob = raw[raw.index(b"_", raw.index(b"<AppendedData")) + 1:]
    nblocks = struct.unpack_from("<Q", blob, 0)[0]
    sizes = struct.unpack_from(f"<{nblocks}Q", blob, 24)
    pos, data = 24 + 8 * nblocks, b""
    for c in sizes:
        data += zlib.decompress(blob[pos:pos + c])
        pos += c
    return n, list(struct.unpack(f"<{len(data) // 8}d", data))


def voids(run, bub, t_from, threshold=0.8, dy=0.0048):
    height = {round(float(r["time_s"]), 6): float(r["bed_height_m"]) for r in bub if r["bed_height_m"] != ""}
    frames = []
    for i, path in enumerate(sorted(glob.glob(os.path.join(run, "fields", "*.vti")))):
        t = round(0.01 * i, 6)
        if t < t_from or t not in height:
            continue
        (nx, ny, nz), eps = vti_voidage(path)
        rows_in_bed = int(height[t] / dy)
        cells = [eps[(k * ny + j) * nx + i] for k in range(nz) for j in range(rows_in_bed) for i in range(nx)]
        frames.append((t, sum(1 for e in cells if e > threshold), max(cells)))
    return frames


def figure(path, mon, bub, weight):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(2, 1, figsize=(6.0, 4.6), sharex=True)
    a.plot(column(mon, "time_s", 0.0), column(mon, "pressure_drop_Pa", 0.0), lw=1.0, label="pressure drop")
    a.axhline(weight, color="k", ls="--", lw=0.8, label=f"bed weight per area, {weight:.1f} Pa")
    a.set_ylabel("pressure drop (Pa)")
    a.legend(fontsize=8, loc="lower right")
    b.plot(column(bub, "time_s", 0.0), [1e3 * h for h in column(bub, "bed_height_m", 0.0)], "o-", ms=2.5, lw=1.0,
           label="bed height (voidage < 0.7)")
    b.axhline(50.0, color="k", ls="--", lw=0.8, label="experiment at 2 U_mf (via the source), about 50 mm")
    b.set_ylabel("bed height (mm)")
    b.set_xlabel("time (s)")
    b.legend(fontsize=8, loc="lower right")
    fig.suptitle("Pseudo-2D bed (Mueller et al. 2008), cases/pseudo2d/dem.toml", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    print(f"figure -> {path}")


def main():
    args = sys.argv[1:]
    png = None
    if "--png" in args:
        i = args.index("--png")
        png = args[i + 1]
        del args[i:i + 2]
    if len(args) not in (1, 2):
        sys.exit(__doc__)
    run = args[0]
    t_from = float(args[1]) if len(args) == 2 else 0.15
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
    force = column(mon, "fluid_force_y_N", t_from)
    if force:
        w = float(mon[0]["solids_mass_kg"]) * G
        print(f"fluid force on the bed  mean {statistics.mean(force) / w:.3f} of its weight")
    fr = voids(run, bub, t_from)
    if fr:
        with_voids = [f for f in fr if f[1] > 0]
        best = max(fr, key=lambda f: f[1])
        print(f"voids (> 0.8 in the bed) in {len(with_voids)} of {len(fr)} frames; most at t = {best[0]:g} s:"
              f" {best[1]} cells, max voidage {best[2]:.3f}")
    lost = [r for r in mon if r.get("particles_lost", "") not in ("", "0")]
    print(f"particles lost          {lost[-1]['particles_lost'] if lost else 0}")
    if png:
        figure(png, mon, bub, weight)


if __name__ == "__main__":
    main()
