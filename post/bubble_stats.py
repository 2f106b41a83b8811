#!/usr/bin/env python3
"""Freely bubbling statistics over a time window from bubbles.csv and bubble_frames.csv (src/analysis/
bubble_population.hpp; docs/analysis.md, "Bubble statistics"):

- equivalent diameter against height (centroid above the distributor), binned, with Darton et al. (1977) in 3D,
  d_b = 0.54 (U - U_mf)^0.4 (h + 4 sqrt(A0))^0.8 g^-0.2 (SI units; A0 the distributor area per orifice, 0 for a
  porous plate); docs/ cite no 2D bubble-size correlation, so 2D runs get none;
- centroid rise velocity against equivalent diameter, binned, with U_b = C sqrt(g D), C = 0.711 in 3D (Davidson and
  Harrison 1963) and 0.5 in 2D (docs/analysis.md gives its sources);
- bubble frequency: bubbles whose centroid crosses a height upwards (between two samples of the same id), per second;
- bubble fraction: bubble area (volume) over bed area (volume) above the distributor zone, mean and standard deviation
  over the samples of the window.

Usage: bubble_stats.py OUT_DIR [--t0 T] [--t1 T] [--u U --u-mf UMF] [--a0 A0] [--distributor-height H]
                       [--heights 0.1,0.2] [--bins 10] [--out FIGURE.png] [--table TABLE.csv]
OUT_DIR holds bubbles.csv and bubble_frames.csv; the dimension is read from the header (volume_m3: 3D).
"""
import argparse
import csv
import os

import numpy as np

G = 9.81


def read_csv(path):
    """Columns of a CSV as lists of strings."""
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    keys = rows[0].keys() if rows else []
    return {k: [r[k] for r in rows] for k in keys}


def num(col):
    return np.array([float(v) if v != "" else np.nan for v in col])


def darton_diameter(h, u, u_mf, a0=0.0, g=G):
    """Darton, LaNauze, Davidson and Harrison (1977), Trans. IChemE 55:274: bubble diameter (m) at height h (m) above
    the distributor, excess gas velocity U - U_mf (m/s), distributor area per orifice A0 (m^2); dimensionally
    homogeneous, so SI in, metres out."""
    return 0.54 * (u - u_mf) ** 0.4 * (np.asarray(h) + 4.0 * np.sqrt(a0)) ** 0.8 / g ** 0.2


def rise_constant(dimension):
    """C of U_b = C sqrt(g D): 0.711 in 3D (Davidson and Harrison 1963), 0.5 in 2D (docs/analysis.md)."""
    return 0.711 if dimension == 3 else 0.5


def binned(x, y, edges):
    """Mean, standard deviation and count of y in each bin of x."""
    idx = np.digitize(x, edges) - 1
    idx[x == edges[-1]] = len(edges) - 2  # the last bin is closed on the right
    mean, std, count = [], [], []
    for b in range(len(edges) - 1):
        v = y[(idx == b) & np.isfinite(y)]
        count.append(v.size)
        mean.append(v.mean() if v.size else np.nan)
        std.append(v.std() if v.size else np.nan)
    return np.array(mean), np.array(std), np.array(count)


def crossings(bubbles, height, t0, t1):
    """Upward crossings of height by the centroid between consecutive samples of the same id, in (t0, t1]."""
    ids, t, y = bubbles["id"], bubbles["time_s"], bubbles["centroid_y_m"]
    n = 0
    last = {}
    for k in np.argsort(t, kind="stable"):
        i = ids[k]
        if i in last:
            tp, yp = last[i]
            if t0 < t[k] <= t1 and yp < height <= y[k]:
                n += 1
        last[i] = (t[k], y[k])
    return n


def bubble_statistics(bubbles, frames, t0=None, t1=None, u=None, u_mf=None, a0=0.0, distributor_height=0.0,
                      heights=None, bins=10, dimension=None, g=G):
    """The statistics as a dict of numpy arrays. bubbles: columns of bubbles.csv (as read_csv() gives them; numbers
    converted here); frames: columns of bubble_frames.csv."""
    dimension = dimension or (3 if "volume_m3" in bubbles else 2)
    b = {"id": np.array([int(v) for v in bubbles["id"]]), "time_s": num(bubbles["time_s"]),
         "centroid_y_m": num(bubbles["centroid_y_m"]), "d": num(bubbles["equivalent_diameter_m"]),
         "u": num(bubbles["u_centroid_m_s"])}
    ft, frac = num(frames["time_s"]), num(frames["bubble_fraction"])
    t0 = ft.min() if t0 is None else t0
    t1 = ft.max() if t1 is None else t1
    inw = (b["time_s"] >= t0) & (b["time_s"] <= t1)
    h = b["centroid_y_m"][inw] - distributor_height
    d, ub = b["d"][inw], b["u"][inw]
    out = {"dimension": dimension, "t0": t0, "t1": t1}
    top = h.max() if h.size else 1.0
    h_edges = np.linspace(0.0, top, bins + 1) if h.size else np.linspace(0.0, 1.0, bins + 1)
    out["h"] = 0.5 * (h_edges[1:] + h_edges[:-1])
    out["d_mean"], out["d_std"], out["d_count"] = binned(h, d, h_edges)
    out["d_darton"] = (darton_diameter(out["h"], u, u_mf, a0, g) if dimension == 3 and u is not None
                       and u_mf is not None else np.full(out["h"].size, np.nan))
    d_edges = np.linspace(0.0, d.max() if d.size else 1.0, bins + 1)
    out["D"] = 0.5 * (d_edges[1:] + d_edges[:-1])
    out["u_mean"], out["u_std"], out["u_count"] = binned(d, ub, d_edges)
    out["u_theory"] = rise_constant(dimension) * np.sqrt(g * out["D"])
    heights = np.asarray(heights if heights is not None else out["h"][::max(1, bins // 4)])
    out["frequency_height"] = heights
    span = t1 - t0
    out["frequency"] = np.array([crossings(b, hh + distributor_height, t0, t1) / span if span > 0 else np.nan
                                 for hh in heights])
    fw = (ft >= t0) & (ft <= t1)
    out["fraction_mean"] = float(np.mean(frac[fw])) if fw.any() else np.nan
    out["fraction_std"] = float(np.std(frac[fw])) if fw.any() else np.nan
    return out


def write_table(s, path):
    """Long CSV: quantity,x,mean,std,count,correlation."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["quantity", "x", "mean", "std", "count", "correlation"])
        for k in range(s["h"].size):
            w.writerow(["diameter_vs_height_m", s["h"][k], s["d_mean"][k], s["d_std"][k], s["d_count"][k],
                        s["d_darton"][k]])
        for k in range(s["D"].size):
            w.writerow(["rise_velocity_vs_diameter_m_s", s["D"][k], s["u_mean"][k], s["u_std"][k], s["u_count"][k],
                        s["u_theory"][k]])
        for hh, fq in zip(s["frequency_height"], s["frequency"]):
            w.writerow(["frequency_per_s", hh, fq, "", "", ""])
        w.writerow(["bubble_fraction", "", s["fraction_mean"], s["fraction_std"], "", ""])


def figure(s, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.8))
    ax[0].errorbar(s["h"], s["d_mean"], yerr=s["d_std"], fmt="o", ms=4, label="run")
    if np.isfinite(s["d_darton"]).any():
        ax[0].plot(s["h"], s["d_darton"], "k-", label="Darton et al. (1977)")
    ax[0].set_xlabel("height above distributor (m)")
    ax[0].set_ylabel("equivalent diameter (m)")
    ax[1].errorbar(s["D"], s["u_mean"], yerr=s["u_std"], fmt="o", ms=4, label="run (centroid)")
    ax[1].plot(s["D"], s["u_theory"], "k-", label=f"{rise_constant(s['dimension'])} $\\sqrt{{gD}}$")
    ax[1].set_xlabel("equivalent diameter D (m)")
    ax[1].set_ylabel("rise velocity (m/s)")
    ax[2].plot(s["frequency_height"], s["frequency"], "o-")
    ax[2].set_xlabel("height above distributor (m)")
    ax[2].set_ylabel("bubble frequency (1/s)")
    ax[2].set_title(f"bubble fraction {s['fraction_mean']:.3g} $\\pm$ {s['fraction_std']:.2g}")
    for a in ax[:2]:
        a.legend(fontsize=8)
    fig.suptitle(f"{s['dimension']}D, t = {s['t0']:.3g} to {s['t1']:.3g} s")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out_dir")
    ap.add_argument("--t0", type=float)
    ap.add_argument("--t1", type=float)
    ap.add_argument("--u", type=float, help="superficial gas velocity, m/s")
    ap.add_argument("--u-mf", type=float, help="minimum fluidization velocity, m/s")
    ap.add_argument("--a0", type=float, default=0.0, help="distributor area per orifice, m^2")
    ap.add_argument("--distributor-height", type=float, default=0.0)
    ap.add_argument("--heights", help="comma-separated heights above the distributor for the frequency, m")
    ap.add_argument("--bins", type=int, default=10)
    ap.add_argument("--out", default="bubble_stats.png")
    ap.add_argument("--table", default="bubble_stats.csv")
    a = ap.parse_args()
    bub = read_csv(os.path.join(a.out_dir, "bubbles.csv"))
    frm = read_csv(os.path.join(a.out_dir, "bubble_frames.csv"))
    heights = [float(v) for v in a.heights.split(",")] if a.heights else None
    s = bubble_statistics(bub, frm, a.t0, a.t1, a.u, a.u_mf, a.a0, a.distributor_height, heights, a.bins)
    write_table(s, a.table)
    figure(s, a.out)
    print(f"wrote {a.table} and {a.out}")


if __name__ == "__main__":
    main()
