#!/usr/bin/env python3
"""Spectra and periods of the van Wachem et al. (2001) bed's probes (cases/vanwachem2001/README.md).

Reads RUN/probes.csv, keeps the statistically steady window (default 1 s to the end), and for the relative pressure
at 45 mm (`rel45_dp_Pa`, the tap's cross-section mean less the outlet's) and the bed height (`bed_bed_height_m`)
prints the mean and the standard deviation (each with a 90% interval from a moving-block bootstrap of 0.5 s
blocks, circular), the dominant frequency of the Welch PSD (post/psd.py) and, for the bed
height, the oscillation period twice: 1 / the PSD peak, and the mean spacing of the upward zero crossings of the
detrended, lightly smoothed signal (with hysteresis, so noise about zero does not count as crossings).

Usage: post.py RUN [--t0 1.0] [--t1 END] [--segment 2.0] [--offset S] [--csv spectra.csv] [--png figure.png]
               [--json out.json]
(--offset: subtract S from time_s first, for a run continued at another time step: results/README.md.)
(--png needs matplotlib: /usr/bin/python3 on the development machine.)
"""
import argparse
import csv
import json
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "post"))
from psd import welch_psd  # noqa: E402

SIGNALS = (("rel45_dp_Pa", "relative pressure at 45 mm", "Pa"), ("bed_bed_height_m", "bed height", "m"))


def read_probes(path):
    """Columns of a probes.csv as float arrays (empty cells NaN)."""
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    head, body = rows[0], rows[1:]
    cols = {}
    for k, name in enumerate(head):
        cols[name] = np.array([float(r[k]) if k < len(r) and r[k] != "" else np.nan for r in body])
    return cols


def pvd_frames(run, series):
    """(time, path) of every frame of a run's series ("fields" or "particles"), from RUN/SERIES.pvd."""
    pvd = os.path.join(run, series + ".pvd")
    if not os.path.exists(pvd):
        sys.exit(f"no {series}.pvd in {run}")
    text = open(pvd).read()
    return [(float(t), os.path.join(run, f)) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)]


def uniform(t, x):
    """The signal on a uniform grid of its median sampling interval (probes.csv rows are uniform already, except
    where a restart or the last row lands off the schedule); returns (x, fs)."""
    ok = np.isfinite(t) & np.isfinite(x)
    t, x = t[ok], x[ok]
    dt = float(np.median(np.diff(t)))
    grid = np.arange(t[0], t[-1] + 0.5 * dt, dt)
    return np.interp(grid, t, x), 1.0 / dt


def zero_crossing_period(x, fs, smooth_s=0.02, hysteresis=0.25):
    """Mean period from the upward zero crossings of x detrended (least-squares line removed) and smoothed by a
    moving average of smooth_s seconds. A crossing counts only after the signal has been below -hysteresis x std
    since the last one, so noise about zero adds none. Returns (period_s, crossings); NaN with fewer than two."""
    n = x.size
    tt = np.arange(n) / fs
    y = x - np.polyval(np.polyfit(tt, x, 1), tt)
    w = max(1, int(round(smooth_s * fs)))
    if w > 1:
        y = np.convolve(y, np.ones(w) / w, mode="same")
    band = hysteresis * np.std(y)
    ups, armed = [], False
    for i in range(1, n):
        if y[i] < -band:
            armed = True
        if armed and y[i - 1] < 0.0 <= y[i]:
            ups.append(tt[i - 1] + (tt[i] - tt[i - 1]) * (-y[i - 1]) / (y[i] - y[i - 1]))
            armed = False
    if len(ups) < 2:
        return float("nan"), len(ups)
    return (ups[-1] - ups[0]) / (len(ups) - 1), len(ups)


def block_bootstrap(y, fs, block_s, stat, n=400, seed=1):
    """5% and 95% of `stat` over circular block-bootstrap resamples of y (Politis and Romano 1992): blocks of
    block_s seconds (longer than an oscillation, so that a resample keeps the signal's correlation), starting
    anywhere and wrapping around the window's end so that every sample is drawn alike, until the resample is as long
    as y. How far a window's statistic can be trusted from the oscillations it holds."""
    rng = np.random.default_rng(seed)
    b = max(1, min(int(round(block_s * fs)), y.size // 2))
    nb = int(np.ceil(y.size / b))
    ring = np.concatenate([y, y[:b]])
    vals = [stat(np.concatenate([ring[s:s + b] for s in rng.integers(0, y.size, nb)])[:y.size]) for _ in range(n)]
    return float(np.percentile(vals, 5)), float(np.percentile(vals, 95))


def analyse(t, x, t0, t1, segment_s, block_s=0.5):
    """Mean, std (with block-bootstrap 90% intervals), Welch PSD (segments of segment_s seconds) and dominant
    frequency of x over t0 <= t <= t1."""
    keep = (t >= t0) & (t <= t1)
    y, fs = uniform(t[keep], x[keep])
    nperseg = min(y.size, int(round(segment_s * fs)))
    f, p, f_dom, std = welch_psd(y, fs, nperseg)
    period, crossings = zero_crossing_period(y, fs)
    return {"mean": float(np.mean(y)), "mean_ci": block_bootstrap(y, fs, block_s, np.mean), "std": std,
            "std_ci": block_bootstrap(y, fs, block_s, np.std), "dominant_frequency_Hz": f_dom, "bin_Hz": float(f[1]),
            "psd_period_s": 1.0 / f_dom if f_dom > 0 else float("nan"), "zero_crossing_period_s": period,
            "upward_crossings": crossings, "samples": int(y.size), "fs_Hz": fs, "f": f, "psd": p, "signal": y}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("--t0", type=float, default=1.0, help="start of the analysed window, s (default 1)")
    ap.add_argument("--t1", type=float, default=float("inf"), help="end of the window, s (default: the run's end)")
    ap.add_argument("--segment", type=float, default=2.0, help="Welch segment length, s (bin = 1 / segment)")
    ap.add_argument("--offset", type=float, default=0.0, help="subtract this from time_s, s (default 0)")
    ap.add_argument("--csv", help="write the spectra: frequency_Hz, then one PSD column per signal")
    ap.add_argument("--png", help="time series and spectra, one figure")
    ap.add_argument("--json", help="the numbers printed, as JSON")
    a = ap.parse_args()
    cols = read_probes(os.path.join(a.run, "probes.csv"))
    t = cols["time_s"] - a.offset
    t1 = min(a.t1, float(np.nanmax(t)))
    results = {}
    for name, label, unit in SIGNALS:
        if name not in cols:
            print(f"{name}: not in probes.csv")
            continue
        r = analyse(t, cols[name], a.t0, t1, a.segment)
        results[name] = r
        print(f"{label} ({name}), {a.t0:g}-{t1:g} s, {r['samples']} samples at {r['fs_Hz']:.0f} Hz: "
              f"mean {r['mean']:.6g} {unit} (90%: {r['mean_ci'][0]:.6g}-{r['mean_ci'][1]:.6g}), std {r['std']:.4g} "
              f"{unit} (90%: {r['std_ci'][0]:.4g}-{r['std_ci'][1]:.4g}), dominant frequency "
              f"{r['dominant_frequency_Hz']:.3f} Hz (bin {r['bin_Hz']:.3f} Hz), period from the PSD peak "
              f"{r['psd_period_s']:.3f} s, from {r['upward_crossings']} upward zero crossings "
              f"{r['zero_crossing_period_s']:.3f} s")
    if not results:
        sys.exit("no analysable probe column")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump({k: {q: v for q, v in r.items() if q not in ("f", "psd", "signal")} | {"t0": a.t0, "t1": t1}
                       for k, r in results.items()}, fh, indent=1)
    if a.csv:
        n = min(r["f"].size for r in results.values())
        first = next(iter(results.values()))
        with open(a.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["frequency_Hz"] + [f"psd_{k}" for k in results])
            for i in range(n):
                w.writerow([f"{first['f'][i]:.6g}"] + [f"{r['psd'][i]:.6g}" for r in results.values()])
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(len(results), 2, figsize=(9, 2.6 * len(results)), squeeze=False)
        for row, (name, r) in enumerate(results.items()):
            label, unit = next((lb, u) for n_, lb, u in SIGNALS if n_ == name)
            scale, unit = (1e3, "mm") if unit == "m" else (1.0, unit)
            tt = a.t0 + np.arange(r["samples"]) / r["fs_Hz"]
            axes[row, 0].plot(tt, r["signal"] * scale, lw=0.5)
            axes[row, 0].set_ylabel(f"{label} ({unit})")
            axes[row, 0].set_xlabel("time (s)")
            keep = (r["f"] > 0) & (r["f"] <= 20.0)
            axes[row, 1].semilogy(r["f"][keep], r["psd"][keep] * scale**2, lw=0.9)
            axes[row, 1].axvline(r["dominant_frequency_Hz"], color="0.5", ls="--", lw=0.8)
            axes[row, 1].set_xlabel("frequency (Hz)")
            axes[row, 1].set_ylabel(f"PSD ({unit}$^2$/Hz)")
            axes[row, 1].set_title(f"dominant {r['dominant_frequency_Hz']:.2f} Hz, std {r['std'] * scale:.3g} {unit}",
                                   fontsize=9)
            for ax in axes[row]:
                ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.png, dpi=90)


if __name__ == "__main__":
    main()
