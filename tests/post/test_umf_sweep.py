#!/usr/bin/env python3
"""post/umf_sweep.py's U_mf from a decreasing curve: synthetic levels dp = min(a U + b U^2, W) (Ergun's form below
U_mf, the bed weight W above) with a = 150 Pa s/m, b = 120 Pa s^2/m^2, W = 800 Pa. Exact: U_mf solves a U + b U^2 =
W, and the fit of the fixed-bed levels is exact for data of its own form, so U_mf is recovered to rounding
(1e-9 relative); noise of 1% on the levels moves it by about 1%, checked within 3%; a fluidised level whose mean lands
above the top level's stays on the plateau (exact). The one-run form: the stepped
inlet table (`stepped_table`) holds each level of the sweep over its own interval, so a synthetic monitor.csv whose
pressure drop is that curve at the table's velocity, read back by `analyse_run`, gives every hold its level's dp and
the same U_mf to rounding.
Usage (CTest): test_umf_sweep.py FLUIDBED_BINARY SOURCE_DIR"""
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(sys.argv[2], "post"))
from umf_sweep import analyse_run, stepped_table, sweep_schedule, umf_from_decreasing  # noqa: E402

a, b, w = 150.0, 120.0, 800.0
exact = (-a + np.sqrt(a * a + 4 * b * w)) / (2 * b)
u = np.array([0.4, 0.8, 1.2, 1.6, 2.4, 3.0, 3.6])
dp = np.minimum(a * u + b * u ** 2, w)
got = umf_from_decreasing(u, dp)[0]
print(f"U_mf exact {exact:.12g} computed {got:.12g} error {got - exact:.3g}")
ok = abs(got - exact) <= 1e-9 * exact
noisy = dp * (1 + 0.01 * np.random.default_rng(7).standard_normal(u.size))
got_n = umf_from_decreasing(u, noisy)[0]
print(f"U_mf with 1% noise: exact {exact:.6g} computed {got_n:.6g} error {got_n - exact:.3g}")
ok = ok and abs(got_n - exact) <= 0.03 * exact
# A fluidised level whose mean lands 20% above the top level's (a slug passing) stays on the plateau: the plateau is
# the mean of the three fluidised levels, 1.067 W, and the fixed-bed fit keeps only fixed levels (exact again).
high = dp.copy()
high[u == 3.0] = 1.2 * w
plateau = np.mean(high[u >= 2.4])
exact_h = (-a + np.sqrt(a * a + 4 * b * plateau)) / (2 * b)
got_h = umf_from_decreasing(u, high)[0]
print(f"U_mf with a fluidised level 20% high: exact {exact_h:.12g} computed {got_h:.12g} error {got_h - exact_h:.3g}")
ok = ok and abs(got_h - exact_h) <= 1e-9 * exact_h

# One run driven by the stepped table: monitor.csv sampled every 2 ms, dp of the velocity the table gives.
hold, ramp = 0.4, 0.05
times, vels = stepped_table(u, hold, ramp)
ok = ok and times[0] == 0.0 and abs(times[-1] - hold * len(sweep_schedule(u))) < 1e-12
with tempfile.TemporaryDirectory() as run:
    t = np.arange(0.0, times[-1] + 1e-9, 0.002)
    ut = np.interp(t, times, vels)
    with open(os.path.join(run, "monitor.csv"), "w") as f:
        f.write("time_s,pressure_drop_Pa\n")
        f.writelines(f"{tt!r},{min(a * v + b * v * v, w)!r}\n" for tt, v in zip(t, ut))
    res = analyse_run(run, u, hold)
levels_ok = all(abs(m - min(a * uu + b * uu ** 2, w)) < 1e-9 * w and s < 1e-9 * w for _, uu, _, _, m, s in res)
down = [(uu, m) for d, uu, _, _, m, _ in res if d == "down"] + [(u.max(), res[len(u) - 1][4])]
got_r = umf_from_decreasing([x for x, _ in down], [m for _, m in down])[0]
print(f"U_mf from one tabled run: exact {exact:.12g} computed {got_r:.12g} error {got_r - exact:.3g}; "
      f"{len(res)} holds, each at its level's dp: {levels_ok}")
ok = ok and levels_ok and abs(got_r - exact) <= 1e-9 * exact
print("umf sweep: all checks passed" if ok else "FAIL")
sys.exit(0 if ok else 1)
