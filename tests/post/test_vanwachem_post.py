#!/usr/bin/env python3
"""cases/vanwachem2001/post.py on a synthetic probes.csv at 1 kHz, 0-6 s: relative pressure
p = 300 + 120 sin(2 pi 2.2 t) Pa, bed height h = 0.12 + 0.2e-3 t + 0.015 sin(2 pi 2.8 t + 1) + 0.002 sin(2 pi 17 t)
m, both with white noise (5 Pa, 0.5 mm), and a start-up (0-1 s) unlike the rest that the window must leave out.
Exact over 1-6 s: the dominant frequencies 2.2 and 2.8 Hz, within one bin (0.5 Hz with 2 s segments); the
bed-height period 1 / 2.8 s from the zero crossings of the detrended signal, whose error is the noise's jitter of
the crossing times (noise / slope ~ 2 ms, averaged over 13 periods: ~0.2 ms, 0.05%), so 1% fails a miscount of
one crossing (7%) or a drift left in (the 17 Hz ripple and the 0.2 mm/s drift are there to cause those); the
standard deviations sqrt(A^2/2 + noise^2 (+ ripple^2/2)) within 3%, the means within 1%.
Usage (CTest): test_vanwachem_post.py FLUIDBED_BINARY SOURCE_DIR"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

script = os.path.join(sys.argv[2], "cases", "vanwachem2001", "post.py")
rng = np.random.default_rng(2001)
t = np.arange(6001) * 1e-3
p = 300 + 120 * np.sin(2 * np.pi * 2.2 * t) + 5 * rng.standard_normal(t.size)
h = (0.12 + 0.2e-3 * t + 0.015 * np.sin(2 * np.pi * 2.8 * t + 1) + 0.002 * np.sin(2 * np.pi * 17 * t)
     + 0.5e-3 * rng.standard_normal(t.size))
start = t < 1.0
p[start], h[start] = 800.0, 0.09  # the start-up: a plug, no oscillation
failures = 0


def check(name, exact, computed, tol):
    global failures
    err = abs(computed - exact)
    ok = err <= tol
    failures += not ok
    print(f"{name}: exact {exact:.6g} computed {computed:.6g} error {err:.3g} tolerance {tol:.3g}",
          "ok" if ok else "FAIL")


with tempfile.TemporaryDirectory() as tmp:
    with open(os.path.join(tmp, "probes.csv"), "w") as f:
        f.write("time_s,rel45_dp_Pa,tap45_p_Pa,bed_bed_height_m\n")
        for row in zip(t, p, p, h):
            f.write(",".join(repr(float(v)) for v in row) + "\n")
    out = os.path.join(tmp, "out.json")
    subprocess.run([sys.executable, script, tmp, "--t0", "1", "--json", out, "--csv", os.path.join(tmp, "s.csv")],
                   check=True)
    r = json.load(open(out))
    rp, rh = r["rel45_dp_Pa"], r["bed_bed_height_m"]
    check("relative pressure: dominant frequency (Hz)", 2.2, rp["dominant_frequency_Hz"], rp["bin_Hz"])
    check("relative pressure: mean (Pa)", 300.0, rp["mean"], 3.0)
    check("relative pressure: std (Pa)", np.sqrt(120**2 / 2 + 25), rp["std"], 0.03 * rp["std"])
    check("bed height: dominant frequency (Hz)", 2.8, rh["dominant_frequency_Hz"], rh["bin_Hz"])
    check("bed height: period from zero crossings (s)", 1 / 2.8, rh["zero_crossing_period_s"], 0.01 / 2.8)
    check("bed height: period from the PSD peak (s)", 1 / 2.8, rh["psd_period_s"],
          1 / (2.8 - rh["bin_Hz"]) - 1 / 2.8)
    check("bed height: mean (m)", 0.12 + 0.2e-3 * 3.5, rh["mean"], 0.0012)
    exact_std = np.sqrt(0.015**2 / 2 + 0.002**2 / 2 + 0.5e-3**2 + (0.2e-3 * 5) ** 2 / 12)
    check("bed height: std (m)", exact_std, rh["std"], 0.03 * exact_std)
    check("samples in 1-6 s", 5001, rh["samples"], 0)
    # The block-bootstrap intervals (0.5 s blocks, a period of 0.45 s and 0.36 s) hold the exact values.
    for name, r_, mean, std in (("relative pressure", rp, 300.0, np.sqrt(120**2 / 2 + 25)),
                                ("bed height", rh, 0.12 + 0.2e-3 * 3.5, exact_std)):
        for q, exact in (("mean", mean), ("std", std)):
            lo, hi = r_[q + "_ci"]
            inside = lo <= exact <= hi and lo <= r_[q] <= hi
            failures += not inside
            print(f"{name}: {q} 90% interval {lo:.6g}-{hi:.6g} holds {exact:.6g}", "ok" if inside else "FAIL")
    lines = open(os.path.join(tmp, "s.csv")).read().splitlines()
    check("spectra.csv: header and 1001 bins", 1002, len(lines), 0)
    assert lines[0] == "frequency_Hz,psd_rel45_dp_Pa,psd_bed_bed_height_m", lines[0]
sys.exit(1 if failures else 0)
