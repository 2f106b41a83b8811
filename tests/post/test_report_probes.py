#!/usr/bin/env python3
"""post/report.py on a synthetic probes.csv: a pressure tap p = 5000 + A sin(2 pi f0 t) Pa sampled at uneven steps
(as probes.interval = 0 samples an adaptive TFM step), and a voidage column. Exact: the report's table gives the
mean 5000 Pa, the standard deviation A / sqrt(2) and the dominant frequency f0. Tolerances: the resampling to the
median step is linear interpolation, whose error on a sine sampled 100 times per period is below 1e-3 relative;
the mean over a whole number of periods is exact up to that; the dominant frequency is within one bin fs / nperseg.
probes.png and pressure_psd.png are written.
Usage (CTest): test_report_probes.py FLUIDBED_BINARY SOURCE_DIR"""
import math
import os
import re
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(sys.argv[2], "post"))
import report  # noqa: E402


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


amp, f0, mean = 300.0, 4.0, 5000.0
rng = np.random.default_rng(4)
dt = 1.0 / (100 * f0)
steps = dt * (1.0 + 0.2 * (rng.uniform(size=4000) - 0.5))
t = np.concatenate([[0.0], np.cumsum(steps)])
t = t[t <= 8.0]  # 32 periods
with tempfile.TemporaryDirectory() as tmp:
    run = os.path.join(tmp, "probed")
    os.makedirs(run)
    with open(os.path.join(run, "case.toml"), "w") as f:
        f.write('[case]\nname = "probed"\nmodel = "tfm"\n')
    with open(os.path.join(run, "probes.csv"), "w") as f:
        f.write("time_s,tap_p_Pa,tap_eps\n")
        for ti in t:
            f.write(f"{ti!r},{mean + amp * math.sin(2 * math.pi * f0 * ti)!r},0.5\n")
    out = os.path.join(tmp, "report")
    report.write_report([run], out)
    for name in ("probes.png", "pressure_psd.png"):
        if not os.path.isfile(os.path.join(out, "figures", name)):
            fail(f"no figures/{name}")
    summary = open(os.path.join(out, "summary.md")).read()
    line = next((ln for ln in summary.splitlines() if ln.startswith("| probed | tap_p_Pa |")), None)
    if line is None:
        fail("no pressure-fluctuation row for tap_p_Pa:\n" + summary)
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    got_mean, got_std, got_f, n, fs = float(cells[2]), float(cells[3]), float(cells[4]), int(cells[5]), float(cells[6])
    exact_std = amp / math.sqrt(2)
    nperseg = 1 << int(math.floor(math.log2(n / 4)))
    print(f"mean exact {mean} computed {got_mean} error {got_mean - mean:.3g}")
    print(f"std exact {exact_std:.4f} computed {got_std} error {got_std - exact_std:.3g}")
    print(f"f_dom exact {f0} computed {got_f} error {got_f - f0:.3g} (bin {fs / nperseg:.3g} Hz)")
    if abs(got_mean - mean) > 1.0:
        fail("mean")
    if abs(got_std - exact_std) > 2e-3 * exact_std + 0.05:
        fail("std")
    if abs(got_f - f0) > fs / nperseg:
        fail("dominant frequency")
    if not re.search(r"## Pressure fluctuations", summary):
        fail("no Pressure fluctuations section")
print("report probes: all checks passed")
