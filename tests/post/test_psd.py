#!/usr/bin/env python3
"""post/psd.py on a synthetic signal: x = A sin(2 pi f0 t) + white noise of standard deviation sigma.
Exact: the dominant frequency is f0, so the peak bin is within one bin (fs / nperseg) of it; the power of the sine,
A^2 / 2, is the integral of the PSD over the peak (the Hann window spreads it over +-2 bins, +-6 taken) less the
noise floor there (density 2 sigma^2 / fs); its error is the scatter of the averaged periodogram, about
1 / sqrt(segments) of the floor over the band (~0.1% here), so 3% on the amplitude is a loose bound that still fails
for a wrong window normalisation (Hann: a factor 8/3 in power) or a two-sided density (factor 2).
The integral of the whole PSD is the variance (Parseval), within 3%.
Usage (CTest): test_psd.py FLUIDBED_BINARY SOURCE_DIR"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(sys.argv[2], "post"))
from psd import welch_psd  # noqa: E402

fs, n, nperseg = 200.0, 1 << 15, 1024
amp, f0, sigma = 2.0, 7.3, 0.5
rng = np.random.default_rng(15)
t = np.arange(n) / fs
x = amp * np.sin(2 * np.pi * f0 * t) + sigma * rng.standard_normal(n) + 101325.0
f, p, f_dom, std = welch_psd(x, fs, nperseg)
df = f[1] - f[0]
k = int(np.argmax(p[1:])) + 1
band = slice(k - 6, k + 7)
floor = 2 * sigma**2 / fs
power = np.sum(p[band]) * df - floor * df * (band.stop - band.start)
amp_psd = np.sqrt(2 * power)
total = np.sum(p) * df
failures = 0


def check(name, exact, computed, tol):
    global failures
    err = abs(computed - exact)
    ok = err <= tol
    failures += not ok
    print(f"{name}: exact {exact:.6g} computed {computed:.6g} error {err:.3g} tolerance {tol:.3g}",
          "ok" if ok else "FAIL")


check("dominant frequency (Hz)", f0, f_dom, df)
check("amplitude from the integrated PSD", amp, amp_psd, 0.03 * amp)
check("integral of the PSD = variance", np.var(x), total, 0.03 * np.var(x))
check("standard deviation", np.sqrt(amp**2 / 2 + sigma**2), std, 0.03 * std)
check("frequency bin (Hz)", fs / nperseg, df, 1e-12)
sys.exit(1 if failures else 0)
