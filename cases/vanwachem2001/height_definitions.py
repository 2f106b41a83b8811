#!/usr/bin/env python3
"""Bed height of the van Wachem et al. (2001) bed by several definitions (issue 32, item 1; README.md, "The bed
height's definition").

The experiment's bed height is what a camera sees of the top of the bed; fluidbed's probe of the validation run is
the height where the cross-section mean solids fraction falls to 0.3. This script puts the definitions side by side
on one run, each with the statistics of the comparison table (mean, standard deviation, 5-95% range, dominant
frequency, period from the upward zero crossings) and bootstrap confidence intervals:

- `bed_height` probes of the run (probes.csv, 1 kHz): the cross-section mean solids fraction falling to 0.3, and to
  the small fractions 0.1 and 0.05 (the highest rows that still hold solids);
- from the particle frames (particles/*.vtu, every output.particle_interval):
  - percentiles of the particles' tops (centre + radius): 95, 99 and 99.5%;
  - a camera's view through the front wall: the particles drawn as their discs (the silhouette a backlit camera
    records through the 8 mm depth) on pixels of `--pixel` m, the image averaged over a square of `--window`
    particle diameters (default 3: a lone particle thrown up darkens 9% of it), and in each pixel column the highest
    pixel whose averaged coverage is at least `--coverage` (default 0.5: half the window dark reads as bed); the
    height is the mean of those column tops over the width.

The confidence intervals are the 5-95% of a circular block bootstrap (post.block_bootstrap; blocks of `--block` s,
longer than an oscillation, so that the resampled series keep their correlation): how far the window's statistics
can be trusted.

Usage: height_definitions.py RUN [--t0 1.0] [--t1 END] [--pixel 2.5e-4] [--coverage 0.5] [--window 3]
                             [--block 0.5] [--json out.json] [--csv heights.csv] [--png figure.png]
(--png needs matplotlib; vtk9's Python module reads the frames: /usr/bin/python3 on the development machine.)
"""
import argparse
import csv
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from post import analyse, block_bootstrap, pvd_frames, read_probes  # noqa: E402


WIDTH = 0.09  # the column's width, m (dem.toml)


def read_frame(path):
    """x, y centres and diameters of a particle frame."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    o = r.GetOutput()
    pts = vtk_to_numpy(o.GetPoints().GetData())
    d = vtk_to_numpy(o.GetPointData().GetArray("diameter"))
    return pts[:, 0], pts[:, 1], d


def camera_height(x, y, d, pixel, coverage, window=3.0, height=0.54):
    """Mean over the pixel columns of the highest pixel whose coverage, averaged over a square of `window`
    diameters, is at least `coverage` (the particles drawn as discs of their diameter in the x-y plane). A lone
    disc darkens pi / (4 window^2) of its window (0.09 at 3 diameters), so particles thrown above the bed do not
    read as bed; a packing does."""
    nx, ny = int(round(WIDTH / pixel)), int(round(height / pixel))
    img = np.zeros((ny, nx), dtype=np.uint8)
    r = 0.5 * float(np.max(d))
    k = int(np.ceil(r / pixel))
    oi, oj = np.meshgrid(np.arange(-k, k + 1), np.arange(-k, k + 1))
    ci, cj = np.floor(x / pixel).astype(int), np.floor(y / pixel).astype(int)
    for di, dj in zip(oi.ravel(), oj.ravel()):
        # pixel centre against each disc (all discs of one size here; the largest radius is a safe bound)
        pi, pj = ci + di, cj + dj
        px, py = (pi + 0.5) * pixel, (pj + 0.5) * pixel
        inside = ((px - x) ** 2 + (py - y) ** 2 <= (0.5 * d) ** 2) & (pi >= 0) & (pi < nx) & (pj >= 0) & (pj < ny)
        img[pj[inside], pi[inside]] = 1
    # box average over `window` diameters: cumulative sums along both axes
    w = max(1, int(round(window * float(np.median(d)) / pixel)))
    c = np.cumsum(np.cumsum(np.pad(img.astype(np.float64), ((1, 0), (1, 0))), axis=0), axis=1)
    h = w // 2
    j0 = np.clip(np.arange(ny) - h, 0, ny)
    j1 = np.clip(np.arange(ny) - h + w, 0, ny)
    i0 = np.clip(np.arange(nx) - h, 0, nx)
    i1 = np.clip(np.arange(nx) - h + w, 0, nx)
    area = np.outer(j1 - j0, i1 - i0)
    avg = (c[j1][:, i1] - c[j0][:, i1] - c[j1][:, i0] + c[j0][:, i0]) / np.maximum(area, 1)
    dark = avg >= coverage
    has = dark.any(axis=0)
    top = np.where(has, ny - 1 - np.argmax(dark[::-1, :], axis=0), -1)
    return float(np.mean(np.where(has, (top + 1) * pixel, 0.0)))


def statistics(t, x, t0, t1, block_s, segment_s=2.0):
    """post.analyse's statistics, and the 5-95% range with its bootstrap interval."""
    r = analyse(t, x, t0, t1, segment_s, block_s)
    y, fs = r["signal"], r["fs_Hz"]
    q05, q95 = np.percentile(y, [5, 95])
    r["range_5_95"] = float(q95 - q05)
    r["range_ci"] = block_bootstrap(y, fs, block_s, lambda z: float(np.subtract(*np.percentile(z, [95, 5]))))
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("--t0", type=float, default=1.0)
    ap.add_argument("--t1", type=float, default=float("inf"))
    ap.add_argument("--pixel", type=float, default=2.5e-4, help="camera pixel, m (default 0.25 mm)")
    ap.add_argument("--coverage", type=float, default=0.5, help="averaged coverage that reads as bed (default 0.5)")
    ap.add_argument("--window", type=float, default=3.0, help="the averaging square's side in diameters (default 3)")
    ap.add_argument("--block", type=float, default=0.5, help="bootstrap block, s (default 0.5)")
    ap.add_argument("--json")
    ap.add_argument("--csv", help="the per-frame heights from the particles")
    ap.add_argument("--png")
    a = ap.parse_args()

    signals = {}
    probes = read_probes(os.path.join(a.run, "probes.csv"))
    for col, label in (("bed_bed_height_m", "cross-section mean solids fraction 0.3 (the validation run's)"),
                       ("bed10_bed_height_m", "cross-section mean solids fraction 0.1"),
                       ("bed05_bed_height_m", "cross-section mean solids fraction 0.05")):
        if col in probes:
            signals[col] = (label, probes["time_s"], probes[col])

    frames = [(t, p) for t, p in pvd_frames(a.run, "particles") if a.t0 - 1e-9 <= t <= a.t1 + 1e-9]
    if frames:
        tt, p95, p99, p995, cam = [], [], [], [], []
        for t, path in frames:
            x, y, d = read_frame(path)
            top = y + 0.5 * d
            q = np.percentile(top, [95, 99, 99.5])
            tt.append(t)
            p95.append(q[0])
            p99.append(q[1])
            p995.append(q[2])
            cam.append(camera_height(x, y, d, a.pixel, a.coverage, a.window))
        tt = np.array(tt)
        signals["top_p95"] = ("95th percentile of the particles' tops", tt, np.array(p95))
        signals["top_p99"] = ("99th percentile of the particles' tops", tt, np.array(p99))
        signals["top_p995"] = ("99.5th percentile of the particles' tops", tt, np.array(p995))
        signals["camera"] = (f"camera through the front wall (coverage {a.coverage:g} over {a.window:g} d, pixel "
                             f"{a.pixel * 1e3:g} mm)",
                             tt, np.array(cam))
        if a.csv:
            with open(a.csv, "w", newline="") as fh:
                w = csv.writer(fh)
                w.writerow(["time_s", "top_p95_m", "top_p99_m", "top_p995_m", "camera_m"])
                for row in zip(tt, p95, p99, p995, cam):
                    w.writerow([f"{v:.7g}" for v in row])

    t1 = min(a.t1, max(float(np.nanmax(s[1])) for s in signals.values()))
    results = {}
    print(f"window {a.t0:g}-{t1:g} s; 90% intervals from a circular block bootstrap ({a.block:g} s blocks)")
    print("| definition | samples | mean (mm) | std (mm) | 5-95% range (mm) | dominant frequency (Hz) | "
          "zero-crossing period (s) |")
    print("|---|---|---|---|---|---|---|")
    for key, (label, t, x) in signals.items():
        r = statistics(t, x, a.t0, t1, a.block)
        results[key] = r
        mm = lambda v: f"{1e3 * v:.1f}"  # noqa: E731
        print(f"| {label} | {r['samples']} at {r['fs_Hz']:.0f} Hz | {mm(r['mean'])} ({mm(r['mean_ci'][0])}-"
              f"{mm(r['mean_ci'][1])}) | {mm(r['std'])} ({mm(r['std_ci'][0])}-{mm(r['std_ci'][1])}) | "
              f"{mm(r['range_5_95'])} ({mm(r['range_ci'][0])}-{mm(r['range_ci'][1])}) | "
              f"{r['dominant_frequency_Hz']:.2f} (bin {r['bin_Hz']:.2f}) | {r['zero_crossing_period_s']:.3f} "
              f"({r['upward_crossings']} crossings) |")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump({k: {q: v for q, v in r.items() if q not in ("signal", "f", "psd")} | {"label": signals[k][0], "t0": a.t0,
                                                                            "t1": t1}
                       for k, r in results.items()}, fh, indent=1)
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(9, 4.4))
        for key, (label, t, x) in signals.items():
            keep = (t >= a.t0) & (t <= t1)
            ax.plot(t[keep], 1e3 * x[keep], lw=0.6, label=label)
        ax.axhline(125.0, color="k", ls="--", lw=0.8, label="experiment's mean (Lethe's digitised signal)")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("bed height (mm)")
        ax.legend(fontsize=6.5, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.png, dpi=90)


if __name__ == "__main__":
    main()
