#!/usr/bin/python3
"""post/report.py's pressure_drop.png carries the bed weight per unit area as a dashed horizontal line labelled
"bed weight / area", from what each run folder gives (bed_weight_per_area), exact to rounding:

- CFD-DEM, monitor.csv with solids_mass_per_depth_kg_m (the paper's 497.628... kg/m of the DEM oracle), domain
  width 0.6 m, one species of 2700 kg/m^3, gas 1.205 kg/m^3, g = 9.81: g M / A (1 - rho_g / rho_p) = 8132.6 Pa;
- CFD-DEM, an older monitor.csv with only solids_mass_kg (1.99 kg) and coupling.depth = 0.004 m, domain.gravity
  (0, -9.0): 9.0 x 1.99 / (0.6 x 0.004) (1 - 1.205 / 2500);
- two-fluid, no mass column: (rho_p - rho_g) (1 - eps) g H of the case's initial bed (2700, 1.205, 0.431, 0.54);
- a run whose folder gives none of these (no width, no mass, no tfm section) has its curve and no line, with the
  reason in summary.md, and the figure is still written.
A report of one run has the label "bed weight / area" exactly; of several, one per run ("bed weight / area, RUN")
in the colour of the run's curve.

Usage (ctest): test_report_bed_weight.py FLUIDBED_BINARY REPO_ROOT. Exits non-zero on failure.
"""

import math
import os
import sys
import tempfile

import numpy as np


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


def make(root, name, case, columns, mass=None):
    """A run folder with case.toml and a monitor.csv of 51 rows: a pressure drop of 7000 Pa and `columns` holding
    `mass` (kg or kg/m) in every row."""
    d = os.path.join(root, name)
    os.makedirs(d)
    with open(os.path.join(d, "case.toml"), "w") as f:
        f.write(case)
    with open(os.path.join(d, "monitor.csv"), "w") as f:
        f.write(",".join(["time_s", "kinetic_energy_J", "pressure_drop_Pa"] + columns + ["wall_s"]) + "\n")
        for k in range(51):
            t = 0.01 * k
            f.write(",".join([repr(t), "0", repr(7000.0 + 100 * math.sin(10 * t))] + [repr(mass)] * len(columns)
                             + [repr(t)]) + "\n")
    return d


def capture(report):
    """Per figure file: every axes' lines as (label, linestyle, colour, ydata)."""
    figs = {}
    original = report.save

    def save(fig, path):
        figs[os.path.basename(path)] = [[(ln.get_label(), ln.get_linestyle(), ln.get_color(),
                                          np.asarray(ln.get_ydata(), dtype=float)) for ln in ax.lines]
                                        for ax in fig.axes]
        original(fig, path)

    report.save = save
    return figs


def weight_lines(fig):
    return [ln for ax in fig for ln in ax if ln[0].startswith("bed weight / area")]


def main():
    repo = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "..", "..")
    sys.path.insert(0, os.path.join(repo, "post"))
    import report

    figs = capture(report)
    g, rho_g = 9.81, 1.205
    per_depth = 497.62827632875974
    with tempfile.TemporaryDirectory() as tmp:
        dem = make(tmp, "dem", '[case]\nname = "dem"\nmodel = "dem"\n[domain]\nwidth = 0.6\nheight = 1.0\n'
                   '[gas]\ndensity = 1.205\n[[species]]\ndiameter = 0.004\ndensity = 2700.0\n',
                   ["solids_mass_kg", "solids_mass_per_depth_kg_m"], per_depth)
        old = make(tmp, "old-dem", '[case]\nname = "old"\nmodel = "dem"\n[domain]\nwidth = 0.6\nheight = 1.0\n'
                   'gravity = [0.0, -9.0]\n[gas]\ndensity = 1.205\n[coupling]\ndepth = 0.004\n'
                   '[[species]]\ndensity = 2500.0\n[[species]]\ndensity = 2500.0\n', ["solids_mass_kg"], 1.99)
        tfm = make(tmp, "tfm", '[case]\nname = "tfm"\nmodel = "tfm"\n[domain]\nwidth = 0.6\nheight = 1.0\n'
                   '[gas]\ndensity = 1.205\n[tfm]\nparticle_density = 2700.0\neps_initial = 0.431\n'
                   'packed_height = 0.54\n', [])
        bare = make(tmp, "bare", '[case]\nname = "bare"\nmodel = "dem"\n', [])
        want = {"dem": g * per_depth / 0.6 * (1 - rho_g / 2700.0),
                "old-dem": 9.0 * 1.99 / (0.6 * 0.004) * (1 - rho_g / 2500.0),
                "tfm": (2700.0 - rho_g) * (1 - 0.431) * g * 0.54}

        # One run: the label is "bed weight / area".
        report.write_report([dem], os.path.join(tmp, "one"))
        lines = weight_lines(figs["pressure_drop.png"])
        if [ln[0] for ln in lines] != ["bed weight / area"]:
            fail(f"one run: bed-weight lines {[ln[0] for ln in lines]}")
        if lines[0][1] != "--" or not np.allclose(lines[0][3], want["dem"], rtol=1e-12, atol=0):
            fail(f"one run: the line is {lines[0][1]} at {lines[0][3]}, want -- at {want['dem']}")

        # Several: a line per run that gives the weight, in its curve's colour; none for the bare folder.
        out = os.path.join(tmp, "many")
        report.write_report([dem, old, tfm, bare], out)
        fig = figs["pressure_drop.png"]
        curves = {ln[0]: ln[2] for ax in fig for ln in ax if ln[1] == "-"}
        if sorted(curves) != ["bare", "dem", "old-dem", "tfm"]:
            fail(f"pressure-drop curves {sorted(curves)}")
        lines = {ln[0]: ln for ln in weight_lines(fig)}
        if sorted(lines) != [f"bed weight / area, {r}" for r in ("dem", "old-dem", "tfm")]:
            fail(f"bed-weight lines {sorted(lines)}")
        for run, value in want.items():
            ln = lines[f"bed weight / area, {run}"]
            if not np.allclose(ln[3], value, rtol=1e-12, atol=0):
                fail(f"{run}: bed weight / area {ln[3]}, want {value}")
            if ln[2] != curves[run]:
                fail(f"{run}: the line's colour {ln[2]} is not its curve's {curves[run]}")
        summary = open(os.path.join(out, "summary.md")).read()
        if "bare: no bed-weight line" not in summary:
            fail(f"summary.md does not say why bare has no bed-weight line:\n{summary}")
        entry = next((ln for ln in summary.splitlines() if ln.startswith("- Bed pressure drop")), "")
        if "](figures/pressure_drop.png)" not in entry:
            fail(f"pressure_drop.png is not in summary.md: {entry!r}")
        if not os.path.isfile(os.path.join(out, "figures", "pressure_drop.png")):
            fail("pressure_drop.png not written")
        if f"dem: bed weight / area {want['dem']:.1f} Pa" not in summary:
            fail(f"summary.md does not give dem's bed weight per area ({want['dem']:.1f} Pa)")
    print("post report bed weight: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
