#!/usr/bin/env python3
"""Power spectral density of a pressure (or any) probe signal by Welch's method (Welch 1967, IEEE Trans. Audio
Electroacoust. 15:70): Hann-windowed segments overlapping by half, each with its mean removed, periodograms
averaged; one-sided, density in unit^2/Hz, so that the integral over 0..fs/2 is the variance of the signal.

Usage as a module: f, p, f_dom, std = welch_psd(x, fs[, nperseg]).
Usage as a script:  psd.py PROBE.csv --column NAME [--time time_s] [--nperseg N] [--out psd.png]
"""
import argparse
import csv

import numpy as np


def welch_psd(x, fs, nperseg=None):
    """Frequencies (Hz), one-sided PSD (unit^2/Hz), dominant frequency (the largest PSD above 0 Hz) and the standard
    deviation of x (about its mean). nperseg defaults to the largest power of two not above len(x) / 4 (at least 8
    segments with the overlap); the frequency bin is fs / nperseg."""
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or x.size < 8:
        raise ValueError("welch_psd: need a 1D signal of at least 8 samples")
    if not fs > 0:
        raise ValueError("welch_psd: the sampling rate must be positive")
    if nperseg is None:
        nperseg = 1 << max(3, int(np.floor(np.log2(x.size / 4))))
    nperseg = int(min(nperseg, x.size))
    step = nperseg // 2
    # Periodic Hann window: with 50% overlap its squares sum to a constant, so every sample weighs the same.
    w = 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(nperseg) / nperseg)
    scale = 1.0 / (fs * np.sum(w * w))
    starts = range(0, x.size - nperseg + 1, step)
    p = np.zeros(nperseg // 2 + 1)
    for s in starts:
        seg = x[s:s + nperseg]
        spec = np.fft.rfft(w * (seg - seg.mean()))
        p += np.abs(spec) ** 2
    p *= scale / len(starts)
    # One-sided: negative frequencies folded onto positive ones; 0 Hz and the Nyquist bin have no mirror.
    p[1:] *= 2.0
    if nperseg % 2 == 0:
        p[-1] /= 2.0
    f = np.fft.rfftfreq(nperseg, 1.0 / fs)
    f_dom = f[1 + int(np.argmax(p[1:]))] if p.size > 1 else 0.0
    return f, p, float(f_dom), float(np.std(x))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("--column", required=True)
    ap.add_argument("--time", default="time_s")
    ap.add_argument("--nperseg", type=int)
    ap.add_argument("--out", default="psd.png")
    a = ap.parse_args()
    with open(a.csv, newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r[a.column] != ""]
    t = np.array([float(r[a.time]) for r in rows])
    x = np.array([float(r[a.column]) for r in rows])
    fs = (t.size - 1) / (t[-1] - t[0])
    f, p, f_dom, std = welch_psd(x, fs, a.nperseg)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogy(f[1:], p[1:])
    ax.axvline(f_dom, color="0.5", ls="--", lw=0.8)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel(f"PSD of {a.column} (unit$^2$/Hz)")
    ax.set_title(f"dominant {f_dom:.3g} Hz, std {std:.3g}")
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"dominant_frequency_Hz={f_dom:.6g} std={std:.6g} bin_Hz={f[1]:.6g}")


if __name__ == "__main__":
    main()
