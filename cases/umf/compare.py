#!/usr/bin/python3
"""The measured U_mf of a run of cases/umf/dem.toml against the closed form of its drag law.

Usage: compare.py RUN_DIR --levels U1 U2 ... --hold S
Prints the bed's weight per area, the voidage of the bed interior at the end of each decreasing-branch hold (the
fields/*.vti voidage of the cells away from the side walls, the distributor row and the surface), and U_mf of the
paper's drag law (Ergun below eps = 0.8, Eqs. 13-14) at the voidage the case's `fluidbed check` assumes (0.43) and
at the measured one: the U at which beta U / eps^2 equals (1 - eps)(rho_s - rho_g) g (docs/model.md).
"""
import argparse
import csv
import os
import re
import struct
import sys
import zlib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "post"))
from umf_sweep import sweep_schedule  # noqa: E402

D, RHO_S, RHO_G, MU, G, WIDTH, CELL = 0.004, 2700.0, 1.205, 1.8e-5, 9.81, 0.16, 0.02


def ergun_umf(eps):
    """Eq. 13 (Ergun) at minimum fluidisation: beta U / eps^2 = (1 - eps)(rho_s - rho_g) g with U = eps w, i.e.
    150 (1-eps) mu U / (eps^3 d^2) + 1.75 rho U^2 / (eps^3 d) = (rho_s - rho_g) g; the positive root."""
    a = 1.75 * RHO_G / (eps ** 3 * D)
    b = 150.0 * (1.0 - eps) * MU / (eps ** 3 * D * D)
    c = (RHO_S - RHO_G) * G
    return (-b + np.sqrt(b * b + 4.0 * a * c)) / (2.0 * a)


def vti_voidage(path):
    """(nx, ny) and the voidage (first appended array, zlib blocks with UInt64 headers) of a fluidbed VTI frame."""
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
    eps = np.frombuffer(data, dtype="<f8")
    return n[0], n[1], eps[:n[0] * n[1]].reshape(n[1], n[0])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run")
    ap.add_argument("--levels", type=float, nargs="+", required=True)
    ap.add_argument("--hold", type=float, required=True)
    a = ap.parse_args()
    with open(os.path.join(a.run, "monitor.csv")) as f:
        first = next(csv.DictReader(f))
    weight = float(first["solids_mass_per_depth_kg_m"]) * G / WIDTH
    print(f"bed weight per area {weight:.1f} Pa (buoyant {weight * (1 - RHO_G / RHO_S):.1f} Pa)")
    print(f"Ergun (Eq. 13) U_mf at eps = 0.43 (fluidbed check): {ergun_umf(0.43):.3f} m/s")
    frames = sorted(os.listdir(os.path.join(a.run, "fields")))
    with open(os.path.join(a.run, "case.toml")) as f:
        interval = float(re.search(r"^interval = ([0-9.e+-]+)", f.read().split("[output]")[1], re.M).group(1))
    for k, (direction, u) in enumerate(sweep_schedule(a.levels)):
        if direction != "down":
            continue
        frame = int(round((k + 1) * a.hold / interval))
        if frame >= len(frames):
            continue
        nx, ny, eps = vti_voidage(os.path.join(a.run, "fields", frames[frame]))
        # Rows fully inside the bed: voidage of every interior cell below 0.6, the distributor row left out.
        rows = [j for j in range(1, ny) if eps[j, 1:nx - 1].max() < 0.6]
        top = max(rows) if rows else 0
        inner = eps[1:top, 1:nx - 1] if top > 2 else eps[1:2, 1:nx - 1]
        e = float(inner.mean())
        print(f"down U = {u:.3g} m/s, t = {(k + 1) * a.hold:.1f} s: interior voidage {e:.4f} (rows 1-{top - 1}, "
              f"sd {inner.std():.4f}), Ergun U_mf there {ergun_umf(e):.3f} m/s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
