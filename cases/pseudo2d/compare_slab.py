#!/usr/bin/env python3
"""Compare the paper's 2D CFD-DEM run with its 3D one-diameter slab (slab1d.toml): settled voidage, pressure drop
and bubble detachment time (issue 12, acceptance item 4).

Usage: compare_slab.py RUN_2D RUN_3D [--depth 0.004] [--diameter 0.004] [--width 0.6] [--png FIGURE.png]
--png draws both runs' pressure drop and bubble nose height (needs matplotlib: /usr/bin/python3 compare_slab.py).
Both run folders need particles/000000.csv (output.particles_csv = true), monitor.csv and bubble.csv.

Voidage: 1 - (sum of sphere volumes with centres in y0 < y < y1) / (width x (y1 - y0) x depth), with depth the 2D
model's coupling.depth and the slab's domain.depth, both one diameter: one definition for both runs. Two regions:
the whole bed (0 < y < the bed height of bubble.csv at t = 0) and 0.02 m < y < 0.40 m, below the bed surface
(0.52 m) and the jet's bubble and above the floor's ordered layers. For the slab, the largest |z - depth/2| of
every particle CSV it wrote measures how far spheres left the mid-plane.
"""
import glob
import argparse
import csv
import math
import os


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def bed_voidage(run, width, depth, d, y0=0.02, y1=0.40, frame="000000"):
    ps = rows(os.path.join(run, "particles", frame + ".csv"))
    n = sum(1 for p in ps if y0 < float(p["y"]) < y1)
    return 1.0 - n * math.pi * d ** 3 / 6.0 / (width * (y1 - y0) * depth), len(ps)


def bed_height0(run):
    return float(rows(os.path.join(run, "bubble.csv"))[0]["bed_height_m"])


def out_of_plane(run, depth):
    worst = 0.0
    for path in sorted(glob.glob(os.path.join(run, "particles", "*.csv"))):
        ps = rows(path)
        if ps and "z" in ps[0]:
            worst = max(worst, max(abs(float(p["z"]) - depth / 2) for p in ps))
    return worst


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
    ap.add_argument("--png")
    a = ap.parse_args()

    e2, n2 = bed_voidage(a.run_2d, a.width, a.depth, a.diameter)
    e3, n3 = bed_voidage(a.run_3d, a.width, a.depth, a.diameter)
    print(f"particles            2D {n2}  3D {n3}")
    h = bed_height0(a.run_2d)
    b2, _ = bed_voidage(a.run_2d, a.width, a.depth, a.diameter, 0.0, h)
    b3, _ = bed_voidage(a.run_3d, a.width, a.depth, a.diameter, 0.0, h)
    print(f"bed height t=0       2D {h:.4f} m  3D {bed_height0(a.run_3d):.4f} m")
    print(f"voidage 0<y<{h:.3f} m  2D {b2:.6f}  3D {b3:.6f}  difference {b3 - b2:+.2e}")
    print(f"voidage 0.02<y<0.40  2D {e2:.6f}  3D {e3:.6f}  difference {e3 - e2:+.2e}")
    last = sorted(set(os.listdir(os.path.join(a.run_2d, "particles"))) & set(os.listdir(os.path.join(a.run_3d, "particles"))))
    last = [f[:-4] for f in last if f.endswith(".csv") and f != "000000.csv"]
    if last:
        f2, _ = bed_voidage(a.run_2d, a.width, a.depth, a.diameter, frame=last[-1])
        f3, _ = bed_voidage(a.run_3d, a.width, a.depth, a.diameter, frame=last[-1])
        print(f"voidage 0.02<y<0.40 at frame {last[-1]}  2D {f2:.6f}  3D {f3:.6f}  difference {f3 - f2:+.2e}")
    print(f"slab out of plane    max |z - depth/2| = {out_of_plane(a.run_3d, a.depth):.3g} m over its particle CSVs")
    p2, p3 = pressure(a.run_2d), pressure(a.run_3d)
    common = sorted(set(p2) & set(p3))
    if common:
        t0 = common[0]
        worst = max(common, key=lambda t: abs(p3[t] - p2[t]))
        print(f"pressure drop t={t0:g} s  2D {p2[t0]:.2f} Pa  3D {p3[t0]:.2f} Pa  difference {p3[t0] - p2[t0]:+.3g} Pa"
              f" ({(p3[t0] - p2[t0]) / p2[t0]:+.2%})")
        print(f"largest pressure-drop difference over {len(common)} samples: {p3[worst] - p2[worst]:+.3g} Pa at t = {worst:g} s")
        rms = math.sqrt(sum((p3[t] - p2[t]) ** 2 for t in common) / len(common))
        mean2 = sum(p2[t] for t in common) / len(common)
        mean3 = sum(p3[t] for t in common) / len(common)
        print(f"pressure drop over the run: mean 2D {mean2:.1f} Pa  3D {mean3:.1f} Pa, rms difference {rms:.3g} Pa")
    d2, d3 = detachment(a.run_2d), detachment(a.run_3d)
    fmt = lambda t: "none" if t is None else f"{t:.3f} s"
    diff = "" if d2 is None or d3 is None else f"  difference {d3 - d2:+.3f} s"
    print(f"bubble detachment    2D {fmt(d2)}  3D {fmt(d3)}{diff}")
    if a.png:
        figure(a.png, (a.run_2d, a.run_3d), (d2, d3))


def figure(path, runs, detached):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.0, 4.6), sharex=True)
    for run, label, style, td in zip(runs, ("2D model", "3D slab, one diameter deep"), ("-", "--"), detached):
        p = pressure(run)
        top.plot(sorted(p), [p[t] for t in sorted(p)], style, lw=1.0, label=label)
        b = [r for r in rows(os.path.join(run, "bubble.csv")) if r["nose_height_m"] != ""]
        bottom.plot([float(r["time_s"]) for r in b], [float(r["nose_height_m"]) for r in b], style, lw=1.0,
                    label=label + ("" if td is None else f", detached {td:.2f} s"))
    top.set_ylabel("pressure drop (Pa)")
    top.legend(fontsize=8)
    bottom.set_ylabel("bubble nose height (m)")
    bottom.set_xlabel("time (s)")
    bottom.legend(fontsize=8)
    fig.suptitle("Gera et al. (1998) bed: 2D model and 3D slab from the same settled bed", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    print(f"figure -> {path}")


if __name__ == "__main__":
    main()
