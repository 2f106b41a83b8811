#!/usr/bin/env python3
"""The TFM runs of post/tfm_closure_study.sh against the CFD-DEM ensemble of 8 packings (issue 32, item 3).

For each run folder: the paper's Table 2 quantities at 0.2-0.5 s, taken as the ensemble's were (docs/validation.md,
"Ensemble of 8 packings": the bubble.csv row nearest the instant; U_b the centroid's rise velocity; U_th/U_mf =
(gas at the nose - U_b) / U_mf with the paper's U_mf = 1.8 m/s; the nose's rise velocity), the detachment and
first eruption from the run's log, and each number's distance from the ensemble mean in ensemble standard
deviations (z). The summary columns: the gas at the nose after the jet closes (0.4 and 0.5 s) as a fraction of the
ensemble mean, the root mean square of z over every quantity the run has, and how many of them lie within 2 sd.

With --figure PNG: the gas velocity at the nose and the nose height against time for the runs named by --plot
(folder names; default all), the ensemble's mean ± sd at the four instants as error bars.

Usage: python3 post/tfm_closure_table.py RUN [RUN ...] [--csv FILE] [--figure PNG [--plot NAME ...]]
"""
import argparse
import csv
import math
import os
import re

U_MF = 1.8
INSTANTS = (0.2, 0.3, 0.4, 0.5)
# The 8-packing CFD-DEM ensemble, mean and sample standard deviation (docs/validation.md, measured with
# `fluidbed ensemble cases/gera1998/dem.toml -n 8 --end-time 1.0`): per instant, gas at the nose, U_b (centroid),
# U_th/U_mf, nose rise velocity (m/s); then detachment and first eruption (s).
ENSEMBLE = {
    0.2: {"gas": (9.81, 0.24), "ub": (0.76, 0.13), "uth": (5.03, 0.18), "rise": (1.40, 0.07)},
    0.3: {"gas": (9.62, 0.56), "ub": (0.88, 0.07), "uth": (4.86, 0.31), "rise": (1.36, 0.12)},
    0.4: {"gas": (6.02, 0.19), "ub": (0.93, 0.09), "uth": (2.83, 0.08), "rise": (1.08, 0.04)},
    0.5: {"gas": (3.98, 0.26), "ub": (0.54, 0.08), "uth": (1.91, 0.18), "rise": (0.47, 0.06)},
}
EVENTS = {"detachment": (0.316, 0.007), "eruption": (0.876, 0.035)}


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def table2(run):
    rows = list(csv.DictReader(open(os.path.join(run, "bubble.csv"))))
    out = {}
    for t in INSTANTS:
        best = min(rows, key=lambda r: abs(number(r["time_s"]) - t)) if rows else None
        if best is None or abs(number(best["time_s"]) - t) > 0.006:
            out[t] = {k: math.nan for k in ("gas", "ub", "uth", "rise")}
            continue
        gas, ub = number(best["nose_gas_velocity_m_s"]), number(best["centroid_rise_velocity_m_s"])
        out[t] = {"gas": gas, "ub": ub, "uth": (gas - ub) / U_MF, "rise": number(best["rise_velocity_m_s"])}
    return out


def events(run):
    text = open(os.path.join(run, "log.txt")).read()
    found = {}
    for name in EVENTS:
        m = re.findall(name + r" ([0-9.]+) s", text)
        found[name] = float(m[-1]) if m else math.nan
    end = re.findall(r"done: t = ([0-9.eE+-]+) s", text)
    found["end"] = float(end[-1]) if end else math.nan
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--csv")
    ap.add_argument("--figure")
    ap.add_argument("--plot", nargs="*")
    a = ap.parse_args()
    if a.figure:
        figure(a.runs, a.plot, a.figure)
    print("| run | gas at nose 0.2 / 0.3 / 0.4 / 0.5 s (m/s) | nose rise 0.2 / 0.3 / 0.4 / 0.5 s (m/s) | "
          "U_th/U_mf 0.2 / 0.3 / 0.4 / 0.5 | detachment (s) | eruption (s) | gas at nose 0.4, 0.5 s / ensemble | "
          "RMS z | within 2 sd |")
    print("|---|---|---|---|---|---|---|---|---|")
    fmt = lambda v, d=2: "-" if math.isnan(v) else f"{v:.{d}f}"
    print("| CFD-DEM ensemble of 8 (mean ± sd) | " +
          " / ".join(f"{ENSEMBLE[t]['gas'][0]:.2f} ± {ENSEMBLE[t]['gas'][1]:.2f}" for t in INSTANTS) + " | " +
          " / ".join(f"{ENSEMBLE[t]['rise'][0]:.2f} ± {ENSEMBLE[t]['rise'][1]:.2f}" for t in INSTANTS) + " | " +
          " / ".join(f"{ENSEMBLE[t]['uth'][0]:.2f} ± {ENSEMBLE[t]['uth'][1]:.2f}" for t in INSTANTS) + " | " +
          f"{EVENTS['detachment'][0]:.3f} ± {EVENTS['detachment'][1]:.3f} | "
          f"{EVENTS['eruption'][0]:.3f} ± {EVENTS['eruption'][1]:.3f} | 1, 1 | | |")
    records = []
    for run in a.runs:
        name = os.path.basename(os.path.normpath(run))
        if not os.path.exists(os.path.join(run, "bubble.csv")):
            print(f"| {name} | no output | | | | | | | |")
            continue
        t2, ev = table2(run), events(run)
        zs = []
        for t in INSTANTS:
            for k in ("gas", "ub", "uth", "rise"):
                if not math.isnan(t2[t][k]):
                    zs.append((t2[t][k] - ENSEMBLE[t][k][0]) / ENSEMBLE[t][k][1])
        for k, (m, s) in EVENTS.items():
            if not math.isnan(ev[k]):
                zs.append((ev[k] - m) / s)
        rms = math.sqrt(sum(z * z for z in zs) / len(zs)) if zs else math.nan
        within = sum(1 for z in zs if abs(z) <= 2.0)
        stopped = "" if ev["end"] >= 1.0 - 1e-9 else f" (stopped at {fmt(ev['end'], 3)} s)"
        ratio = [t2[t]["gas"] / ENSEMBLE[t]["gas"][0] for t in (0.4, 0.5)]
        print(f"| {name}{stopped} | " + " / ".join(fmt(t2[t]["gas"]) for t in INSTANTS) + " | " +
              " / ".join(fmt(t2[t]["rise"]) for t in INSTANTS) + " | " +
              " / ".join(fmt(t2[t]["uth"]) for t in INSTANTS) + " | " +
              f"{fmt(ev['detachment'], 3)} | {fmt(ev['eruption'], 3)} | {fmt(ratio[0])}, {fmt(ratio[1])} | "
              f"{fmt(rms, 1)} | {within} of {len(zs)} |")
        records.append({"run": name, "end_s": ev["end"], "detachment_s": ev["detachment"],
                        "eruption_s": ev["eruption"], "rms_z": rms, "within_2sd": within, "quantities": len(zs),
                        **{f"{k}_{t}": t2[t][k] for t in INSTANTS for k in ("gas", "ub", "uth", "rise")}})
    if a.csv and records:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(records[0].keys()))
            w.writeheader()
            w.writerows(records)


def figure(runs, chosen, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for run in runs:
        name = os.path.basename(os.path.normpath(run))
        if chosen and name not in chosen or not os.path.exists(os.path.join(run, "bubble.csv")):
            continue
        rows = list(csv.DictReader(open(os.path.join(run, "bubble.csv"))))
        t = [number(r["time_s"]) for r in rows]
        axes[0].plot(t, [number(r["nose_gas_velocity_m_s"]) for r in rows], label=name, lw=1.2)
        axes[1].plot(t, [number(r["nose_height_m"]) for r in rows], label=name, lw=1.2)
    axes[0].errorbar(INSTANTS, [ENSEMBLE[t]["gas"][0] for t in INSTANTS], yerr=[ENSEMBLE[t]["gas"][1] for t in INSTANTS],
                     fmt="ko", capsize=3, label="CFD-DEM, 8 packings (mean ± sd)")
    axes[0].axvline(0.4, color="0.6", ls=":", lw=1)
    axes[1].axvline(0.4, color="0.6", ls=":", lw=1)
    axes[0].set(xlabel="t (s)", ylabel="gas velocity above the nose (m/s)", xlim=(0.1, 0.8), ylim=(0, 14))
    axes[1].set(xlabel="t (s)", ylabel="nose height (m)", xlim=(0.1, 0.8))
    axes[0].legend(fontsize=7)
    axes[0].set_title("the jet closes at 0.4 s (dotted)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
