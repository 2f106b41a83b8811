#!/usr/bin/env python3
"""Freely bubbling statistics over a time window from bubbles.csv and bubble_frames.csv (src/analysis/
bubble_population.hpp; docs/analysis.md, "Bubble statistics"):

- equivalent diameter against height (centroid above the distributor), binned, with Darton et al. (1977) in 3D,
  d_b = 0.54 (U - U_mf)^0.4 (h + 4 sqrt(A0))^0.8 g^-0.2 (SI units; A0 the distributor area per orifice, 0 for a
  porous plate); in 2D the form of Shen, Johnsson and Leckner (2004) for two-dimensional beds,
  D = 0.89 [(U - U_mf)(h + h0)]^(2/3) g^(-1/3) (docs/analysis.md gives the sources and what was checked);
- centroid rise velocity against equivalent diameter, binned, with U_b = C sqrt(g D), C = 0.711 in 3D (Davidson and
  Harrison 1963) and 0.5 in 2D (docs/analysis.md gives its sources);
- bubble frequency: bubbles whose centroid crosses a height upwards (between two samples of the same id), per second;
- bubble fraction: bubble area (volume) over bed area (volume) above the distributor zone, mean and standard deviation
  over the samples of the window.

Slugs and plugs (bubbles.csv's last column `slug` = 1: a void across the whole cross-section of the column) are not
free bubbles: their rows are set aside from every statistic above and from the comparison with the correlations,
counted (`slug_samples`), and drawn apart in the figures ("slug / plug"). Files written before the column read as
slug = 0, and bubble_frames.csv without its `slugs` column as no slug.

Usage: bubble_stats.py OUT_DIR [--t0 T] [--t1 T] [--u U --u-mf UMF] [--a0 A0] [--h0 H0] [--distributor-height H]
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


def flags(cols, name, n):
    """An integer column (bubbles.csv `slug`, bubble_frames.csv `slugs`) as an int array of n values; 0 where the
    file has no such column (written before it) or the cell is empty."""
    col = cols.get(name) if cols else None
    if col is None:
        return np.zeros(n, dtype=int)
    return np.array([int(float(v)) if v.strip() not in ("", "nan") else 0 for v in col], dtype=int)


def slug_mask(bubbles):
    """True for the bubbles.csv rows that are slugs or plugs (column `slug` = 1; none in a file without it)."""
    n = len(bubbles.get("time_s", [])) if bubbles else 0
    return flags(bubbles, "slug", n) == 1


def darton_diameter(h, u, u_mf, a0=0.0, g=G):
    """Darton, LaNauze, Davidson and Harrison (1977), Trans. IChemE 55:274: bubble diameter (m) at height h (m) above
    the distributor, excess gas velocity U - U_mf (m/s), distributor area per orifice A0 (m^2); dimensionally
    homogeneous, so SI in, metres out."""
    return 0.54 * (u - u_mf) ** 0.4 * (np.asarray(h) + 4.0 * np.sqrt(a0)) ** 0.8 / g ** 0.2


def shen_diameter_2d(h, u, u_mf, h0=0.0, g=G):
    """Shen, Johnsson and Leckner (2004), Chem. Eng. Sci. 59:2607, for two-dimensional beds: area-equivalent bubble
    diameter (m) at height h (m) above the distributor, excess gas velocity U - U_mf (m/s), h0 (m) the height of the
    equivalent bubble source (0 for a porous plate). (U - U_mf) h is the bubble flow per unit depth (m^2/s), and
    [(U - U_mf) h]^(2/3) g^(-1/3) is the only power law of it and g that is a length: the 2D counterpart of Darton's
    [(U - U_mf)^2 h^4 / g]^(1/5)."""
    return 0.89 * ((u - u_mf) * (np.asarray(h) + h0)) ** (2.0 / 3.0) / g ** (1.0 / 3.0)


def diameter_correlation(dimension, h, u, u_mf, a0=0.0, h0=0.0, g=G):
    """The bubble-size correlation of the run's dimension (Darton et al. 1977 in 3D, Shen et al. 2004 in 2D)."""
    if dimension == 3:
        return darton_diameter(h, u, u_mf, a0, g)
    return shen_diameter_2d(h, u, u_mf, h0, g)


def correlation_name(dimension):
    return "Darton et al. (1977)" if dimension == 3 else "Shen et al. (2004), 2D"


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
    """Upward crossings of height by the centroid between consecutive samples of the same id, in (t0, t1]; with a
    `slug` mask, only between two samples that are both free bubbles (a void that is a slug at either sample is
    set aside)."""
    ids, t, y = bubbles["id"], bubbles["time_s"], bubbles["centroid_y_m"]
    slug = bubbles.get("slug", np.zeros(len(t), dtype=bool))
    n = 0
    last = {}
    for k in np.argsort(t, kind="stable"):
        i = ids[k]
        if i in last:
            tp, yp, sp = last[i]
            if t0 < t[k] <= t1 and yp < height <= y[k] and not sp and not slug[k]:
                n += 1
        last[i] = (t[k], y[k], slug[k])
    return n


def bubble_statistics(bubbles, frames, t0=None, t1=None, u=None, u_mf=None, a0=0.0, distributor_height=0.0,
                      heights=None, bins=10, dimension=None, g=G, h0=0.0):
    """The statistics as a dict of numpy arrays. bubbles: columns of bubbles.csv (as read_csv() gives them; numbers
    converted here); frames: columns of bubble_frames.csv. Rows with slug = 1 (slugs and plugs) are left out of
    every statistic and of the correlation; their number in the window is slug_samples, their heights and
    diameters slug_h, slug_d, slug_u (for the figures), and frame_slugs the sum of bubble_frames.csv's `slugs`."""
    dimension = dimension or (3 if "volume_m3" in bubbles else 2)
    b = {"id": np.array([int(v) for v in bubbles["id"]]), "time_s": num(bubbles["time_s"]),
         "centroid_y_m": num(bubbles["centroid_y_m"]), "d": num(bubbles["equivalent_diameter_m"]),
         "u": num(bubbles["u_centroid_m_s"]), "slug": slug_mask(bubbles)}
    ft, frac = num(frames["time_s"]), num(frames["bubble_fraction"])
    t0 = ft.min() if t0 is None else t0
    t1 = ft.max() if t1 is None else t1
    window = (b["time_s"] >= t0) & (b["time_s"] <= t1)
    inw = window & ~b["slug"]
    slugs = window & b["slug"]
    h = b["centroid_y_m"][inw] - distributor_height
    d, ub = b["d"][inw], b["u"][inw]
    out = {"dimension": dimension, "t0": t0, "t1": t1}
    out["slug_samples"] = int(slugs.sum())
    out["slug_h"] = b["centroid_y_m"][slugs] - distributor_height
    out["slug_d"], out["slug_u"] = b["d"][slugs], b["u"][slugs]
    top = h.max() if h.size else 1.0
    h_edges = np.linspace(0.0, top, bins + 1) if h.size else np.linspace(0.0, 1.0, bins + 1)
    out["h"] = 0.5 * (h_edges[1:] + h_edges[:-1])
    out["d_mean"], out["d_std"], out["d_count"] = binned(h, d, h_edges)
    out["d_corr"] = (diameter_correlation(dimension, out["h"], u, u_mf, a0, h0, g) if u is not None
                       and u_mf is not None and u > u_mf else np.full(out["h"].size, np.nan))
    out["samples"] = int(d.size)
    out["d_all_mean"] = float(np.nanmean(d)) if d.size else np.nan
    out["u_all_mean"] = float(np.nanmean(ub)) if np.isfinite(ub).any() else np.nan
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
    out["frame_slugs"] = int(flags(frames, "slugs", ft.size)[fw].sum())
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
                        s["d_corr"][k]])
        for k in range(s["D"].size):
            w.writerow(["rise_velocity_vs_diameter_m_s", s["D"][k], s["u_mean"][k], s["u_std"][k], s["u_count"][k],
                        s["u_theory"][k]])
        for hh, fq in zip(s["frequency_height"], s["frequency"]):
            w.writerow(["frequency_per_s", hh, fq, "", "", ""])
        w.writerow(["bubble_fraction", "", s["fraction_mean"], s["fraction_std"], "", ""])
        w.writerow(["bubble_samples", "", "", "", s["samples"], ""])
        w.writerow(["slug_samples_set_aside", "", "", "", s["slug_samples"], ""])
        w.writerow(["frame_slugs", "", "", "", s["frame_slugs"], ""])


def slug_note(s):
    """'N slug / plug samples set aside' of a statistics dict."""
    n = s.get("slug_samples", 0)
    return f"{n} slug / plug sample{'' if n == 1 else 's'} set aside"


def plot_slugs(ax_d, ax_u, s, colour="k", label="slug / plug"):
    """The slug and plug samples, which the statistics leave out, as open squares: diameter against height and,
    where they have one, rise velocity against diameter."""
    if not s.get("slug_samples"):
        return
    ax_d.plot(s["slug_h"], s["slug_d"], "s", ms=5, mfc="none", color=colour, label=label)
    ok = np.isfinite(s["slug_d"]) & np.isfinite(s["slug_u"])
    if ok.any():
        ax_u.plot(s["slug_d"][ok], s["slug_u"][ok], "s", ms=5, mfc="none", color=colour, label=label)


def figure(s, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.8))
    ax[0].errorbar(s["h"], s["d_mean"], yerr=s["d_std"], fmt="o", ms=4, label="run")
    if np.isfinite(s["d_corr"]).any():
        ax[0].plot(s["h"], s["d_corr"], "k-", label=correlation_name(s["dimension"]))
    ax[0].set_xlabel("height above distributor (m)")
    ax[0].set_ylabel("equivalent diameter (m)")
    ax[1].errorbar(s["D"], s["u_mean"], yerr=s["u_std"], fmt="o", ms=4, label="run (centroid)")
    ax[1].plot(s["D"], s["u_theory"], "k-", label=f"{rise_constant(s['dimension'])} $\\sqrt{{gD}}$")
    plot_slugs(ax[0], ax[1], s, colour="C3")
    ax[1].set_xlabel("equivalent diameter D (m)")
    ax[1].set_ylabel("rise velocity (m/s)")
    ax[2].plot(s["frequency_height"], s["frequency"], "o-")
    ax[2].set_xlabel("height above distributor (m)")
    ax[2].set_ylabel("bubble frequency (1/s)")
    ax[2].set_title(f"bubble fraction {s['fraction_mean']:.3g} $\\pm$ {s['fraction_std']:.2g}")
    for a in ax[:2]:
        a.legend(fontsize=8)
    fig.suptitle(f"{s['dimension']}D, t = {s['t0']:.3g} to {s['t1']:.3g} s, {s['samples']} bubble samples"
                 + (f" ({slug_note(s)}: not in the statistics)" if s.get("slug_samples") else ""))
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


# ------------------------------------------------------------------------------------ for post/report.py

def run_window(case, t_first, t_last):
    """(t0, t1, why) of a run: its [averages] window when the case has one (the averaged fields and the statistics
    then describe the same interval), else the second half of its bubble samples (the first holds the start-up)."""
    a = case.get("averages", {}) if isinstance(case.get("averages"), dict) else {}
    t0, t1 = a.get("t_start"), a.get("t_end")
    if isinstance(t0, (int, float)) and isinstance(t1, (int, float)) and t1 > t0:
        return float(t0), float(t1), "the case's [averages] window"
    return 0.5 * (t_first + t_last), t_last, "the second half of the run"


def run_statistics(folder, case, dimension, g=G, bins=8):
    """(statistics, None) of a run folder with bubbles.csv and bubble_frames.csv, or (None, why not). U from
    inlet.velocity, U_mf from bubble.u_mf (the paper's 1.8 m/s if absent), a porous plate (A0 = 0, h0 = 0); the
    frequency at the quarters of the mean bed height of the window (bed_height_m of bubble_frames.csv, else the
    highest centroid)."""
    paths = [os.path.join(folder, f) for f in ("bubbles.csv", "bubble_frames.csv")]
    if not all(os.path.isfile(p) for p in paths):
        return None, "no bubbles.csv or bubble_frames.csv"
    bub, frm = read_csv(paths[0]), read_csv(paths[1])
    if not bub or not bub.get("time_s") or not frm or not frm.get("time_s"):
        return None, "no bubble in bubbles.csv"
    ft = num(frm["time_s"])
    t0, t1, why = run_window(case, float(ft.min()), float(ft.max()))
    inlet = case.get("inlet", {}) if isinstance(case.get("inlet"), dict) else {}
    bubble = case.get("bubble", {}) if isinstance(case.get("bubble"), dict) else {}
    u = inlet.get("velocity") if isinstance(inlet.get("velocity"), (int, float)) else None
    u_mf = bubble.get("u_mf") if isinstance(bubble.get("u_mf"), (int, float)) else 1.8
    bed = num(frm["bed_height_m"]) if "bed_height_m" in frm else np.array([np.nan])
    bed = bed[(ft >= t0) & (ft <= t1)] if bed.size == ft.size else bed
    top = float(np.nanmean(bed)) if np.isfinite(bed).any() else float(np.nanmax(num(bub["centroid_y_m"])))
    heights = [top * k / 4 for k in (1, 2, 3)]
    s = bubble_statistics(bub, frm, t0, t1, u, u_mf, heights=heights, bins=bins, dimension=dimension, g=g)
    if s["samples"] == 0:
        return None, (f"no bubble sample in {why} ({t0:.3g} to {t1:.3g} s)"
                      + (f"; {slug_note(s)}" if s["slug_samples"] else ""))
    s["window"] = why
    s["u"], s["u_mf"], s["g"] = u, u_mf, g
    return s, None


def figure_runs(entries, path):
    """The three panels of figure() with one colour per run: entries are (label, statistics)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.8))
    for k, (label, s) in enumerate(entries):
        c = f"C{k % 10}"
        ok = s["d_count"] > 0
        ax[0].errorbar(s["h"][ok], s["d_mean"][ok], yerr=s["d_std"][ok], fmt="o", ms=4, color=c, label=label)
        if np.isfinite(s["d_corr"]).any():
            ax[0].plot(s["h"], s["d_corr"], "--", color=c, label=f"{correlation_name(s['dimension'])}")
        ok = s["u_count"] > 0
        ax[1].errorbar(s["D"][ok], s["u_mean"][ok], yerr=s["u_std"][ok], fmt="o", ms=4, color=c, label=label)
        ax[1].plot(s["D"], s["u_theory"], "--", color=c,
                   label=f"{rise_constant(s['dimension'])} $\\sqrt{{gD}}$ ({s['dimension']}D)")
        plot_slugs(ax[0], ax[1], s, colour=c, label="slug / plug" if len(entries) == 1 else f"{label}: slug / plug")
        ax[2].plot(s["frequency_height"], s["frequency"], "o-", color=c,
                   label=f"{label}: fraction {s['fraction_mean']:.3g} $\\pm$ {s['fraction_std']:.2g}")
    ax[0].set_xlabel("centroid height above distributor (m)")
    ax[0].set_ylabel("equivalent diameter (m)")
    ax[1].set_xlabel("equivalent diameter D (m)")
    ax[1].set_ylabel("centroid rise velocity (m/s)")
    ax[2].set_xlabel("height above distributor (m)")
    ax[2].set_ylabel("bubble frequency (1/s)")
    ax[2].set_ylim(bottom=0.0)
    for a in ax:
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def table_runs(entries):
    """Markdown lines: per run the window, the samples, the means against the correlations, frequency, fraction."""
    lines = ["| run | window (s) | bubble samples (slugs / plugs set aside) | mean D (m) | correlation D at mean "
             "height (m) | mean u_centroid (m/s) | C sqrt(g D) at mean D (m/s) | frequency (1/s) at heights (m) | "
             "bubble fraction |",
             "|---|---|---|---|---|---|---|---|---|"]
    for label, s in entries:
        h_mean = float(np.nansum(s["h"] * s["d_count"]) / max(np.sum(s["d_count"]), 1))
        corr = (diameter_correlation(s["dimension"], h_mean, s["u"], s["u_mf"], g=s["g"])
                if s["u"] is not None and s["u"] > s["u_mf"] else np.nan)
        theory = rise_constant(s["dimension"]) * np.sqrt(s["g"] * s["d_all_mean"])
        freq = ", ".join(f"{f:.2f} at {h:.2f}" for h, f in zip(s["frequency_height"], s["frequency"]))
        lines.append(f"| {label} | {s['t0']:.3g}-{s['t1']:.3g} ({s['window']}) | {s['samples']} ({slug_note(s)}) | "
                     f"{s['d_all_mean']:.3f} | {corr:.3f} (h = {h_mean:.2f} m, {correlation_name(s['dimension'])}) | "
                     f"{s['u_all_mean']:.2f} | {theory:.2f} (C = {rise_constant(s['dimension'])}) | {freq} | "
                     f"{s['fraction_mean']:.3f} ± {s['fraction_std']:.3f} |")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out_dir")
    ap.add_argument("--t0", type=float)
    ap.add_argument("--t1", type=float)
    ap.add_argument("--u", type=float, help="superficial gas velocity, m/s")
    ap.add_argument("--u-mf", type=float, help="minimum fluidization velocity, m/s")
    ap.add_argument("--a0", type=float, default=0.0, help="distributor area per orifice, m^2")
    ap.add_argument("--h0", type=float, default=0.0, help="2D: height of the equivalent bubble source, m")
    ap.add_argument("--distributor-height", type=float, default=0.0)
    ap.add_argument("--heights", help="comma-separated heights above the distributor for the frequency, m")
    ap.add_argument("--bins", type=int, default=10)
    ap.add_argument("--out", default="bubble_stats.png")
    ap.add_argument("--table", default="bubble_stats.csv")
    a = ap.parse_args()
    bub = read_csv(os.path.join(a.out_dir, "bubbles.csv"))
    frm = read_csv(os.path.join(a.out_dir, "bubble_frames.csv"))
    heights = [float(v) for v in a.heights.split(",")] if a.heights else None
    s = bubble_statistics(bub, frm, a.t0, a.t1, a.u, a.u_mf, a.a0, a.distributor_height, heights, a.bins, h0=a.h0)
    write_table(s, a.table)
    figure(s, a.out)
    print(f"wrote {a.table} and {a.out}: {s['samples']} bubble samples, {slug_note(s)}")


if __name__ == "__main__":
    main()
