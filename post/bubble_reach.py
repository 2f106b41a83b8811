#!/usr/bin/env python3
"""How far from a bubble the bed moves: the paper's test of a rheology (Gera et al. 1998, closing remarks: with
kinetic theory the TFM bed responds to a bubble at a greater distance than the DEM's, where "the particles are at
rest until the rising bubble comes to their vicinity").

For each run folder (2D, with fields/*.vti frames holding voidage and solids_velocity) and each instant, on the
frame nearest it:
  - the bubble: the largest connected region (4-neighbours) of cells with voidage above --threshold that does not
    touch the top row (the freeboard);
  - its shape: equivalent diameter sqrt(4 A / pi), aspect ratio height / width of its bounding cells;
  - the reach: among the emulsion cells (voidage below --emulsion) beside and below the bubble (centre below the
    bubble's highest cell), the distance d from a cell's centre to the nearest bubble cell's centre, binned by one
    cell size; the reach is the distance of the first bin, outwards, whose median horizontal solids speed |u_x| is
    below --speed (m/s), the half distance that of the first bin whose median is below half the largest median
    (both searched outwards from the bin of the largest median). Horizontal, because while a jet blows the whole bed above it is
    lifted as a block (in DEM too: the vertical speed is 0.6 m/s everywhere above 0.3 m at 0.2 s): what a bubble does
    to its neighbourhood is to push it aside.
Prints one table (markdown) and, with --csv, writes it.

With --ensemble, the runs are the members of one ensemble (`fluidbed ensemble`): one row per instant with the mean
and sample standard deviation over the members that have a bubble then.

Usage: python3 post/bubble_reach.py RUN [RUN ...] [--label L ...] [--times 0.1 0.2 0.3] [--speed 0.05] [--ensemble]
"""
import argparse
import csv
import os
import sys
from collections import deque

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report import read_pvd  # noqa: E402


def read_frame(path):
    """Voidage eps[j, i], horizontal solids speed |u_x|[j, i] and the cell size of a 2D fields/NNNNNN.vti frame."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy

    r = vtk.vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    ext = img.GetExtent()
    nx, ny = ext[1] - ext[0], ext[3] - ext[2]
    if ext[5] - ext[4] > 0:
        raise SystemExit(f"{path}: a 3D frame; this measure is for the 2D beds")
    data = img.GetCellData()
    eps = vtk_to_numpy(data.GetArray("voidage")).reshape(ny, nx)
    us = data.GetArray("solids_velocity")
    if us is None:
        raise SystemExit(f"{path}: no solids_velocity array")
    u = vtk_to_numpy(us).reshape(ny, nx, -1)
    speed = np.abs(u[..., 0])
    dx, dy, _ = img.GetSpacing()
    return eps, speed, dx, dy


def components(mask):
    """Labels of the 4-connected regions of a boolean array (0: outside), and their count."""
    labels = np.zeros(mask.shape, dtype=int)
    n = 0
    for start in zip(*np.nonzero(mask)):
        if labels[start]:
            continue
        n += 1
        labels[start] = n
        todo = deque([start])
        while todo:
            j, i = todo.popleft()
            for jj, ii in ((j + 1, i), (j - 1, i), (j, i + 1), (j, i - 1)):
                if 0 <= jj < mask.shape[0] and 0 <= ii < mask.shape[1] and mask[jj, ii] and not labels[jj, ii]:
                    labels[jj, ii] = n
                    todo.append((jj, ii))
    return labels, n


def measure(eps, speed, dx, dy, threshold, emulsion, speed_limit):
    labels, n = components(eps > threshold)
    top = set(labels[-1, :]) - {0}
    best, area = 0, 0
    for k in range(1, n + 1):
        if k in top:
            continue
        a = int((labels == k).sum())
        if a > area:
            best, area = k, a
    if best == 0:
        return None
    js, is_ = np.nonzero(labels == best)
    height = (js.max() - js.min() + 1) * dy
    width = (is_.max() - is_.min() + 1) * dx
    diameter = float(np.sqrt(4.0 * area * dx * dy / np.pi))
    # Emulsion cells beside and below the bubble, their distance to its nearest cell.
    bj, bi = js * dy, is_ * dx
    ny, nx = eps.shape
    d, s = [], []
    for j in range(min(js.max() + 1, ny)):
        for i in range(nx):
            if eps[j, i] >= emulsion:
                continue
            d.append(float(np.min(np.hypot(bi - i * dx, bj - j * dy))))
            s.append(float(speed[j, i]))
    d, s = np.array(d), np.array(s)
    h = max(dx, dy)
    medians = []
    for k in range(int(d.max() / h) + 1 if d.size else 0):
        sel = (d >= k * h) & (d < (k + 1) * h)
        medians.append((k * h, float(np.median(s[sel]))) if sel.any() else None)
    medians = [m for m in medians if m is not None]
    # Outwards from the bin of the largest median (the cells touching the bubble may be slower: its base, a wall).
    at = max(range(len(medians)), key=lambda k: medians[k][1]) if medians else 0
    peak = medians[at][1] if medians else 0.0
    reach = next((dist for dist, m in medians[at:] if m < speed_limit), float("nan"))
    half = next((dist for dist, m in medians[at:] if m < 0.5 * peak), float("nan"))
    return {"diameter": diameter, "aspect": height / width, "reach": reach, "half": half, "peak": peak,
            "nose": (js.max() + 1) * dy}


def ensemble(a):
    keys = [("reach", "reach (m)"), ("half", "half distance (m)"), ("peak", "largest median |u_x| (m/s)"),
            ("diameter", "equivalent diameter (m)"), ("aspect", "aspect (h/w)"), ("nose", "top of the bubble (m)")]
    print("| t (s) | members | " + " | ".join(k[1] for k in keys) + " |")
    print("|" + "---|" * (len(keys) + 2))
    for t in a.times:
        values = []
        for run in a.runs:
            frames = read_pvd(os.path.join(run, "fields.pvd"))
            ft, path = min(frames, key=lambda f: abs(f[0] - t))
            m = measure(*read_frame(path), a.threshold, a.emulsion, a.speed)
            if m:
                values.append(m)
        cells = []
        for key, _ in keys:
            v = np.array([m[key] for m in values], dtype=float)
            cells.append(f"{v.mean():.3f} +- {v.std(ddof=1):.3f}" if v.size > 1 else "-")
        print(f"| {t:.2f} | {len(values)} | " + " | ".join(cells) + " |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--label", nargs="*", default=None)
    ap.add_argument("--times", nargs="*", type=float, default=[0.1, 0.2, 0.3])
    ap.add_argument("--threshold", type=float, default=0.8, help="bubble voidage (the bubble tracker's)")
    ap.add_argument("--emulsion", type=float, default=0.6, help="voidage below which a cell is emulsion")
    ap.add_argument("--speed", type=float, default=0.05, help="horizontal solids speed taken as at rest, m/s")
    ap.add_argument("--csv", default=None)
    ap.add_argument("--ensemble", action="store_true", help="the runs are one ensemble: mean and sd per instant")
    a = ap.parse_args()
    labels = a.label if a.label else [os.path.basename(os.path.normpath(r)) for r in a.runs]
    if a.ensemble:
        ensemble(a)
        return
    rows = []
    for run, label in zip(a.runs, labels):
        frames = read_pvd(os.path.join(run, "fields.pvd"))
        if not frames:
            raise SystemExit(f"{run}: no fields.pvd frames")
        for t in a.times:
            ft, path = min(frames, key=lambda f: abs(f[0] - t))
            m = measure(*read_frame(path), a.threshold, a.emulsion, a.speed)
            if m:
                rows.append([label, f"{ft:.2f}", f"{m['reach']:.2f}", f"{m['half']:.2f}", f"{m['peak']:.2f}",
                             f"{m['diameter']:.3f}", f"{m['aspect']:.2f}", f"{m['nose']:.2f}"])
            else:
                rows.append([label, f"{ft:.2f}"] + ["-"] * 6)
    head = ["run", "t (s)", f"reach, median |u_x| < {a.speed:g} m/s (m)", "half distance (m)", "largest median |u_x| (m/s)",
            "equivalent diameter (m)", "aspect (h/w)", "top of the bubble (m)"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for r in rows:
        print("| " + " | ".join(r) + " |")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(head)
            w.writerows(rows)


if __name__ == "__main__":
    main()
