#!/usr/bin/env python3
"""Neighbour-list entries and contacts per particle in the particle frames of a fluidbed DEM run.

For every particle frame of a run folder (the `particles/NNNNNN.vtu` files its `particles.pvd` lists, written by
default; read with post/report.py's readers) this counts

  E  neighbour-list entries per particle: pairs with centre distance < r_i + r_j + skin (surface gap below the
     skin, the test of src/dem/neighbor_list.cpp), counted once for each partner, E = 2 pairs / N;
  C  contacts per particle: pairs with centre distance < r_i + r_j, C = 2 pairs / N;

and prints time, N, E and C per frame and their mean over the frames. 2D runs (discs) use the distance in x, y,
3D runs (spheres) in x, y, z. Walls are not counted. Axes in `domain.periodic` wrap (nearest image, as the
solver does). The skin is the run's `dem.skin` (its case.toml; default half the largest diameter) unless --skin
is given. With the run's monitor.csv the script also prints the neighbour-list builds (column
`neighbor_rebuilds`) over the window of the frames and per DEM step (`dem.time_step`).

Pairs come from scipy.spatial.cKDTree.query_pairs at the largest cutoff (d_max + skin), then each pair is kept
against its own cutoff, so polydisperse beds are exact.

Usage:
  python3 bench/contact_counts.py RUN_DIR [--t-min S] [--t-max S] [--skin M]

RUN_DIR is a `fluidbed run ... --out RUN_DIR` folder. Example:
  build/fluidbed run cases/bench/settle-22k.toml --out /tmp/counts/settle --overwrite --quiet
  python3 bench/contact_counts.py /tmp/counts/settle
"""

import argparse
import csv
import os
import pathlib
import sys
import tomllib

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "post"))
from report import read_pvd, read_vtu  # noqa: E402  (the project's frame readers)

PERIODIC_LENGTH_KEY = {"x": "width", "y": "height", "z": "depth"}


def case_info(run, skin_arg):
    """Dimension, skin, DEM step and periodic lengths (0: not periodic) from the run's case.toml."""
    case = tomllib.loads((run / "case.toml").read_text())
    dim = int(case.get("case", {}).get("dimension", 2))
    d_max = max(s["diameter"] for s in case.get("species", []))
    dem = case.get("dem", {})
    skin = skin_arg if skin_arg is not None else dem.get("skin", 0.5 * d_max)
    domain = case.get("domain", {})
    box = np.zeros(dim)
    for axis in domain.get("periodic", []):
        box["xyz".index(axis)] = domain[PERIODIC_LENGTH_KEY[axis]]
    return dim, float(skin), dem.get("time_step"), box, d_max


def frames(run):
    """Yield (time, centres N x 3, diameters) for each particle frame of the run, in time order."""
    for time, path in read_pvd(str(run / "particles.pvd")):
        f = read_vtu(path)
        if f is not None:
            yield time, np.column_stack([f["x"], f["y"], f["z"]]), f["diameter"]


def count_pairs(xyz, d, skin, box):
    """(list pairs, contact pairs): centre distance below r_i + r_j + skin, and below r_i + r_j."""
    pts = xyz.copy()
    periodic = box > 0
    pts[:, periodic] = np.mod(pts[:, periodic], box[periodic])
    tree = cKDTree(pts, boxsize=box if periodic.any() else None)
    pairs = tree.query_pairs(d.max() + skin, output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    delta = pts[i] - pts[j]
    delta[:, periodic] -= box[periodic] * np.round(delta[:, periodic] / box[periodic])
    dist = np.sqrt((delta * delta).sum(axis=1))
    reach = 0.5 * (d[i] + d[j])
    return int((dist < reach + skin).sum()), int((dist < reach).sum())


def builds(run, t0, t1, dt):
    """List builds between t0 and t1 from monitor.csv's neighbor_rebuilds, and per DEM step; None if absent."""
    path = run / "monitor.csv"
    if not path.exists():
        return None
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r.get("neighbor_rebuilds")]
    if not rows:
        return None
    t = np.array([float(r["time_s"]) for r in rows])
    nb = np.array([float(r["neighbor_rebuilds"]) for r in rows])
    a, b = int(np.argmin(abs(t - t0))), int(np.argmin(abs(t - t1)))
    n = nb[b] - nb[a]
    steps = (t[b] - t[a]) / dt if dt else float("nan")
    return t[a], t[b], n, steps


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("run", type=pathlib.Path, help="output folder of a fluidbed DEM run (--out)")
    p.add_argument("--t-min", type=float, default=-np.inf, help="first frame time to use (s)")
    p.add_argument("--t-max", type=float, default=np.inf, help="last frame time to use (s)")
    p.add_argument("--skin", type=float, help="skin (m); default the run's dem.skin")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    dim, skin, dt, box, d_max = case_info(args.run, args.skin)
    periodic = ", ".join("xyz"[k] for k in range(dim) if box[k] > 0) or "none"
    print(f"# run {args.run}: {dim}D, skin {skin:.6g} m ({skin / d_max:.3g} d_max), periodic: {periodic}")
    print(f"{'time_s':>10} {'N':>7} {'E':>8} {'C':>8}")
    rows = []
    for time, xyz, d in frames(args.run):
        if not args.t_min - 1e-12 <= time <= args.t_max + 1e-12:
            continue
        n_list, n_contact = count_pairs(xyz[:, :dim], d, skin, box)
        n = len(d)
        rows.append((time, n, 2 * n_list / n, 2 * n_contact / n))
        print(f"{time:10.4f} {n:7d} {rows[-1][2]:8.3f} {rows[-1][3]:8.3f}")
    if not rows:
        sys.exit("no particle frames in the time window")
    e, c = np.array([r[2] for r in rows]), np.array([r[3] for r in rows])
    print(f"{'mean':>10} {'':>7} {e.mean():8.3f} {c.mean():8.3f}   ({len(rows)} frames; "
          f"E {e.min():.3f}-{e.max():.3f}, C {c.min():.3f}-{c.max():.3f})")
    b = builds(args.run, rows[0][0], rows[-1][0], dt)
    if b:
        t0, t1, n, steps = b
        print(f"# list builds {t0:.4g}-{t1:.4g} s: {n:.0f} over {steps:.0f} DEM steps "
              f"(dt {dt}), {n / steps:.4g} a step")


if __name__ == "__main__":
    main()
