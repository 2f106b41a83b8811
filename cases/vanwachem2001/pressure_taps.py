#!/usr/bin/env python3
"""Where the relative pressure at 45 mm is read (issue 32, item 1; README.md, "The pressure tap").

The validation run's probe is the cross-section mean at 45 mm less the outlet's (`rel45_dp_Pa`). An experimenter's
tap is one hole: in a side wall, or in the front wall at some point of the width. This script reads the field frames
(fields/*.vti, every output.interval) and gives the relative pressure at 45 mm as each tap would read it, the gas
pressure interpolated linearly in height between the cell centres around 45 mm, less the mean of the top row:

- `side wall`: the cells along the left side wall (x = h/2), the depth's mean;
- `centre line`: the two cells about the centre line (x = 45 mm), the depth's mean;
- `front wall, centre`: the same two cells, front layer only (z = h_z/2);
- `cross-section mean`: every cell of the row (the run's probe, as a check at the frames' rate).

For each: mean, standard deviation (with a 90% circular block-bootstrap interval) and the dominant frequency.

Usage: pressure_taps.py RUN [--t0 1.0] [--t1 END] [--height 0.045] [--json out.json]
(vtk9's Python module reads the frames: /usr/bin/python3 on the development machine.)
"""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from post import analyse, pvd_frames  # noqa: E402


def pressure(path):
    """The cell pressure as an array [k, j, i] (z, y, x) and the cell sizes."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    r = vtk.vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    o = r.GetOutput()
    nx, ny, nz = (max(1, d - 1) for d in o.GetDimensions())
    p = vtk_to_numpy(o.GetCellData().GetArray("pressure")).reshape(nz, ny, nx)
    return p, o.GetSpacing()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("--t0", type=float, default=1.0)
    ap.add_argument("--t1", type=float, default=float("inf"))
    ap.add_argument("--height", type=float, default=0.045)
    ap.add_argument("--json")
    a = ap.parse_args()
    taps = {"side wall": [], "centre line": [], "front wall, centre": [], "cross-section mean": []}
    times = []
    for t, path in pvd_frames(a.run, "fields"):
        if not a.t0 - 1e-9 <= t <= a.t1 + 1e-9:
            continue
        p, (hx, hy, _) = pressure(path)
        nz, ny, nx = p.shape
        s = min(max(a.height / hy - 0.5, 0.0), ny - 1.0)
        j0 = min(int(s), ny - 2)
        w = s - j0
        row = (1.0 - w) * p[:, j0, :] + w * p[:, j0 + 1, :]  # [k, i] at the tap height
        top = float(np.mean(p[:, ny - 1, :]))
        mid = [nx // 2 - 1, nx // 2] if nx % 2 == 0 else [nx // 2]
        times.append(t)
        taps["side wall"].append(float(np.mean(row[:, 0])) - top)
        taps["centre line"].append(float(np.mean(row[:, mid])) - top)
        taps["front wall, centre"].append(float(np.mean(row[0, mid])) - top)
        taps["cross-section mean"].append(float(np.mean(row)) - top)
    times = np.array(times)
    out = {}
    print(f"relative pressure at {a.height * 1e3:g} mm from {times.size} field frames, "
          f"{times[0]:g}-{times[-1]:g} s")
    print("| tap | mean (Pa) | std (Pa), 90% interval | dominant frequency (Hz) | zero-crossing period (s) |")
    print("|---|---|---|---|---|")
    for name, v in taps.items():
        r = analyse(times, np.array(v), times[0], times[-1], 2.0)
        out[name] = {k: r[k] for k in ("mean", "std", "std_ci", "dominant_frequency_Hz", "zero_crossing_period_s")}
        print(f"| {name} | {r['mean']:.1f} | {r['std']:.1f} ({r['std_ci'][0]:.1f}-{r['std_ci'][1]:.1f}) | "
              f"{r['dominant_frequency_Hz']:.2f} | {r['zero_crossing_period_s']:.3f} |")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(out, fh, indent=1)


if __name__ == "__main__":
    main()
