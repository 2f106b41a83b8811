#!/usr/bin/env python3
"""post/ensemble_compare.py on two synthetic ensembles whose statistics are known by hand.
Base: seeds 1-4 with the nose gas velocity 10, 11, 12, 13 m/s at every instant (mean 11.5, sample sd sqrt(5/3));
new: the same seeds shifted by +0.5 m/s, and a seed 5 that the base lacks (it must be left out). The centroid rise
velocity is 1 m/s in the base and 2 m/s in the new runs, so U_th/U_mf = (gas - U_b) / 1.8 moves by
(0.5 - 1) / 1.8 with sd sqrt(5/3) / 1.8 in both. Detachment: the first row with attached = 0 after a 1, at
0.30 + 0.01 k s for the k-th seed in both (difference 0). The mean difference and z = d / sqrt((s_b^2 + s_n^2) / n)
are exact to round-off.
Usage (CTest): test_ensemble_compare.py FLUIDBED_BINARY SOURCE_DIR"""
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(sys.argv[2], "post"))
from ensemble_compare import table  # noqa: E402

HEAD = "time_s,nose_height_m,rise_velocity_m_s,nose_gas_velocity_m_s,attached,centroid_rise_velocity_m_s\n"
TIMES = [0.2, 0.3, 0.4, 0.5]


def write(folder, seed, gas, u_b, detach):
    d = os.path.join(folder, f"seed-{seed}")
    os.makedirs(d)
    with open(os.path.join(d, "bubble.csv"), "w") as f:
        f.write(HEAD)
        for k in range(61):
            t = round(0.01 * k, 2)
            attached = "1" if 0.05 <= t < detach else "0"
            f.write(f"{t},0.3,1.2,{gas},{attached},{u_b}\n")


failures = 0


def check(name, exact, computed, tol=1e-12):
    global failures
    ok = abs(computed - exact) <= tol * max(1.0, abs(exact))
    failures += not ok
    print(f"{name}: exact {exact:.12g} computed {computed:.12g}", "ok" if ok else "FAIL")


with tempfile.TemporaryDirectory() as tmp:
    base, new = os.path.join(tmp, "base"), os.path.join(tmp, "new")
    for k, seed in enumerate([1, 2, 3, 4]):
        write(base, seed, 10.0 + k, 1.0, 0.30 + 0.01 * k)
        write(new, seed, 10.5 + k, 2.0, 0.30 + 0.01 * k)
    write(new, 5, 99.0, 9.0, 0.45)
    seeds, rows = table(base, new, TIMES, 1.8)
    check("seeds in both", 4, len(seeds))
    sd = math.sqrt(5.0 / 3.0)
    by = {(r[0], r[1]): r for r in rows}
    for t in TIMES:
        n, mb, sb, mn, sn, d, z = by[("nose gas velocity (m/s)", t)][2:]
        check(f"t={t} pairs", 4, n)
        check(f"t={t} gas base mean", 11.5, mb)
        check(f"t={t} gas base sd", sd, sb)
        check(f"t={t} gas difference", 0.5, d)
        check(f"t={t} gas z", 0.5 / math.sqrt(2 * sd**2 / 4), z)
        n, mb, sb, mn, sn, d, z = by[("U_th/U_mf", t)][2:]
        check(f"t={t} U_th/U_mf difference", (0.5 - 1.0) / 1.8, d)
        check(f"t={t} U_th/U_mf sd", sd / 1.8, sn)
    n, mb, sb, mn, sn, d, z = by[("detachment time (s)", None)][2:]
    check("detachment mean", 0.315, mb)
    check("detachment difference", 0.0, d, 1e-9)
sys.exit(1 if failures else 0)
