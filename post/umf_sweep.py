#!/usr/bin/python3
"""Minimum fluidisation velocity as an experimenter measures it (issue 15, item 7): the superficial velocity is
stepped up and then down, held at each level, and the bed pressure drop averaged over the second half of each
hold; U_mf is where the fixed-bed branch of the decreasing curve (Ergun's a U + b U^2 fitted to the levels below the
plateau) meets the fluidised branch (dp equal to
the bed weight per area, the mean of the plateau levels). The usual procedure (Kunii and Levenspiel 1991, ch. 3):
the decreasing curve, because the increasing one carries the packing's history (overshoot, wall friction).

One run folder: the first level from t = 0, every later level a `--restart` of the previous final checkpoint with
`--set inlet.velocity=U --allow-changed inlet`, so the bed carries over from level to level.

Usage: umf_sweep.py FLUIDBED CASE.toml --out DIR --levels U1 U2 ... [--hold S] [--threads N] [--set K=V ...]
Writes DIR/umf_sweep.csv (direction,u_m_s,t0_s,t1_s,pressure_drop_Pa,std_Pa), DIR/umf_sweep.png and prints U_mf.
"""
import argparse
import csv
import os
import subprocess
import sys

import numpy as np


def hold_mean(monitor, t0, t1):
    """Mean and std of pressure_drop_Pa over the second half of [t0, t1] (the first half lets the bed settle)."""
    with open(monitor) as f:
        rows = list(csv.DictReader(f))
    t = np.array([float(r["time_s"]) for r in rows])
    dp = np.array([float(r["pressure_drop_Pa"]) if r["pressure_drop_Pa"] else np.nan for r in rows])
    sel = (t >= 0.5 * (t0 + t1)) & (t <= t1 + 1e-12) & np.isfinite(dp)
    return float(np.mean(dp[sel])), float(np.std(dp[sel]))


def umf_from_decreasing(u, dp, plateau_tol=0.15):
    """U_mf from the decreasing branch: the fluidised levels are those within plateau_tol of the highest level's
    dp (their mean is the plateau); the fixed-bed levels, the others, are fitted by Ergun's form dp = a U + b U^2
    (viscous and inertial terms; for the paper's 4 mm particles the inertial one dominates, so a line would not
    do); U_mf solves a U + b U^2 = plateau. Returns (U_mf, plateau, a, b) or None when a branch has no level."""
    u, dp = np.asarray(u, float), np.asarray(dp, float)
    top = dp[np.argmax(u)]
    fluid = np.abs(dp - top) <= plateau_tol * abs(top)
    fixed = ~fluid & (u > 0)
    if not fluid.any() or not fixed.any():
        return None
    plateau = float(np.mean(dp[fluid]))
    if fixed.sum() >= 2:
        (a, b), *_ = np.linalg.lstsq(np.column_stack([u[fixed], u[fixed] ** 2]), dp[fixed], rcond=None)
    else:  # one level: the line through it
        a, b = float(dp[fixed][0] / u[fixed][0]), 0.0
    if b > 0:
        umf = (-a + np.sqrt(a * a + 4 * b * plateau)) / (2 * b)
    else:
        umf = plateau / a
    return float(umf), plateau, float(a), float(b)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("fluidbed")
    ap.add_argument("case")
    ap.add_argument("--out", required=True)
    ap.add_argument("--levels", type=float, nargs="+", required=True, help="increasing velocities, m/s")
    ap.add_argument("--hold", type=float, default=0.5, help="s at each level")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--set", action="append", default=[])
    a = ap.parse_args(argv)
    up = sorted(a.levels)
    schedule = [("up", u) for u in up] + [("down", u) for u in reversed(up[:-1])]
    results = []
    t = 0.0
    for k, (direction, u) in enumerate(schedule):
        t1 = t + a.hold
        cmd = [a.fluidbed, "run", a.case, "--out", a.out, "--end-time", repr(t1), "--threads", str(a.threads),
               "--quiet", "--set", f"inlet.velocity={u!r}"]
        for s in a.set:
            cmd += ["--set", s]
        cmd += ["--overwrite"] if k == 0 else ["--restart", os.path.join(a.out, "checkpoints", "final.h5"),
                                               "--allow-changed", "inlet"]
        res = subprocess.run(cmd, capture_output=True, text=True)
        if res.returncode != 0:
            print(f"umf_sweep: level {u} m/s failed (exit {res.returncode}):\n{res.stderr}", file=sys.stderr)
            return res.returncode
        mean, std = hold_mean(os.path.join(a.out, "monitor.csv"), t, t1)
        results.append((direction, u, t, t1, mean, std))
        print(f"{direction:4s} U = {u:.4g} m/s: pressure drop {mean:.1f} +- {std:.1f} Pa")
        t = t1
    with open(os.path.join(a.out, "umf_sweep.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["direction", "u_m_s", "t0_s", "t1_s", "pressure_drop_Pa", "std_Pa"])
        w.writerows([[d, repr(u), repr(t0), repr(t1), repr(m), repr(s)] for d, u, t0, t1, m, s in results])
    # The decreasing curve: the top level (reached going up) and the levels coming down.
    down = [(u, m) for d, u, _, _, m, _ in results if d == "down"] + [(up[-1], results[len(up) - 1][4])]
    fit = umf_from_decreasing([u for u, _ in down], [m for _, m in down])
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    for d, marker in (("up", "^"), ("down", "v")):
        pts = [(u, m, s) for dd, u, _, _, m, s in results if dd == d]
        if pts:
            ax.errorbar([p[0] for p in pts], [p[1] for p in pts], yerr=[p[2] for p in pts], marker=marker, ls="-",
                        capsize=2, label=f"velocity {'increasing' if d == 'up' else 'decreasing'}")
    if fit:
        umf, plateau, ca, cb = fit
        uu = np.linspace(0, umf, 20)
        ax.plot(uu, ca * uu + cb * uu ** 2, "k--", lw=0.8, label="fixed bed, decreasing (a U + b U², fit)")
        ax.axhline(plateau, color="k", ls=":", lw=0.8, label="fluidised, decreasing (mean)")
        ax.axvline(umf, color="C3", lw=0.8, label=f"U_mf = {umf:.3g} m/s")
        print(f"U_mf = {umf:.4g} m/s (plateau {plateau:.1f} Pa, fixed bed {ca:.1f} U + {cb:.1f} U^2 Pa)")
    else:
        print("U_mf: the decreasing curve has no fixed-bed or no fluidised level; widen --levels")
    ax.set_xlabel("superficial gas velocity U (m/s)")
    ax.set_ylabel("bed pressure drop (Pa)")
    ax.set_title("Minimum fluidisation: pressure drop against velocity")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "umf_sweep.png"), dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
