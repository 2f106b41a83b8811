#!/usr/bin/env python3
"""Inflow and pressure drop of a pulsed run: plot.py RUN_DIR [OUT.png].

Reads RUN_DIR/monitor.csv (inlet_velocity_m_s, pressure_drop_Pa) and RUN_DIR/case.toml (the bed's mass for the
weight line is the monitor's solids_mass_per_depth_kg_m), prints the mean pressure drop per pulsation phase, and
writes the two series against time. Needs numpy and matplotlib (/usr/bin/python3 on the development machine).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    run = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else f"{run}/pulsed.png"
    # The CFD-DEM's t = 0 row comes before any gas step (inlet_velocity_m_s 0).
    rows = [r for r in csv.DictReader(open(f"{run}/monitor.csv")) if float(r["time_s"]) > 0.0]
    t = np.array([float(r["time_s"]) for r in rows])
    u = np.array([float(r["inlet_velocity_m_s"]) for r in rows])
    dp = np.array([float(r["pressure_drop_Pa"]) if r["pressure_drop_Pa"] else np.nan for r in rows])
    mass = float(rows[0]["solids_mass_per_depth_kg_m"])
    width = None
    for line in open(f"{run}/case.toml"):
        if line.strip().startswith("width") and width is None:
            width = float(line.split("=")[1].split("#")[0])
    weight = mass * 9.81 / width if width else None
    hi = u > 0.5 * (u.min() + u.max())
    print(f"rows {len(t)}, inflow {u.min():.4g} to {u.max():.4g} m/s")
    print(f"mean pressure drop: high inflow {np.nanmean(dp[hi]):.0f} Pa, low inflow {np.nanmean(dp[~hi]):.0f} Pa"
          + (f", bed weight per area {weight:.0f} Pa" if weight else ""))
    fig, ax = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
    ax[0].plot(t, u)
    ax[0].set_ylabel("inlet velocity [m/s]")
    ax[1].plot(t, dp, label="pressure drop")
    if weight:
        ax[1].axhline(weight, color="k", ls="--", lw=0.8, label="bed weight / area")
    ax[1].set_ylabel("pressure drop [Pa]")
    ax[1].set_xlabel("t [s]")
    ax[1].legend()
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
