#!/usr/bin/python3
"""Report of one or more fluidbed run folders: figures in the layout of Gera et al. (1998) and summary.md.

Usage: report.py OUT_DIR [OUT_DIR ...] --out REPORT_DIR

Reads per run folder (see /work/shared/interface.md): case.toml, monitor.csv, bubble.csv, fields.pvd with
fields/NNNNNN.vti, particles.pvd with particles/NNNNNN.vtu, tracers/NNNNNN.csv and cost.json. Every missing input
skips its figure or table with a note in summary.md. Numbers in summary.md are the CSV/JSON values as written.
"""

import argparse
import csv
import json
import math
import os
import sys
import tomllib
import xml.etree.ElementTree as ET

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Instants of the paper's Figs. 3 and 4.
PAPER_INSTANTS = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]
# Instants of the paper's Table 2.
TABLE2_TIMES = [0.2, 0.3, 0.4, 0.5]
# U_b = C sqrt(g D) for two-dimensional bubbles; the same constant as src/analysis/rise_velocity.hpp.
RISE_CONSTANT_2D = 0.5
G = 9.81
VOIDAGE_CMAP = "cividis"
# Two alternating shades that stay distinct in grey print, as the paper's coloured layers.
LAYER_COLOURS = ["#1f3b73", "#e8c547"]


# ---------------------------------------------------------------------------------------------------------- input

def read_csv(path):
    """Columns of a CSV file as lists of the raw strings, or None when the file is missing or empty."""
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return None
    header = [h.strip() for h in rows[0]]
    cols = {h: [] for h in header}
    for row in rows[1:]:
        if not row:
            continue
        for k, h in enumerate(header):
            cols[h].append(row[k].strip() if k < len(row) else "")
    return cols


def to_float(token):
    try:
        return float(token) if token != "" else math.nan
    except ValueError:
        return math.nan


def numeric(cols, name):
    return np.array([to_float(v) for v in cols.get(name, [])], dtype=float)


def read_pvd(path):
    """(time, absolute file path) of every frame of a ParaView collection, sorted by time."""
    if not os.path.isfile(path):
        return []
    root = ET.parse(path).getroot()
    base = os.path.dirname(path)
    frames = []
    for ds in root.iter("DataSet"):
        f = os.path.join(base, ds.get("file", ""))
        if os.path.isfile(f):
            frames.append((float(ds.get("timestep", "nan")), f))
    return sorted(frames)


def vtk_array(data, name):
    from vtk.util.numpy_support import vtk_to_numpy

    arr = data.GetArray(name)
    return None if arr is None else vtk_to_numpy(arr)


def read_vti(path):
    """Voidage and grid geometry of a fields/NNNNNN.vti file: dict with eps[j, i], x0, y0, dx, dy, nx, ny."""
    import vtk

    r = vtk.vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    ext = img.GetExtent()
    nx, ny = ext[1] - ext[0], ext[3] - ext[2]
    ox, oy, _ = img.GetOrigin()
    dx, dy, _ = img.GetSpacing()
    eps = vtk_array(img.GetCellData(), "voidage")
    if eps is None or nx <= 0 or ny <= 0:
        return None
    return {"eps": np.asarray(eps, dtype=float).reshape(ny, nx), "x0": ox + ext[0] * dx, "y0": oy + ext[2] * dy,
            "dx": dx, "dy": dy, "nx": nx, "ny": ny}


def read_vtu(path):
    """Particle centres, diameters and layers of a particles/NNNNNN.vtu file."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy

    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    grid = r.GetOutput()
    if grid.GetPoints() is None or grid.GetNumberOfPoints() == 0:
        return None
    pts = vtk_to_numpy(grid.GetPoints().GetData())
    pd = grid.GetPointData()
    layer = vtk_array(pd, "layer")
    diameter = vtk_array(pd, "diameter")
    n = pts.shape[0]
    return {"x": pts[:, 0].astype(float), "y": pts[:, 1].astype(float),
            "layer": np.zeros(n, dtype=int) if layer is None else np.asarray(layer, dtype=int),
            "diameter": np.full(n, 0.004) if diameter is None else np.asarray(diameter, dtype=float)}


def frame_index(path):
    stem = os.path.splitext(os.path.basename(path))[0]
    return int(stem) if stem.isdigit() else None


class Run:
    def __init__(self, folder):
        self.folder = folder
        self.notes = []
        self.name = os.path.basename(os.path.normpath(folder))
        self.model = "?"
        self.case = {}
        case_path = os.path.join(folder, "case.toml")
        if os.path.isfile(case_path):
            try:
                with open(case_path, "rb") as f:
                    self.case = tomllib.load(f)
                c = self.case.get("case", {})
                self.name = str(c.get("name", self.name))
                self.model = str(c.get("model", self.model))
            except (tomllib.TOMLDecodeError, OSError) as e:
                self.notes.append(f"case.toml unreadable ({e})")
        else:
            self.notes.append("no case.toml")
        self.monitor = read_csv(os.path.join(folder, "monitor.csv"))
        if self.monitor is None:
            self.notes.append("no monitor.csv")
        self.bubble = read_csv(os.path.join(folder, "bubble.csv"))
        if self.bubble is None:
            self.notes.append("no bubble.csv")
        self.fields = read_pvd(os.path.join(folder, "fields.pvd"))
        if not self.fields:
            self.notes.append("no fields.pvd frames")
        self.particles = read_pvd(os.path.join(folder, "particles.pvd"))
        tracer_dir = os.path.join(folder, "tracers")
        self.tracers = []
        if os.path.isdir(tracer_dir):
            times_by_index = {frame_index(f): t for t, f in self.fields + self.particles}
            for fn in sorted(os.listdir(tracer_dir)):
                idx = frame_index(fn)
                if fn.endswith(".csv") and idx is not None and idx in times_by_index:
                    self.tracers.append((times_by_index[idx], os.path.join(tracer_dir, fn)))
            self.tracers.sort()
        self.cost = None
        cost_path = os.path.join(folder, "cost.json")
        if os.path.isfile(cost_path):
            try:
                with open(cost_path) as f:
                    self.cost = json.load(f)
            except (json.JSONDecodeError, OSError) as e:
                self.notes.append(f"cost.json unreadable ({e})")
        self.gravity = G
        g = self.case.get("gas", {}).get("gravity") if isinstance(self.case.get("gas"), dict) else None
        if isinstance(g, (int, float)) and g > 0:
            self.gravity = float(g)

    def label(self):
        return f"{self.name} ({self.model})"


# ---------------------------------------------------------------------------------------------------- selection

def nearest_frame(frames, t, tol):
    """The frame nearest to time t, if within tol."""
    if not frames:
        return None
    best = min(frames, key=lambda fr: abs(fr[0] - t))
    return best if abs(best[0] - t) <= tol else None


def choose_instants(frame_lists):
    """The paper's instants that some run has a frame for (within 5 ms), else up to 6 instants spread over the
    frames of the first run with frames."""
    chosen = [t for t in PAPER_INSTANTS if any(nearest_frame(fl, t, 0.005) for fl in frame_lists)]
    if chosen:
        return chosen, 0.005
    for fl in frame_lists:
        if fl:
            times = [fr[0] for fr in fl]
            k = np.unique(np.linspace(0, len(times) - 1, min(6, len(times))).round().astype(int))
            return [times[i] for i in k], 1e-9
    return [], 0.0


# ------------------------------------------------------------------------------------------------------- figures

def save(fig, path):
    fig.savefig(path, dpi=110)
    plt.close(fig)


def panel_grid(n_rows, n_cols, aspect):
    w = 1.6
    fig, axes = plt.subplots(n_rows, n_cols, figsize=(w * n_cols + 1.2, w * aspect * n_rows + 0.8), squeeze=False)
    return fig, axes


def figure_voidage(runs, path):
    lists = [r.fields for r in runs]
    instants, tol = choose_instants(lists)
    if not instants:
        return "no fields.pvd frames in any run"
    rows = [r for r in runs if r.fields]
    first = read_vti(rows[0].fields[0][1])
    if first is None:
        return "fields have no voidage array"
    aspect = (first["ny"] * first["dy"]) / (first["nx"] * first["dx"])
    fig, axes = panel_grid(len(rows), len(instants), aspect)
    image = None
    for a, run in enumerate(rows):
        for b, t in enumerate(instants):
            ax = axes[a][b]
            fr = nearest_frame(run.fields, t, tol)
            f = read_vti(fr[1]) if fr else None
            if f is None:
                ax.set_axis_off()
                continue
            ext = [f["x0"], f["x0"] + f["nx"] * f["dx"], f["y0"], f["y0"] + f["ny"] * f["dy"]]
            image = ax.imshow(f["eps"], origin="lower", extent=ext, cmap=VOIDAGE_CMAP, vmin=0.35, vmax=1.0,
                              interpolation="nearest")
            ax.set_title(f"t = {fr[0]:.2f} s", fontsize=8)
            ax.tick_params(labelsize=6)
            if b == 0:
                ax.set_ylabel(f"{run.label()}\ny (m)", fontsize=7)
            if a == len(rows) - 1:
                ax.set_xlabel("x (m)", fontsize=7)
    if image is not None:
        cb = fig.colorbar(image, ax=axes.ravel().tolist(), shrink=0.8)
        cb.set_label("voidage")
    fig.suptitle("Voidage (layout of Gera et al. 1998, Fig. 3)", fontsize=10)
    save(fig, path)
    return None


def scatter_layers(ax, x, y, layer, diameter_m, width_m, panel_w_in):
    # Marker area in points^2 from the physical diameter, so the balls look as large as they are.
    pts_per_m = panel_w_in * 72.0 / max(width_m, 1e-12)
    size = (np.asarray(diameter_m) * pts_per_m) ** 2
    colours = np.array(LAYER_COLOURS)[np.asarray(layer) % 2]
    ax.scatter(x, y, s=size, c=colours, linewidths=0)


def domain_of(run):
    if run.fields:
        f = read_vti(run.fields[0][1])
        if f is not None:
            return f["x0"], f["x0"] + f["nx"] * f["dx"], f["y0"], f["y0"] + f["ny"] * f["dy"], f["dx"]
    return None


def figure_layers(runs, kind, path):
    """kind 'particles': DEM particles by initial layer (Fig. 4a); 'tracers': cell balls (Fig. 4b/c)."""
    rows = [r for r in runs if (r.particles if kind == "particles" else r.tracers)]
    if not rows:
        return f"no {kind} in any run"
    instants, tol = choose_instants([r.particles if kind == "particles" else r.tracers for r in rows])
    dom = domain_of(rows[0])
    width = (dom[1] - dom[0]) if dom else 0.6
    height = (dom[3] - dom[2]) if dom else 1.0
    fig, axes = panel_grid(len(rows), len(instants), height / width)
    panel_w = 1.6
    for a, run in enumerate(rows):
        d = domain_of(run)
        frames = run.particles if kind == "particles" else run.tracers
        for b, t in enumerate(instants):
            ax = axes[a][b]
            fr = nearest_frame(frames, t, tol)
            if fr is None:
                ax.set_axis_off()
                continue
            if kind == "particles":
                p = read_vtu(fr[1])
                if p is None:
                    ax.set_axis_off()
                    continue
                scatter_layers(ax, p["x"], p["y"], p["layer"], p["diameter"], width, panel_w)
            else:
                c = read_csv(fr[1])
                if c is None:
                    ax.set_axis_off()
                    continue
                ball = d[4] if d else 0.02  # the paper's balls have the diameter of a cell
                scatter_layers(ax, numeric(c, "x"), numeric(c, "y"), numeric(c, "layer").astype(int), ball, width,
                               panel_w)
            if d:
                ax.set_xlim(d[0], d[1])
                ax.set_ylim(d[2], d[3])
            ax.set_aspect("equal")
            ax.set_title(f"t = {fr[0]:.2f} s", fontsize=8)
            ax.tick_params(labelsize=6)
            if b == 0:
                ax.set_ylabel(f"{run.label()}\ny (m)", fontsize=7)
            if a == len(rows) - 1:
                ax.set_xlabel("x (m)", fontsize=7)
    title = ("Particles by initial layer (Fig. 4a)" if kind == "particles"
             else "Cell tracer balls moved by the cell solids velocity (Fig. 4b/c)")
    fig.suptitle(title, fontsize=10)
    save(fig, path)
    return None


def figure_curves(runs, source, column, ylabel, title, path):
    """One curve per run of `column` against time; a column ending in '*' is a prefix (one curve per match)."""
    fig, ax = plt.subplots(figsize=(6, 4))
    drawn = 0
    for run in runs:
        cols = run.bubble if source == "bubble" else run.monitor
        if cols is None:
            continue
        names = ([c for c in cols if c.startswith(column[:-1])] if column.endswith("*")
                 else [column] if column in cols else [])
        t = numeric(cols, "time_s")
        for name in names:
            v = numeric(cols, name)
            ok = np.isfinite(t) & np.isfinite(v)
            if not ok.any():
                continue
            label = run.label() if len(names) == 1 else f"{run.label()} {name}"
            ax.plot(t[ok], v[ok], marker=".", markersize=3, label=label)
            drawn += 1
    if drawn == 0:
        plt.close(fig)
        return f"no {column} values in any {source}.csv"
    ax.set_xlabel("time (s)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save(fig, path)
    return None


def figure_rise_vs_correlation(runs, path):
    fig, ax = plt.subplots(figsize=(6, 4))
    d_max = 0.0
    g = G
    drawn = 0
    for run in runs:
        if run.bubble is None:
            continue
        d = numeric(run.bubble, "equivalent_diameter_m")
        u = numeric(run.bubble, "rise_velocity_m_s")
        ok = np.isfinite(d) & np.isfinite(u)
        if not ok.any():
            continue
        ax.plot(d[ok], u[ok], "o", markersize=3, label=run.label())
        d_max = max(d_max, float(d[ok].max()))
        g = run.gravity
        drawn += 1
    if drawn == 0:
        plt.close(fig)
        return "no equivalent_diameter_m and rise_velocity_m_s values in any bubble.csv"
    dd = np.linspace(0.0, 1.1 * d_max, 100)
    ax.plot(dd, RISE_CONSTANT_2D * np.sqrt(g * dd), "k--", label=f"U_b = {RISE_CONSTANT_2D} sqrt(g D) (2D)")
    ax.set_xlabel("equivalent diameter D = sqrt(4A/pi) (m)")
    ax.set_ylabel("rise velocity (m/s)")
    ax.set_title("Rise velocity against the 2D single-bubble correlation")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save(fig, path)
    return None


# ------------------------------------------------------------------------------------------------------ tables

def nearest_row(cols, t):
    """Index of the bubble.csv row whose time is nearest to t."""
    times = numeric(cols, "time_s")
    if times.size == 0 or not np.isfinite(times).any():
        return None
    return int(np.nanargmin(np.abs(times - t)))


def detachment_time(cols):
    """Raw time token of the first row with attached == 0 after a row with attached == 1 (as the C++ tracker)."""
    seen = False
    for t, a in zip(cols.get("time_s", []), cols.get("attached", [])):
        if a == "1":
            seen = True
        elif a == "0" and seen:
            return t
    return None


def first_time_where(cols, column, value):
    for t, v in zip(cols.get("time_s", []), cols.get(column, [])):
        if v == value:
            return t
    return None


def cell(token, fmt=".2f"):
    """A bubble.csv value as a table cell, rounded for reading ('–' where empty). Velocities and ratios are given
    to 0.01 (m/s), times to 1 ms: finer digits are below what the 0.02 m grid and 0.01 s sampling resolve."""
    if token in (None, ""):
        return "–"
    return format(float(token), fmt)


def table2(runs):
    lines = []
    with_bubble = [r for r in runs if r.bubble is not None]
    if not with_bubble:
        return ["No run has a bubble.csv: Table 2 skipped."]
    lines.append("Values are the bubble.csv rows nearest in time to each instant (the row's own time in brackets); "
                 "'–' where the row has no bubble.")
    lines.append("")
    head = "| t (s) |"
    sep = "|---|"
    for r in with_bubble:
        head += f" {r.label()}: axial gas velocity (m/s) | rise velocity (m/s) | U_th/U_mf |"
        sep += "---|---|---|"
    lines += [head, sep]
    for t in TABLE2_TIMES:
        line = f"| {t} |"
        for r in with_bubble:
            k = nearest_row(r.bubble, t)
            if k is None:
                line += " – | – | – |"
                continue
            get = lambda c: r.bubble.get(c, [""] * (k + 1))[k]  # noqa: E731
            line += (f" {cell(get('nose_gas_velocity_m_s'))} [{cell(get('time_s'), '.3f')}] |"
                     f" {cell(get('rise_velocity_m_s'))} |"
                     f" {cell(get('throughflow_ratio'))} |")
        lines.append(line)
    return lines


def cost_table(runs):
    with_cost = [r for r in runs if r.cost is not None]
    if not with_cost:
        return ["No run has a cost.json: cost table skipped."]
    keys = ["cells", "particles", "time_steps", "wall_s", "simulated_s"]
    lines = ["| run | " + " | ".join(keys) + " |", "|---" * (len(keys) + 1) + "|"]
    for r in with_cost:
        lines.append(f"| {r.label()} | " + " | ".join(str(r.cost.get(k, "–")) for k in keys) + " |")
    return lines


# -------------------------------------------------------------------------------------------------------- main

def write_report(folders, out):
    figdir = os.path.join(out, "figures")
    os.makedirs(figdir, exist_ok=True)
    runs = [Run(f) for f in folders]
    figures = [
        ("voidage.png", "Voidage maps at the paper's instants (Fig. 3 layout)", lambda p: figure_voidage(runs, p)),
        ("layers_particles.png", "Particles coloured by initial layer (Fig. 4a)",
         lambda p: figure_layers(runs, "particles", p)),
        ("layers_tracers.png", "Cell tracer balls coloured by initial layer (Fig. 4b/c)",
         lambda p: figure_layers(runs, "tracers", p)),
        ("nose_height.png", "Bubble nose height",
         lambda p: figure_curves(runs, "bubble", "nose_height_m", "nose height (m)", "Bubble nose height", p)),
        ("rise_velocity.png", "Bubble rise velocity",
         lambda p: figure_curves(runs, "bubble", "rise_velocity_m_s", "rise velocity (m/s)", "Bubble rise velocity",
                                 p)),
        ("throughflow_ratio.png", "Throughflow ratio U_th/U_mf",
         lambda p: figure_curves(runs, "bubble", "throughflow_ratio", "U_th / U_mf", "Throughflow at the nose", p)),
        ("equivalent_diameter.png", "Bubble equivalent diameter",
         lambda p: figure_curves(runs, "bubble", "equivalent_diameter_m", "D = sqrt(4A/pi) (m)",
                                 "Bubble equivalent diameter", p)),
        ("rise_vs_correlation.png", "Rise velocity against the 2D correlation",
         lambda p: figure_rise_vs_correlation(runs, p)),
        ("pressure_drop.png", "Bed pressure drop",
         lambda p: figure_curves(runs, "monitor", "pressure_drop_Pa", "pressure drop (Pa)", "Bed pressure drop", p)),
        ("mixing_index.png", "Lacey mixing index",
         lambda p: figure_curves(runs, "monitor", "lacey*", "Lacey index M", "Mixing index", p)),
    ]
    md = ["# fluidbed report", ""]
    md.append("## Runs")
    md.append("")
    md.append("| run | model | folder | notes |")
    md.append("|---|---|---|---|")
    for r in runs:
        md.append(f"| {r.name} | {r.model} | {r.folder} | {'; '.join(r.notes) if r.notes else '–'} |")
    md += ["", "## Figures", ""]
    for fname, caption, make in figures:
        path = os.path.join(figdir, fname)
        try:
            why = make(path)
        except Exception as e:  # a broken input file skips its figure, never the report
            why = f"failed: {type(e).__name__}: {e}"
            plt.close("all")
        if why is None:
            md.append(f"- {caption}: ![{caption}](figures/{fname})")
        else:
            md.append(f"- {caption}: skipped ({why}).")
    md += ["", "## Table 2: axial gas velocity at the nose, rise velocity and U_th/U_mf", ""]
    md += table2(runs)
    md += ["", "## Bubble events", ""]
    md.append("| run | detachment time (s) | first eruption time (s) |")
    md.append("|---|---|---|")
    for r in runs:
        if r.bubble is None:
            md.append(f"| {r.label()} | no bubble.csv | no bubble.csv |")
            continue
        t_det = detachment_time(r.bubble)
        t_eru = first_time_where(r.bubble, 'erupted', '1')
        md.append(f"| {r.label()} | {cell(t_det, '.3f') if t_det else 'none'} | "
                  f"{cell(t_eru, '.3f') if t_eru else 'none'} |")
    md.append("")
    md.append("Detachment: the first bubble.csv row with attached = 0 after a row with attached = 1.")
    md += ["", "## Cost", ""]
    md += cost_table(runs)
    md.append("")
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(md))
    return runs


def main(argv=None):
    ap = argparse.ArgumentParser(description="Figures and summary.md of fluidbed run folders.")
    ap.add_argument("runs", nargs="+", help="run output folders")
    ap.add_argument("--out", default="report", help="report folder (default: report)")
    args = ap.parse_args(argv)
    missing = [d for d in args.runs if not os.path.isdir(d)]
    if missing:
        print(f"report: not a folder: {', '.join(missing)}", file=sys.stderr)
        return 2
    write_report(args.runs, args.out)
    print(f"report written to {os.path.join(args.out, 'summary.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
