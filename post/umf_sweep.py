#!/usr/bin/python3
"""Minimum fluidisation velocity as an experimenter measures it (issue 15, item 7): the superficial velocity is
stepped up and then down, held at each level, and the bed pressure drop averaged over the second half of each
hold; U_mf is where the fixed-bed branch of the decreasing curve (Ergun's a U + b U^2 fitted to the levels below the
plateau) meets the fluidised branch (dp equal to
the bed weight per area, the mean of the plateau levels). The usual procedure (Kunii and Levenspiel 1991, ch. 3):
the decreasing curve, because the increasing one carries the packing's history (overshoot, wall friction).

One run folder: the first level from t = 0, every later level a `--restart` of the previous final checkpoint with
`--set inlet.velocity=U --allow-changed inlet`, so the bed carries over from level to level.

Or one run with the whole sweep as the inlet's table schedule (`inlet.schedule = "table"`, no restarts):
`--write-table FILE` writes the stepped table (each level reached by a linear ramp of `--ramp` seconds at the
start of its hold), the case names it in `inlet.table_file`, and `--analyse RUN_DIR` reads that run's monitor.csv
with the same `--levels`, `--hold` and `--ramp`.

Usage: umf_sweep.py FLUIDBED CASE.toml --out DIR --levels U1 U2 ... [--hold S] [--threads N] [--set K=V ...]
       umf_sweep.py --write-table FILE --levels U1 U2 ... [--hold S] [--ramp S]
       umf_sweep.py --analyse RUN_DIR --levels U1 U2 ... [--hold S] [--ramp S] [--out DIR]
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
    """U_mf from the decreasing branch: the fluidised levels are those whose dp is at least (1 - plateau_tol)
    times the highest level's (their mean is the plateau; one-sided, since a bubbling or slugging level whose mean
    lands above the top level's is still fluidised, while a fixed bed below U_mf carries less than its weight); the
    fixed-bed levels, the others, are fitted by Ergun's form dp = a U + b U^2 (viscous and inertial terms; for the
    paper's 4 mm particles the inertial one dominates, so a line would not do); U_mf solves a U + b U^2 = plateau.
    Returns (U_mf, plateau, a, b) or None when a branch has no level."""
    u, dp = np.asarray(u, float), np.asarray(dp, float)
    top = dp[np.argmax(u)]
    fluid = dp >= (1.0 - plateau_tol) * top
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


def sweep_schedule(levels):
    """The levels in the order of the sweep: up through the sorted levels, then down again (the top one once)."""
    up = sorted(levels)
    return [("up", u) for u in up] + [("down", u) for u in reversed(up[:-1])]


def stepped_table(levels, hold, ramp):
    """(times, velocities) of the inlet table that holds each level of the sweep for `hold` seconds, reaching it
    from the previous level by a linear ramp over the first `ramp` seconds (a table is linear between its points)."""
    times, vels = [0.0], [sweep_schedule(levels)[0][1]]
    for k, (_, u) in enumerate(sweep_schedule(levels)):
        if k > 0:
            times.append(round(k * hold + ramp, 9))
            vels.append(u)
        times.append(round((k + 1) * hold, 9))
        vels.append(u)
    return times, vels


def analyse_run(run_dir, levels, hold):
    """The hold means of one run driven by stepped_table: level k of the sweep holds over [k hold, (k + 1) hold]."""
    mon = os.path.join(run_dir, "monitor.csv")
    return [(d, u, k * hold, (k + 1) * hold) + hold_mean(mon, k * hold, (k + 1) * hold)
            for k, (d, u) in enumerate(sweep_schedule(levels))]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("fluidbed", nargs="?")
    ap.add_argument("case", nargs="?")
    ap.add_argument("--out")
    ap.add_argument("--levels", type=float, nargs="+", required=True, help="increasing velocities, m/s")
    ap.add_argument("--hold", type=float, default=0.5, help="s at each level")
    ap.add_argument("--ramp", type=float, default=0.05, help="s to reach each level (--write-table)")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--write-table", metavar="FILE", help="write the sweep as an inlet table CSV and stop")
    ap.add_argument("--analyse", metavar="RUN_DIR", help="analyse a run of a case with that table")
    a = ap.parse_args(argv)
    if a.write_table:
        with open(a.write_table, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["time_s", "velocity_m_s"])
            w.writerows(zip(*stepped_table(a.levels, a.hold, a.ramp)))
        return 0
    up = sorted(a.levels)
    if a.analyse:
        a.out = a.out or a.analyse
        results = analyse_run(a.analyse, a.levels, a.hold)
        for direction, u, _, _, mean, std in results:
            print(f"{direction:4s} U = {u:.4g} m/s: pressure drop {mean:.1f} +- {std:.1f} Pa")
    else:
        if not (a.fluidbed and a.case and a.out):
            ap.error("FLUIDBED, CASE and --out are needed (or --write-table / --analyse)")
        results = run_levels(a)
        if results is None:
            return 1
    write_and_plot(a.out, up, results)
    return 0


def run_levels(a):
    """Each level a run of its own, restarted from the previous level's final checkpoint."""
    results = []
    t = 0.0
    for k, (direction, u) in enumerate(sweep_schedule(a.levels)):
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
            return None
        mean, std = hold_mean(os.path.join(a.out, "monitor.csv"), t, t1)
        results.append((direction, u, t, t1, mean, std))
        print(f"{direction:4s} U = {u:.4g} m/s: pressure drop {mean:.1f} +- {std:.1f} Pa")
        t = t1
    return results


def write_and_plot(out, up, results):
    """umf_sweep.csv and umf_sweep.png in `out`, U_mf from the decreasing curve printed."""
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "umf_sweep.csv"), "w", newline="") as f:
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
    fig.savefig(os.path.join(out, "umf_sweep.png"), dpi=120)
    return fit


if __name__ == "__main__":
    sys.exit(main())
