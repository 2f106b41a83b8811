#!/usr/bin/env python3
"""post/umf_sweep.py's U_mf from a decreasing curve: synthetic levels dp = min(a U + b U^2, W) (Ergun's form below
U_mf, the bed weight W above) with a = 150 Pa s/m, b = 120 Pa s^2/m^2, W = 800 Pa. Exact: U_mf solves a U + b U^2 =
W, and the fit of the fixed-bed levels is exact for data of its own form, so U_mf is recovered to rounding
(1e-9 relative); noise of 1% on the levels moves it by about 1%, checked within 3%.
Usage (CTest): test_umf_sweep.py FLUIDBED_BINARY SOURCE_DIR"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(sys.argv[2], "post"))
from umf_sweep import umf_from_decreasing  # noqa: E402

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
print("umf sweep: all checks passed" if ok else "FAIL")
sys.exit(0 if ok else 1)
