#!/usr/bin/env python3
"""Maps of the time-averaged fields of a run (averages.csv, written for the case's [averages] window;
docs/analysis.md, "Time averages"): the mean voidage with the particle-weighted solids velocity as arrows, the
cell-weighted solids velocity's vertical component, and the granular temperature. A 3D run is shown on its
mid-depth layer of cells (k = nz // 2).

Usage: averages.py OUT_DIR [--out FIGURE.png]
"""
import argparse
import csv
import json
import os

import numpy as np


def read_averages(folder):
    """(dict of 2D arrays [j, i], metadata dict) of averages.csv and averages.json; None when absent."""
    path = os.path.join(folder, "averages.csv")
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    if not rows:
        return None
    three_d = "k" in rows[0]
    if three_d:
        nz = max(int(r["k"]) for r in rows) + 1
        rows = [r for r in rows if int(r["k"]) == nz // 2]
    nx = max(int(r["i"]) for r in rows) + 1
    ny = max(int(r["j"]) for r in rows) + 1
    out = {}
    for name in rows[0]:
        a = np.full((ny, nx), np.nan)
        for r in rows:
            a[int(r["j"]), int(r["i"])] = float(r[name]) if r[name] != "" else np.nan
        out[name] = a
    meta = {}
    mpath = os.path.join(folder, "averages.json")
    if os.path.isfile(mpath):
        with open(mpath) as fh:
            meta = json.load(fh)
    meta["dimension"] = 3 if three_d else 2
    return out, meta


def figure(entries, path):
    """One row per run, entries (label, fields, meta): voidage with particle-weighted solids velocity arrows,
    the cell- and particle-weighted vertical solids velocity, the granular temperature."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = len(entries)
    fig, axes = plt.subplots(n, 4, figsize=(13, 4.2 * n), squeeze=False)
    for row, (label, f, meta) in zip(axes, entries):
        x, y = f["x_m"], f["y_m"]
        dx = float(np.nanmean(np.diff(x[0]))) if x.shape[1] > 1 else 1.0
        dy = float(np.nanmean(np.diff(y[:, 0]))) if y.shape[0] > 1 else 1.0
        ext = (np.nanmin(x) - dx / 2, np.nanmax(x) + dx / 2, np.nanmin(y) - dy / 2, np.nanmax(y) + dy / 2)
        im = row[0].imshow(f["voidage"], origin="lower", extent=ext, cmap="cividis", vmin=0.35, vmax=1.0)
        fig.colorbar(im, ax=row[0], shrink=0.8, label="mean voidage")
        step = max(1, f["voidage"].shape[1] // 15)
        u, v = f["us_particle_x_m_s"], f["us_particle_y_m_s"]
        row[0].quiver(x[::step, ::step], y[::step, ::step], u[::step, ::step], v[::step, ::step], color="w",
                      scale=30, width=0.004)
        vmax = float(np.nanmax(np.abs(np.concatenate([f["us_cell_y_m_s"].ravel(), v.ravel()])))) or 1.0
        for ax, name, title in ((row[1], "us_cell_y_m_s", "solids v_y, cell-weighted"),
                                (row[2], "us_particle_y_m_s", "solids v_y, particle-weighted")):
            im = ax.imshow(f[name], origin="lower", extent=ext, cmap="RdBu_r", vmin=-vmax, vmax=vmax)
            fig.colorbar(im, ax=ax, shrink=0.8, label="m/s")
            ax.set_title(title, fontsize=9)
        im = row[3].imshow(f["granular_temperature_m2_s2"], origin="lower", extent=ext, cmap="magma")
        fig.colorbar(im, ax=row[3], shrink=0.8, label="m$^2$/s$^2$")
        row[3].set_title("granular temperature", fontsize=9)
        window = (f"{meta.get('first_sample_s', float('nan')):.3g}-{meta.get('last_sample_s', float('nan')):.3g} s, "
                  f"{meta.get('samples', '?')} samples")
        row[0].set_title(f"{label}: {window}" + (" (mid-depth)" if meta.get("dimension") == 3 else ""), fontsize=9)
        for ax in row:
            ax.set_xlabel("x (m)")
        row[0].set_ylabel("y (m)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out_dir")
    ap.add_argument("--out", default="averages.png")
    a = ap.parse_args()
    got = read_averages(a.out_dir)
    if got is None:
        raise SystemExit(f"{a.out_dir}: no averages.csv (the case has no [averages] window, or the run has not "
                         "reached it)")
    figure([(os.path.basename(os.path.normpath(a.out_dir)), got[0], got[1])], a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
