#!/usr/bin/python3
"""Report of one or more fluidbed run folders: figures in the layout of Gera et al. (1998) and summary.md.

Usage: report.py OUT_DIR [OUT_DIR ...] [--label NAME ...] --out REPORT_DIR

Reads per run folder (see /work/shared/interface.md): case.toml, monitor.csv, bubble.csv, fields.pvd with
fields/NNNNNN.vti, particles.pvd with particles/NNNNNN.vtu, tracers/NNNNNN.csv and cost.json. Every missing input
skips its figure or table with a note in summary.md, and every run a figure or table leaves out is named there with
the reason. Numbers in summary.md are the CSV/JSON values as written.

Runs are labelled by their folder name (the shortest tail of the path that tells the folders apart), or by
--label, given once per folder in the order of the folders: a --set sweep of one case gets one label per run.
"""

import argparse
import csv
import json
import math
import os
import sys
import tomllib
import warnings
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from psd import welch_psd  # noqa: E402
import averages as time_averages  # noqa: E402
import bubble_stats  # noqa: E402

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

# Instants of the paper's Figs. 3 and 4.
PAPER_INSTANTS = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]
# A frame this close to an instant is "at" it (the runner stamps frames k * interval exactly).
AT_INSTANT = 0.005
# Rounding slack (s) when a frame's or row's distance from an instant is compared with half its series' interval.
TIME_SLACK = 1e-9
# Panels of a run that has no frame at any of the paper's instants (a short run, another output interval).
OWN_INSTANTS = 6
# Instants of the paper's Table 2.
TABLE2_TIMES = [0.2, 0.3, 0.4, 0.5]
# U_b = C sqrt(g D) for two-dimensional bubbles; the same constant as src/analysis/rise_velocity.hpp.
RISE_CONSTANT_2D = 0.5
G = 9.81
VOIDAGE_CMAP = "cividis"
# Two alternating shades that stay distinct in grey print, as the paper's coloured layers.
LAYER_COLOURS = ["#1f3b73", "#e8c547"]
# Species: Okabe-Ito colours (distinct for colour-blind readers), none of them a layer shade.
SPECIES_COLOURS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#F0E442", "#56B4E9", "#E69F00", "#000000"]
# Panel size of the bed maps, inches: the paper's bed (0.6 x 1.0 m) gets 1.6 x 2.7; a panel is never taller
# than PANEL_MAX_H nor narrower than PANEL_MIN_W (a tall narrow bed), nor wider than PANEL_MAX_W (a wide one).
PANEL_REF_W, PANEL_REF_ASPECT = 1.6, 1.0 / 0.6
PANEL_MAX_H, PANEL_MIN_W, PANEL_MAX_W = 4.5, 0.45, 3.2


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


def mid_depth_slice(eps3):
    """The voidage on the plane z = D/2 of a (nz, ny, nx) array of cell values: the middle layer for odd nz, the
    mean of the two layers either side of the plane for even nz (linear interpolation between their centres)."""
    nz = eps3.shape[0]
    if nz % 2 == 1:
        return eps3[nz // 2]
    return 0.5 * (eps3[nz // 2 - 1] + eps3[nz // 2])


def read_vti(path):
    """Voidage and grid geometry of a fields/NNNNNN.vti file: dict with eps[j, i], x0, y0, dx, dy, nx, ny,
    dimension. A 3D frame (WholeExtent with z cells, nz >= 1) also gives eps3[k, j, i], nz, dz, z0 and
    eps_mean[j, i] (the depth average); its eps is the mid-depth slice (mid_depth_slice)."""
    import vtk

    r = vtk.vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    ext = img.GetExtent()
    nx, ny, nz = ext[1] - ext[0], ext[3] - ext[2], ext[5] - ext[4]
    ox, oy, oz = img.GetOrigin()
    dx, dy, dz = img.GetSpacing()
    eps = vtk_array(img.GetCellData(), "voidage")
    if eps is None or nx <= 0 or ny <= 0:
        return None
    if nz <= 0:
        return {"eps": np.asarray(eps, dtype=float).reshape(ny, nx), "x0": ox + ext[0] * dx, "y0": oy + ext[2] * dy,
                "dx": dx, "dy": dy, "nx": nx, "ny": ny, "dimension": 2}
    eps3 = np.asarray(eps, dtype=float).reshape(nz, ny, nx)
    return {"eps": mid_depth_slice(eps3), "eps_mean": eps3.mean(axis=0), "eps3": eps3, "x0": ox + ext[0] * dx,
            "y0": oy + ext[2] * dy, "z0": oz + ext[4] * dz, "dx": dx, "dy": dy, "dz": dz, "nx": nx, "ny": ny,
            "nz": nz, "dimension": 3}


def read_vtu(path):
    """Particle centres, diameters, layers and species of a particles/NNNNNN.vtu file."""
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
    species = vtk_array(pd, "species")
    diameter = vtk_array(pd, "diameter")
    n = pts.shape[0]
    return {"x": pts[:, 0].astype(float), "y": pts[:, 1].astype(float), "z": pts[:, 2].astype(float),
            "layer": np.zeros(n, dtype=int) if layer is None else np.asarray(layer, dtype=int),
            "species": np.zeros(n, dtype=int) if species is None else np.asarray(species, dtype=int),
            "diameter": np.full(n, 0.004) if diameter is None else np.asarray(diameter, dtype=float)}


def frame_index(path):
    stem = os.path.splitext(os.path.basename(path))[0]
    return int(stem) if stem.isdigit() else None


def jets_of(case):
    """The jets of a resolved case.toml: [[inlet.jet]] entries that blow faster or slower than the rest of the
    inlet for some time, with the gas on. None when the case is unknown."""
    if not case:
        return None
    gas = case.get("gas", {})
    if isinstance(gas, dict) and gas.get("enabled") is False:
        return []
    inlet = case.get("inlet", {})
    if not isinstance(inlet, dict):
        return []
    base = inlet.get("velocity", 0.0)
    jets = inlet.get("jet", [])
    if not isinstance(jets, list):
        return []
    out = []
    for j in jets:
        if not isinstance(j, dict):
            continue
        v, start, end = j.get("velocity", 0.0), j.get("start", 0.0), j.get("end", math.inf)
        if isinstance(v, (int, float)) and v != base and end > start:
            out.append(j)
    return out


def gravity_of(case):
    """|g| of a resolved case.toml (domain.gravity, formerly dem.gravity: x, y(, z) components), else 9.81."""
    for section in ("domain", "dem", "gas"):
        g = case.get(section, {}).get("gravity") if isinstance(case.get(section), dict) else None
        if isinstance(g, list) and len(g) in (2, 3) and all(isinstance(c, (int, float)) for c in g):
            magnitude = math.sqrt(sum(c * c for c in g))
            if magnitude > 0:
                return magnitude
        elif isinstance(g, (int, float)) and g > 0:
            return float(g)
    return G


class Run:
    def __init__(self, folder):
        self.folder = folder
        self.notes = []
        self.label = os.path.basename(os.path.normpath(folder))
        self.name = self.label
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
        self.jets = jets_of(self.case)
        self.species = [s for s in self.case.get("species", []) if isinstance(s, dict)] if self.case else []
        self.monitor = read_csv(os.path.join(folder, "monitor.csv"))
        if self.monitor is None:
            self.notes.append("no monitor.csv")
        self.bubble = read_csv(os.path.join(folder, "bubble.csv"))
        # probes.csv only where the case has [[probe]]s: its absence is no gap.
        self.probes = read_csv(os.path.join(folder, "probes.csv"))
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
        self.gravity = gravity_of(self.case) if self.case else G
        self._domain = None
        # 2 or 3: case.toml's case.dimension (written by every run since issue 12), else the first field frame's
        # extent (a 3D frame has z cells), else 2.
        self.dimension = 2
        self.depth = None
        c = self.case.get("case", {}) if isinstance(self.case.get("case"), dict) else {}
        d = self.case.get("domain", {}) if isinstance(self.case.get("domain"), dict) else {}
        if c.get("dimension") in (2, 3):
            self.dimension = int(c["dimension"])
        elif self.fields:
            f = read_vti(self.fields[0][1])
            if f is not None:
                self.dimension = f["dimension"]
        if self.dimension == 3 and isinstance(d.get("depth"), (int, float)):
            self.depth = float(d["depth"])

    def has_jet(self):
        """True or False from case.toml; None when the case is unknown (then the jet tables show the run)."""
        return None if self.jets is None else bool(self.jets)

    def domain(self):
        """(x0, x1, y0, y1, cell width) of the bed: from the first field frame, else from case.toml."""
        if self._domain is None:
            if self.fields:
                f = read_vti(self.fields[0][1])
                if f is not None:
                    self._domain = (f["x0"], f["x0"] + f["nx"] * f["dx"], f["y0"], f["y0"] + f["ny"] * f["dy"],
                                    f["dx"])
            if self._domain is None and isinstance(self.case.get("domain"), dict):
                d = self.case["domain"]
                w, h = d.get("width"), d.get("height")
                cw = self.case.get("grid", {}).get("cell_width", 0.02) if isinstance(self.case.get("grid"), dict) \
                    else 0.02
                if isinstance(w, (int, float)) and isinstance(h, (int, float)) and w > 0 and h > 0:
                    self._domain = (0.0, float(w), 0.0, float(h), float(cw))
        return self._domain


def unique_labels(folders):
    """Folder names, lengthened by parent folders where two runs would otherwise share one (a/run, b/run)."""
    parts = [os.path.normpath(os.path.abspath(f)).split(os.sep) for f in folders]
    depth = [1] * len(folders)
    while True:
        labels = ["/".join(p[-d:]) for p, d in zip(parts, depth)]
        clash = [k for k, lab in enumerate(labels) if labels.count(lab) > 1 and depth[k] < len(parts[k])]
        if not clash:
            return labels
        for k in clash:
            depth[k] += 1


# ---------------------------------------------------------------------------------------------------- selection

def span_of(frames):
    """(first, last, spacing) of a run's frame times."""
    times = [t for t, _ in frames]
    spacing = float(np.median(np.diff(times))) if len(times) > 1 else 0.0
    return times[0], times[-1], spacing


def nearest_within(times, t):
    """Index of the time nearest to t, or None unless it lies within half the series' interval of t (the median
    spacing of its times; 0 for a single time, which then counts only at t itself). An instant the run did not
    reach (beyond its last time + half an interval), or one in a gap of its output, has none."""
    times = np.asarray(times, dtype=float)
    ok = np.isfinite(times)
    if not ok.any():
        return None
    spacing = float(np.median(np.diff(times[ok]))) if ok.sum() > 1 else 0.0
    dist = np.where(ok, np.abs(times - t), np.inf)
    k = int(np.argmin(dist))
    return k if dist[k] <= 0.5 * max(spacing, 0.0) + TIME_SLACK else None


def nearest_frame(frames, t):
    """The frame nearest to time t, if it lies within half the run's frame interval of t (nearest_within)."""
    if not frames:
        return None
    k = nearest_within([fr[0] for fr in frames], t)
    return None if k is None else frames[k]


def own_instants(frames, n=OWN_INSTANTS):
    times = [t for t, _ in frames]
    k = np.unique(np.linspace(0, len(times) - 1, min(n, len(times))).round().astype(int))
    return [times[i] for i in k]


def choose_panels(runs, frames_of, what):
    """One row per run with frames: the columns are the paper's instants that some run reaches, and a panel shows
    only a frame within half the run's frame interval of its column's instant (nearest_frame), else None ('–'). A
    run reaching none of them keeps its row: all '–' when some other run sets the columns (its own frames are not
    put under instants they are not at), its own instants (up to OWN_INSTANTS frames spread over it) when no run
    reaches any. Returns (rows, n_cols, notes, columns): rows [(run, [frame or None per column])], notes for
    summary.md on every run or panel left out and on frames shown away from the instant, columns the instants of
    the columns ([] when every row shows its own instants)."""
    notes = []
    with_frames = []
    for r in runs:
        if frames_of(r):
            with_frames.append(r)
        else:
            notes.append(f"{r.label}: left out, it has no {what}")
    columns = [t for t in PAPER_INSTANTS if any(nearest_frame(frames_of(r), t) for r in with_frames)]
    n_cols = len(columns) if columns else min(OWN_INSTANTS, max((len(frames_of(r)) for r in with_frames), default=0))
    rows = []
    for r in with_frames:
        frames = frames_of(r)
        first, last, _ = span_of(frames)
        chosen = [nearest_frame(frames, t) for t in columns]
        if columns and not any(chosen):
            notes.append(f"{r.label}: no {what} within half its frame interval of the paper's instants (its frames "
                         f"run from {first:.3g} to {last:.3g} s): its row is '–' at every instant shown")
        elif not any(chosen):
            own = own_instants(frames, max(n_cols, 1))
            chosen = [next(fr for fr in frames if fr[0] == t) for t in own] + [None] * max(0, n_cols - len(own))
            notes.append(f"{r.label}: no {what} at the paper's instants (its frames run from {first:.3g} to "
                         f"{last:.3g} s); its row shows its own instants " + ", ".join(f"{t:.3g}" for t in own) + " s")
        else:
            missing = [t for t, fr in zip(columns, chosen) if fr is None]
            if missing:
                notes.append(f"{r.label}: no panel at t = " + ", ".join(f"{t:g}" for t in missing)
                             + f" s ('–': no frame within half its frame interval; its frames run from {first:.3g} "
                             f"to {last:.3g} s)")
            off = [(t, fr[0]) for t, fr in zip(columns, chosen) if fr is not None and abs(fr[0] - t) > AT_INSTANT]
            if off:
                notes.append(f"{r.label}: no frame within {AT_INSTANT * 1e3:g} ms of every instant; the nearest are "
                             "shown: " + ", ".join(f"{fr:.3g} s for {t:g} s" for t, fr in off))
        rows.append((r, chosen))
    return rows, n_cols, notes, columns


# ------------------------------------------------------------------------------------------------------- figures

def save(fig, path):
    fig.savefig(path, dpi=110)
    plt.close(fig)


def panel_size(aspect):
    """(width, height) in inches of one bed panel for a bed of height / width = aspect: the panel keeps the bed's
    shape; tall narrow beds get narrow panels of bounded height, wide beds wider, shorter ones."""
    w = PANEL_REF_W * math.sqrt(PANEL_REF_ASPECT / max(aspect, 1e-6))
    w = min(max(w, PANEL_MIN_W), PANEL_MAX_W)
    h = w * aspect
    if h > PANEL_MAX_H:
        h = PANEL_MAX_H
        w = max(h / aspect, PANEL_MIN_W)
    return w, h


def bed_aspect(rows):
    """The largest height / width of the runs' beds (a figure's panels share one size)."""
    aspects = []
    for r, _ in rows:
        d = r.domain()
        if d:
            aspects.append((d[3] - d[2]) / max(d[1] - d[0], 1e-12))
    return max(aspects) if aspects else PANEL_REF_ASPECT


def panel_grid(n_rows, n_cols, aspect, side=1.4):
    """A grid of bed panels; `side` inches on the right for a colour bar or a legend, and room for the row
    labels, the y ticks of the first column, the titles and the x ticks of each panel."""
    w, h = panel_size(aspect)
    fig, axes = plt.subplots(n_rows, n_cols, figsize=((w + 0.12) * n_cols + 0.9 + side, (h + 0.5) * n_rows + 0.5),
                             squeeze=False, layout="compressed")
    return fig, axes, (w, h)


def time_text(t):
    """A frame time as a panel title: 0.10 for the instants of a 0.01 s output, else three decimals."""
    return f"{t:.2f}" if abs(t * 100 - round(t * 100)) < 1e-6 else f"{t:.3f}"


def style_panel(ax, run, fr, column, n_rows, row, panel_w, domain):
    narrow = panel_w < 1.0
    ax.set_title(f"{time_text(fr[0])} s" if narrow else f"t = {time_text(fr[0])} s", fontsize=6 if narrow else 8)
    ax.tick_params(labelsize=5 if narrow else 6, labelleft=column == 0)
    if narrow and domain:
        ax.set_xticks([domain[0], domain[1]])
    else:
        ax.xaxis.set_major_locator(MaxNLocator(3))
    if column == 0:
        ax.set_ylabel(f"{run.label}\ny (m)", fontsize=7)
    if row == n_rows - 1:
        ax.set_xlabel("x (m)", fontsize=6 if narrow else 7)


def empty_panel(ax):
    ax.set_axis_off()


def missing_panel(ax, run, column, instant):
    """The panel of an instant the run has no frame at (within half its frame interval): '–', and in the first
    column the run's label, so that its row stays named."""
    ax.set_xticks([])
    ax.set_yticks([])
    for spine in ax.spines.values():
        spine.set_visible(False)
    ax.text(0.5, 0.5, "–", ha="center", va="center", transform=ax.transAxes, fontsize=14, color="0.45")
    ax.set_title(f"{instant:g} s: –", fontsize=7, color="0.45")
    if column == 0:
        ax.set_ylabel(run.label, fontsize=7)


def figure_voidage(runs, path, notes, depth_averaged=False):
    """Voidage maps; a 3D run shows its mid-depth slice, or with depth_averaged its depth-averaged voidage (then
    only the 3D runs have rows)."""
    if depth_averaged:
        runs = [r for r in runs if r.dimension == 3]
    else:
        for r in runs:
            if r.dimension == 3:
                notes.append(f"{r.label}: 3D; its panels show the mid-depth slice z = D/2 (the middle cell layer, or "
                             "the mean of the two layers either side of the plane); voidage_depth_averaged.png has "
                             "the depth average")
    rows, n_cols, why, columns = choose_panels(runs, lambda r: r.fields, "field frames")
    notes += why
    if not rows or n_cols == 0:
        return "no fields.pvd frames in any run"
    fig, axes, (pw, _) = panel_grid(len(rows), n_cols, bed_aspect(rows))
    image = None
    for a, (run, frames) in enumerate(rows):
        for b in range(n_cols):
            ax = axes[a][b]
            fr = frames[b] if b < len(frames) else None
            if fr is None and columns:
                missing_panel(ax, run, b, columns[b])
                continue
            f = read_vti(fr[1]) if fr else None
            if f is None:
                if fr is not None:
                    notes.append(f"{run.label}: {os.path.basename(fr[1])} has no voidage array")
                empty_panel(ax)
                continue
            ext = [f["x0"], f["x0"] + f["nx"] * f["dx"], f["y0"], f["y0"] + f["ny"] * f["dy"]]
            eps = f["eps_mean"] if depth_averaged and "eps_mean" in f else f["eps"]
            image = ax.imshow(eps, origin="lower", extent=ext, cmap=VOIDAGE_CMAP, vmin=0.35, vmax=1.0,
                              interpolation="nearest")
            style_panel(ax, run, fr, b, len(rows), a, pw, run.domain())
    if image is None:
        plt.close(fig)
        return "no field frame has a voidage array"
    cb = fig.colorbar(image, ax=axes.ravel().tolist(), shrink=0.8)
    cb.set_label("depth-averaged voidage" if depth_averaged else "voidage")
    fig.suptitle("Depth-averaged voidage of the 3D runs (layout of Gera et al. 1998, Fig. 3)" if depth_averaged
                 else "Voidage (layout of Gera et al. 1998, Fig. 3)", fontsize=10)
    save(fig, path)
    return None


def scatter_colours(ax, x, y, colours, diameter_m, scale_pt_per_m):
    # Marker area in points^2 from the physical diameter, so the balls look as large as they are.
    size = (np.asarray(diameter_m) * scale_pt_per_m) ** 2
    ax.scatter(x, y, s=size, c=colours, linewidths=0)


def points_per_metre(domain, panel):
    """Display scale of a panel of `panel` inches showing `domain` with equal axes (the smaller of the two fits)."""
    if not domain:
        return panel[0] * 72.0 / 0.6
    return 72.0 * 0.85 * min(panel[0] / max(domain[1] - domain[0], 1e-12), panel[1] / max(domain[3] - domain[2],
                                                                                        1e-12))


def species_of(run, k):
    """'species k: d = 4 mm' from case.toml where it has the species."""
    if k < len(run.species):
        d = run.species[k].get("diameter")
        rho = run.species[k].get("density")
        bits = []
        if isinstance(d, (int, float)):
            bits.append(f"d = {d * 1e3:.3g} mm")
        if isinstance(rho, (int, float)):
            bits.append(f"{rho:.4g} kg/m^3")
        if bits:
            return f"species {k}: " + ", ".join(bits)
    return f"species {k}"


def figure_particles(runs, kind, path, notes):
    """kind 'layers': DEM particles by initial layer (Fig. 4a); 'species': by species; 'tracers': cell balls
    (Fig. 4b/c)."""
    frames_of = (lambda r: r.tracers) if kind == "tracers" else (lambda r: r.particles)
    what = "tracer frames" if kind == "tracers" else "particle frames"
    candidates = runs
    if kind == "species":
        # Only worth a figure where some run mixes species.
        candidates = [r for r in runs if r.particles]
        mixed = []
        for r in candidates:
            p = read_vtu(r.particles[-1][1])
            if (p is not None and len(np.unique(p["species"])) > 1) or len(r.species) > 1:
                mixed.append(r)
        if not mixed:
            return "no run has particles of more than one species"
        for r in candidates:
            if r not in mixed:
                notes.append(f"{r.label}: left out, its particles are all of one species")
        candidates = mixed
    rows, n_cols, why, columns = choose_panels(candidates, frames_of, what)
    notes += why
    if not rows or n_cols == 0:
        return f"no {what} in any run"
    if kind != "tracers":
        for r, _ in rows:
            if r.dimension == 3:
                notes.append(f"{r.label}: 3D; its panels show the spheres the mid-depth plane z = D/2 cuts"
                             + ("" if r.depth else " (no domain.depth in case.toml: every sphere)"))
    fig, axes, panel = panel_grid(len(rows), n_cols, bed_aspect(rows), side=2.7 if kind == "species" else 0.2)
    species_seen = {}
    drawn = 0
    for a, (run, frames) in enumerate(rows):
        d = run.domain()
        scale = points_per_metre(d, panel)
        for b in range(n_cols):
            ax = axes[a][b]
            fr = frames[b] if b < len(frames) else None
            if fr is None:
                if columns:
                    missing_panel(ax, run, b, columns[b])
                else:
                    empty_panel(ax)
                continue
            if kind == "tracers":
                c = read_csv(fr[1])
                if c is None:
                    empty_panel(ax)
                    continue
                ball = d[4] if d else 0.02  # the paper's balls have the diameter of a cell
                x, y, layer = numeric(c, "x"), numeric(c, "y"), numeric(c, "layer").astype(int)
                if run.dimension == 3 and run.depth and "z" in c:
                    # A 3D bed's balls (one per cell): the slab of one ball's width about the mid-depth plane.
                    # (with an even number of cells across, the two layers either side of it, as the voidage slice).
                    cut = np.abs(numeric(c, "z") - 0.5 * run.depth) <= 0.5 * ball * (1.0 + 1e-9)
                    x, y, layer = x[cut], y[cut], layer[cut]
                colours = np.array(LAYER_COLOURS)[layer % 2]
                scatter_colours(ax, x, y, colours, ball, scale)
            else:
                p = read_vtu(fr[1])
                if p is not None and run.dimension == 3 and run.depth:
                    # A slice of a 3D bed: the spheres the mid-depth plane cuts.
                    cut = np.abs(p["z"] - 0.5 * run.depth) < 0.5 * p["diameter"]
                    p = {k: v[cut] for k, v in p.items()}
                if p is None:
                    empty_panel(ax)
                    continue
                if kind == "species":
                    colours = np.array(SPECIES_COLOURS)[p["species"] % len(SPECIES_COLOURS)]
                    for k in np.unique(p["species"]):
                        species_seen.setdefault(int(k), species_of(run, int(k)))
                else:
                    colours = np.array(LAYER_COLOURS)[p["layer"] % 2]
                scatter_colours(ax, p["x"], p["y"], colours, p["diameter"], scale)
            drawn += 1
            if d:
                ax.set_xlim(d[0], d[1])
                ax.set_ylim(d[2], d[3])
            ax.set_aspect("equal")
            style_panel(ax, run, fr, b, len(rows), a, panel[0], d)
    if drawn == 0:
        plt.close(fig)
        return f"no readable {what}"
    if species_seen:
        handles = [Line2D([], [], marker="o", linestyle="", color=SPECIES_COLOURS[k % len(SPECIES_COLOURS)],
                          label=species_seen[k]) for k in sorted(species_seen)]
        axes[0][-1].legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7, frameon=False)
    title = {"layers": "Particles by initial layer (Fig. 4a)", "species": "Particles by species",
             "tracers": "Cell tracer balls moved by the cell solids velocity (Fig. 4b/c)"}[kind]
    fig.suptitle(title, fontsize=10)
    save(fig, path)
    return None


def number(table, key):
    """table[key] when it is a number (not a bool), else None."""
    v = table.get(key) if isinstance(table, dict) else None
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else None


def bed_weight_per_area(run):
    """(value in Pa, how it was found) of the weight of the run's bed per unit area of the bottom, less the
    buoyancy of the gas it displaces, the pressure drop that carries a fluidized bed; (None, why not) when the run
    folder does not give it. From the most direct quantity the folder has:
    1. monitor.csv's solids_mass_per_depth_kg_m (the solids in the domain per metre of depth; 3D: of the box over
       domain.depth) at its first row, over domain.width: g M / A;
    2. else (a monitor.csv from before the per-depth columns) a CFD-DEM run's solids_mass_kg, the slab's particles,
       over domain.width x coupling.depth (2D; default 0.004 m) or x domain.depth (3D);
    3. else a two-fluid run's initial bed from case.toml, (1 - tfm.eps_initial) tfm.particle_density g
       tfm.packed_height.
    The buoyancy correction (1 - rho_g / rho_p) of 1 and 2 takes gas.density and the particle density
    (tfm.particle_density, or the one density of every [[species]]); without them, or with species of different
    densities, the weight is not corrected (said in how). g is |domain.gravity| (9.81 m/s^2 without one)."""
    case = run.case or {}
    domain = case.get("domain", {}) if isinstance(case.get("domain"), dict) else {}
    gas = case.get("gas", {}) if isinstance(case.get("gas"), dict) else {}
    tfm = case.get("tfm", {}) if isinstance(case.get("tfm"), dict) else {}
    coupling = case.get("coupling", {}) if isinstance(case.get("coupling"), dict) else {}
    g = run.gravity
    width = number(domain, "width")
    if width is None and run.domain() is not None:
        d = run.domain()
        width = d[1] - d[0]
    rho_g = number(gas, "density")
    if run.model == "tfm":
        rho_p = number(tfm, "particle_density")
    else:
        dens = {number(sp, "density") for sp in run.species}
        rho_p = dens.pop() if len(dens) == 1 else None
    mon = run.monitor or {}

    def first_value(column):
        v = numeric(mon, column)
        v = v[np.isfinite(v)]
        return float(v[0]) if v.size else None

    mass, how = None, None
    per_depth = first_value("solids_mass_per_depth_kg_m")
    if per_depth is not None and width:
        mass, how = per_depth / width, "monitor.csv solids_mass_per_depth_kg_m at its first row / domain.width"
    elif run.model == "dem" and first_value("solids_mass_kg") is not None and width:
        depth = number(domain, "depth") if run.dimension == 3 else number(coupling, "depth") or 0.004
        if depth:
            mass = first_value("solids_mass_kg") / (width * depth)
            how = (f"monitor.csv solids_mass_kg at its first row / (domain.width x "
                   f"{'domain.depth' if run.dimension == 3 else 'coupling.depth'})")
    if mass is not None:
        if rho_g is not None and rho_p and rho_p > rho_g:
            return g * mass * (1.0 - rho_g / rho_p), f"g M / A (1 - rho_g / rho_p), M / A from {how}"
        return g * mass, f"g M / A, M / A from {how} (no buoyancy correction: no single particle and gas density)"
    eps, height = number(tfm, "eps_initial"), number(tfm, "packed_height")
    if run.model == "tfm" and rho_p is not None and eps is not None and height is not None:
        return ((rho_p - (rho_g or 0.0)) * (1.0 - eps) * g * height,
                "(rho_p - rho_g) (1 - eps) g H of case.toml's initial bed (tfm.particle_density, gas.density, "
                "tfm.eps_initial, tfm.packed_height)")
    if run.monitor is None:
        return None, "no monitor.csv"
    return None, ("neither monitor.csv's solids_mass_per_depth_kg_m (or a CFD-DEM run's solids_mass_kg) with "
                  "case.toml's domain.width, nor a two-fluid bed in case.toml")


def bed_weight_lines(ax, run, line, n_runs, notes):
    """The horizontal line of bed_weight_per_area() in the colour of the run's curve, or a note why there is none."""
    try:
        value, how = bed_weight_per_area(run)
    except (TypeError, ValueError, ZeroDivisionError, AttributeError) as e:  # an odd case.toml skips the line only
        value, how = None, f"{type(e).__name__}: {e}"
    if value is None or not math.isfinite(value):
        notes.append(f"{run.label}: no bed-weight line ({how})")
        return
    label = "bed weight / area" if n_runs == 1 else f"bed weight / area, {run.label}"
    ax.axhline(value, color=line.get_color(), linestyle="--", linewidth=1.0, label=label)
    notes.append(f"{run.label}: bed weight / area {value:.1f} Pa = {how}")


def figure_pressure_drop(runs, path, notes):
    """monitor.csv pressure_drop_Pa against time, one curve per run, with the bed's weight per unit area as a
    dashed horizontal line of the run's colour (bed_weight_per_area; none, with a note, where the run does not give
    it)."""
    shown = [r for r in runs if r.monitor is not None and "pressure_drop_Pa" in r.monitor]
    return figure_curves(runs, "monitor", "pressure_drop_Pa", "pressure drop (Pa)", "Bed pressure drop", path, notes,
                         after=lambda ax, run, line: bed_weight_lines(ax, run, line, len(shown), notes))


def figure_curves(runs, source, column, ylabel, title, path, notes, after=None):
    """One curve per run of `column` against time; a column ending in '*' is a prefix (one curve per match).
    after(ax, run, line), where given, is called after the run's last curve."""
    fig, ax = plt.subplots(figsize=(6, 4))
    drawn = 0
    for run in runs:
        cols = run.bubble if source == "bubble" else run.monitor
        if cols is None:
            notes.append(f"{run.label}: left out, no {source}.csv")
            continue
        names = ([c for c in cols if c.startswith(column[:-1])] if column.endswith("*")
                 else [column] if column in cols else [])
        t = numeric(cols, "time_s")
        shown = 0
        for name in names:
            v = numeric(cols, name)
            ok = np.isfinite(t) & np.isfinite(v)
            if not ok.any():
                continue
            label = run.label if len(names) == 1 else f"{run.label} {name}"
            line, = ax.plot(t[ok], v[ok], marker=".", markersize=3, label=label)
            drawn += 1
            shown += 1
        if shown and after is not None:
            after(ax, run, line)
        if shown == 0:
            why = f"{source}.csv has no values of {column}" if names else f"{source}.csv has no column {column}"
            if names and source == "bubble":
                why += " (no bubble was detected)"
            notes.append(f"{run.label}: left out, {why}")
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


def pressure_columns(cols):
    return [c for c in cols if c.endswith("_p_Pa") or c.endswith("_dp_Pa")]


def uniform_signal(t, v):
    """The signal on a uniform time grid at its median sampling interval (linear interpolation): Welch's method
    needs uniform samples, and probes.interval = 0 samples every adaptive TFM step. Returns (x, fs)."""
    ok = np.isfinite(t) & np.isfinite(v)
    t, v = t[ok], v[ok]
    if t.size < 16:
        return None, None
    dt = float(np.median(np.diff(t)))
    if not dt > 0:
        return None, None
    grid = np.arange(t[0], t[-1] + 0.5 * dt, dt)
    return np.interp(grid, t, v), 1.0 / dt


def figure_probes(runs, path, notes):
    """Probe time series: every pressure and pressure-drop column of every probes.csv (top), voidage (middle), and
    the bed height of any bed_height probe (bottom, only where a run has one)."""
    heights = any(run.probes is not None and any(n.endswith("_bed_height_m") for n in run.probes) for run in runs)
    fig, axes = plt.subplots(3 if heights else 2, 1, figsize=(7, 8 if heights else 6), sharex=True)
    ax_p, ax_e = axes[0], axes[1]
    drawn = 0
    for run in runs:
        if run.probes is None:
            continue
        t = numeric(run.probes, "time_s")
        for name in run.probes:
            if name.endswith("_bed_height_m"):
                ax = axes[2]
            elif name.endswith("_eps"):
                ax = ax_e
            elif name.endswith("_p_Pa") or name.endswith("_dp_Pa"):
                ax = ax_p
            else:
                continue
            v = numeric(run.probes, name)
            ok = np.isfinite(t) & np.isfinite(v)
            if ok.any():
                ax.plot(t[ok], v[ok], lw=0.8, label=f"{run.label} {name}")
                drawn += 1
    if drawn == 0:
        plt.close(fig)
        return "no run has a probes.csv (the case has no [[probe]])"
    ax_p.set_ylabel("pressure (Pa)")
    ax_e.set_ylabel("voidage")
    if heights:
        axes[2].set_ylabel("bed height (m)")
    axes[-1].set_xlabel("time (s)")
    for ax in axes:
        ax.grid(alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=7)
    ax_p.set_title("Probe time series (probes.csv)")
    fig.tight_layout()
    save(fig, path)
    return None


def pressure_spectra(runs):
    """(run, column, mean, std, dominant frequency, f, psd, fs, n) per pressure column of every probes.csv."""
    out = []
    for run in runs:
        if run.probes is None:
            continue
        t = numeric(run.probes, "time_s")
        for name in pressure_columns(run.probes):
            x, fs = uniform_signal(t, numeric(run.probes, name))
            if x is None:
                continue
            f, p, f_dom, std = welch_psd(x, fs)
            out.append((run, name, float(np.mean(x)), std, f_dom, f, p, fs, x.size))
    return out


def figure_pressure_psd(runs, path, notes):
    spectra = pressure_spectra(runs)
    if not spectra:
        return "no pressure probe with 16 samples or more in any probes.csv"
    fig, ax = plt.subplots(figsize=(6, 4))
    for run, name, _, std, f_dom, f, p, _, _ in spectra:
        ax.semilogy(f[1:], p[1:], lw=0.9, label=f"{run.label} {name} (f_dom {f_dom:.2f} Hz, std {std:.0f} Pa)")
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("PSD (Pa²/Hz)")
    ax.set_title("Pressure fluctuations (Welch, Hann, 50% overlap)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    save(fig, path)
    return None


def pressure_table(runs):
    spectra = pressure_spectra(runs)
    if not spectra:
        return ["No probes.csv with a pressure probe (a case's [[probe]] tables add them, docs/analysis.md)."]
    lines = ["Welch PSD of each pressure probe (post/psd.py) after resampling to its median sampling interval; "
             "std is the standard deviation about the mean over the whole run, the frequency resolution fs / "
             "nperseg.", "",
             "| run | probe column | mean (Pa) | std (Pa) | dominant frequency (Hz) | samples | fs (Hz) |",
             "|---|---|---|---|---|---|---|"]
    for run, name, mean, std, f_dom, _, _, fs, n in spectra:
        lines.append(f"| {run.label} | {name} | {mean:.1f} | {std:.1f} | {f_dom:.2f} | {n} | {fs:.0f} |")
    return lines


def figure_rise_vs_correlation(runs, path, notes):
    fig, ax = plt.subplots(figsize=(6, 4))
    d_max = 0.0
    g = G
    drawn = 0
    for run in runs:
        if run.bubble is None:
            notes.append(f"{run.label}: left out, no bubble.csv")
            continue
        d = numeric(run.bubble, "equivalent_diameter_m")
        u = numeric(run.bubble, "rise_velocity_m_s")
        ok = np.isfinite(d) & np.isfinite(u)
        if not ok.any():
            notes.append(f"{run.label}: left out, bubble.csv has no rows with both a diameter and a rise velocity")
            continue
        ax.plot(d[ok], u[ok], "o", markersize=3, label=run.label)
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


def bubbling_statistics(runs):
    """(entries, notes) of post/bubble_stats.run_statistics for the beds without a jet (freely bubbling)."""
    entries, notes = [], []
    for r in runs:
        if r.has_jet() is not False:
            continue
        s, why = bubble_stats.run_statistics(r.folder, r.case, r.dimension, r.gravity)
        if s is None:
            notes.append(f"{r.label}: left out, {why}")
        else:
            entries.append((r.label, s))
    return entries, notes


def figure_bubbling_statistics(runs, path, notes):
    entries, left_out = bubbling_statistics(runs)
    notes += left_out
    if not entries:
        return "no bed without a jet has bubbles in its statistics window"
    bubble_stats.figure_runs(entries, path)
    return None


def figure_time_averages(runs, path, notes):
    entries = []
    for r in runs:
        got = time_averages.read_averages(r.folder)
        if got is None:
            notes.append(f"{r.label}: left out, no averages.csv (no [averages] window reached)")
        else:
            entries.append((r.label, got[0], got[1]))
    if not entries:
        return "no run has averages.csv"
    time_averages.figure(entries, path)
    return None


# ------------------------------------------------------------------------------------------------------ tables

def nearest_row(cols, t):
    """Index of the bubble.csv row whose time is nearest to t, or None unless it lies within half the file's
    sampling interval of t (nearest_within): an instant after the run ended, or in a gap of its rows, has none."""
    times = numeric(cols, "time_s")
    if times.size == 0:
        return None
    return nearest_within(times, t)


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


def jet_runs(runs):
    """Runs the jet-bubble tables apply to, and a sentence naming those left out (beds without a jet)."""
    with_jet = [r for r in runs if r.has_jet() is not False]
    without = [r.label for r in runs if r.has_jet() is False]
    note = []
    if without:
        note = [f"Left out, beds without a jet (case.toml has no [[inlet.jet]] that differs from the inlet, or the "
                f"gas is off), so no jet-formed bubble to follow: {', '.join(without)}."]
    return with_jet, note


def u_mf_of(case):
    """bubble.u_mf of a resolved case.toml (the U_mf that scales the throughflow), else the paper's 1.8 m/s."""
    b = case.get("bubble", {}) if isinstance(case.get("bubble"), dict) else {}
    u = b.get("u_mf")
    return float(u) if isinstance(u, (int, float)) and u > 0 else 1.8


def centroid_throughflow(gas, u_centroid, u_mf):
    """U_th / U_mf with the bubble's own (centroid) rise velocity: (gas velocity at the nose - U_b) / U_mf."""
    if gas in (None, "") or u_centroid in (None, ""):
        return ""
    return repr((float(gas) - float(u_centroid)) / u_mf)


def table2(runs):
    lines = []
    with_jet, note = jet_runs(runs)
    if not with_jet:
        return ["No run has a jet: Table 2 (the jet-formed bubble of the paper) does not apply."] + [""] + note
    with_bubble = [r for r in with_jet if r.bubble is not None]
    no_bubble = [r.label for r in with_jet if r.bubble is None]
    if not with_bubble:
        return ["No run with a jet has a bubble.csv: Table 2 skipped."] + [""] + note
    lines.append("Values are the bubble.csv rows nearest in time to each instant (the row's own time in brackets); "
                 "'–' where the row has no bubble, and where the run has no row within half its sampling interval "
                 "of the instant (an instant after the run ended). The bubble rise velocity U_b is that of the "
                 "bubble's centroid (centroid_rise_velocity_m_s, the usual definition in bubble-tracking studies), "
                 "and U_th/U_mf = (gas velocity at the nose - U_b) / U_mf uses it; the nose rise velocity "
                 "(rise_velocity_m_s, the nose on the jet's vertical line) is beside it: while the bubble grows on "
                 "the jet the nose rises about twice as fast as the centroid.")
    lines.append("")
    head = "| t (s) |"
    sep = "|---|"
    for r in with_bubble:
        head += (f" {r.label}: axial gas velocity at the nose (m/s) | bubble rise velocity U_b, centroid (m/s) |"
                 f" U_th/U_mf (from U_b) | nose rise velocity (m/s) |")
        sep += "---|---|---|---|"
    lines += [head, sep]
    unreached = {}
    for t in TABLE2_TIMES:
        line = f"| {t} |"
        for r in with_bubble:
            k = nearest_row(r.bubble, t)
            if k is None:
                line += " – | – | – | – |"
                unreached.setdefault(r.label, []).append(t)
                continue
            get = lambda c: r.bubble.get(c, [""] * (k + 1))[k]  # noqa: E731
            u_th = centroid_throughflow(get('nose_gas_velocity_m_s'), get('centroid_rise_velocity_m_s'),
                                        u_mf_of(r.case))
            line += (f" {cell(get('nose_gas_velocity_m_s'))} [{cell(get('time_s'), '.3f')}] |"
                     f" {cell(get('centroid_rise_velocity_m_s'))} |"
                     f" {cell(u_th)} |"
                     f" {cell(get('rise_velocity_m_s'))} |")
        lines.append(line)
    if unreached:
        lines += ["", "No bubble.csv row within half the sampling interval ('–'): " + "; ".join(
            f"{lab} at t = {', '.join(f'{t:g}' for t in ts)} s" for lab, ts in unreached.items()) + "."]
    if no_bubble:
        lines += ["", f"Left out, no bubble.csv: {', '.join(no_bubble)}."]
    if note:
        lines += [""] + note
    return lines


def bubble_events(runs):
    with_jet, note = jet_runs(runs)
    if not with_jet:
        return ["No run has a jet: no detachment of a jet-formed bubble to report."] + [""] + note
    lines = ["| run | detachment time (s) | first eruption time (s) |", "|---|---|---|"]
    for r in with_jet:
        if r.bubble is None:
            lines.append(f"| {r.label} | no bubble.csv | no bubble.csv |")
            continue
        t_det = detachment_time(r.bubble)
        t_eru = first_time_where(r.bubble, 'erupted', '1')
        lines.append(f"| {r.label} | {cell(t_det, '.3f') if t_det else 'none'} | "
                     f"{cell(t_eru, '.3f') if t_eru else 'none'} |")
    lines += ["", "Detachment: the first bubble.csv row with attached = 0 after a row with attached = 1."]
    if note:
        lines += [""] + note
    return lines


def cost_table(runs):
    with_cost = [r for r in runs if r.cost is not None]
    if not with_cost:
        return ["No run has a cost.json: cost table skipped."]
    keys = ["cells", "particles", "time_steps", "wall_s", "simulated_s"]
    lines = ["| run | " + " | ".join(keys) + " |", "|---" * (len(keys) + 1) + "|"]
    for r in with_cost:
        lines.append(f"| {r.label} | " + " | ".join(str(r.cost.get(k, "–")) for k in keys) + " |")
    return lines


# -------------------------------------------------------------------------------------------------------- main

def write_animation(run, path, max_frames=120, fps=10):
    """GIF (Pillow, through matplotlib's PillowWriter) of the run's voidage frames (3D: the mid-depth slice) with
    the particles of the particle frame of the same instant over it (DEM), at most max_frames frames evenly
    picked. Returns None, or why it was skipped."""
    from matplotlib.animation import PillowWriter
    if not run.fields:
        return "no field frames"
    step = max(1, math.ceil(len(run.fields) / max_frames))
    frames = run.fields[::step]
    first = read_vti(frames[0][1])
    if first is None:
        return "the first field frame has no voidage"
    particles = {round(t, 9): f for t, f in run.particles}
    ext = [first["x0"], first["x0"] + first["nx"] * first["dx"], first["y0"], first["y0"] + first["ny"] * first["dy"]]
    aspect = (ext[3] - ext[2]) / max(ext[1] - ext[0], 1e-12)
    fig, ax = plt.subplots(figsize=(3.2, min(3.2 * aspect, 6.0) + 0.4))
    im = ax.imshow(first["eps"], origin="lower", extent=ext, cmap=VOIDAGE_CMAP, vmin=0.35, vmax=1.0)
    fig.colorbar(im, ax=ax, label="voidage", shrink=0.8)
    dots = ax.scatter([], [], s=0.8, c="white", alpha=0.6, lw=0)
    title = ax.set_title("")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    writer = PillowWriter(fps=fps)
    with writer.saving(fig, path, dpi=90):
        for t, f in frames:
            v = read_vti(f)
            if v is None:
                continue
            im.set_data(v["eps"])
            pf = particles.get(round(t, 9))
            p = read_vtu(pf) if pf else None
            if p is not None and run.dimension == 3 and run.depth:
                keep = np.abs(p["z"] - 0.5 * run.depth) < 0.5 * p["diameter"]
                dots.set_offsets(np.column_stack([p["x"][keep], p["y"][keep]]))
            elif p is not None:
                dots.set_offsets(np.column_stack([p["x"], p["y"]]))
            title.set_text(f"{run.label}  t = {t:.3f} s")
            writer.grab_frame()
    plt.close(fig)
    return None


def expand_ensembles(folders, labels):
    """Folders with an ensemble.json (written by `fluidbed ensemble`) stand for their members that ended with 0.
    Returns (member folders, their labels, [(ensemble label, [member indices], failed member names)])."""
    labels = labels or unique_labels(folders)
    out_folders, out_labels, groups = [], [], []
    for folder, label in zip(folders, labels):
        path = os.path.join(folder, "ensemble.json")
        if not os.path.isfile(path):
            out_folders.append(folder)
            out_labels.append(label)
            continue
        with open(path) as f:
            members = json.load(f).get("members", [])
        index, failed = [], []
        for m in members:
            sub = os.path.join(folder, str(m.get("folder")))
            if m.get("exit") != 0 or not os.path.isdir(sub):
                failed.append(str(m.get("folder")))
                continue
            index.append(len(out_folders))
            out_folders.append(sub)
            out_labels.append(f"{label}/{m.get('folder')}")
        groups.append((label, index, failed))
    return out_folders, out_labels, groups


def member_values(runs, column, t):
    """The bubble.csv value of `column` nearest in time to t of each run (NaN where empty or absent)."""
    vals = []
    for r in runs:
        k = nearest_row(r.bubble, t) if r.bubble is not None else None
        v = r.bubble.get(column, [""] * (k + 1))[k] if k is not None else ""
        vals.append(float(v) if v not in ("", None) else float("nan"))
    return np.array(vals)


def mean_std(v, fmt=".2f"):
    ok = np.isfinite(v)
    if not ok.any():
        return "–"
    n = int(ok.sum())
    sd = float(np.std(v[ok], ddof=1)) if n > 1 else 0.0
    return f"{np.mean(v[ok]):{fmt}} ± {sd:{fmt}} (n={n})"


def ensemble_table2(runs, groups):
    lines = ["Mean ± sample standard deviation over the members (n: members with a bubble at that row), each "
             "member's bubble.csv row nearest to the instant; U_b is the centroid rise velocity, U_th/U_mf = (gas "
             "velocity at the nose - U_b) / U_mf per member, then averaged.", ""]
    for label, index, failed in groups:
        members = [runs[k] for k in index]
        lines += [f"**{label}**: {len(members)} members" + (f"; failed, left out: {', '.join(failed)}" if failed
                                                             else ""), ""]
        if not members:
            continue
        lines += ["| t (s) | axial gas velocity at the nose (m/s) | bubble rise velocity U_b, centroid (m/s) | "
                  "U_th/U_mf (from U_b) | nose rise velocity (m/s) |", "|---|---|---|---|---|"]
        u_mf = np.array([u_mf_of(r.case) for r in members])
        for t in TABLE2_TIMES:
            gas = member_values(members, "nose_gas_velocity_m_s", t)
            uc = member_values(members, "centroid_rise_velocity_m_s", t)
            nose = member_values(members, "rise_velocity_m_s", t)
            lines.append(f"| {t} | {mean_std(gas)} | {mean_std(uc)} | {mean_std((gas - uc) / u_mf)} | "
                         f"{mean_std(nose)} |")
        # The bubble's events per member, as bubble_events does for one run (n: members where it happened).
        det = np.array([float(t) if t else np.nan for t in (detachment_time(r.bubble) if r.bubble is not None
                                                             else None for r in members)])
        eru = np.array([float(t) if t else np.nan for t in (first_time_where(r.bubble, "erupted", "1")
                                                             if r.bubble is not None else None for r in members)])
        lines += ["", "| detachment time (s) | first eruption time (s) |", "|---|---|",
                  f"| {mean_std(det, '.3f')} | {mean_std(eru, '.3f')} |"]
        lines.append("")
    return lines


def figure_ensemble_bands(runs, groups, path, notes):
    """Mean and mean ± std bands over the members of nose and centroid height and of the bed pressure drop."""
    series = [("bubble", "nose_height_m", "nose height (m)"), ("bubble", "centroid_y_m", "centroid height (m)"),
              ("monitor", "pressure_drop_Pa", "pressure drop (Pa)")]
    fig, axes = plt.subplots(len(series), 1, figsize=(7, 8), sharex=True)
    drawn = 0
    for label, index, _ in groups:
        members = [runs[k] for k in index]
        for ax, (source, column, ylabel) in zip(axes, series):
            curves = []
            grid = None
            for r in members:
                cols = r.bubble if source == "bubble" else r.monitor
                if cols is None or column not in cols:
                    continue
                t, v = numeric(cols, "time_s"), numeric(cols, column)
                if grid is None:
                    grid = t
                # Members share their output instants; interpolation only bridges a member's missing rows.
                ok = np.isfinite(t) & np.isfinite(v)
                if ok.sum() < 2:
                    curves.append(np.full(grid.size, np.nan))
                    continue
                c = np.interp(grid, t[ok], v[ok], left=np.nan, right=np.nan)
                # No value where the member has none (no bubble): the gap stays a gap.
                have = np.isfinite(np.interp(grid, t, np.where(ok, 1.0, np.nan)))
                c[~have] = np.nan
                curves.append(c)
            if grid is None or not curves:
                notes.append(f"{label}: no {column} in the members' {source}.csv")
                continue
            a = np.array(curves)
            n = np.sum(np.isfinite(a), axis=0)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)  # instants where no member has a value
                m = np.nanmean(a, axis=0)
                sd = np.where(n > 1, np.nanstd(a, axis=0, ddof=1), 0.0)
            line, = ax.plot(grid, m, lw=1.2, label=f"{label} mean (n={len(members)})")
            ax.fill_between(grid, m - sd, m + sd, color=line.get_color(), alpha=0.25, lw=0,
                            label=f"{label} ± 1 std")
            ax.set_ylabel(ylabel)
            drawn += 1
    if drawn == 0:
        plt.close(fig)
        return "no member has bubble.csv or monitor.csv values"
    for ax in axes:
        ax.grid(alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=7)
    axes[-1].set_xlabel("time (s)")
    axes[0].set_title("Ensemble mean and spread")
    fig.tight_layout()
    save(fig, path)
    return None


def write_report(folders, out, labels=None, animate=False):
    figdir = os.path.join(out, "figures")
    os.makedirs(figdir, exist_ok=True)
    folders, labels, groups = expand_ensembles(folders, labels)
    runs = [Run(f) for f in folders]
    for r, lab in zip(runs, labels):
        r.label = lab
    figures = [
        ("voidage.png", "Voidage maps at the paper's instants (Fig. 3 layout)",
         lambda p, n: figure_voidage(runs, p, n)),
    ] + ([
        ("voidage_depth_averaged.png", "Depth-averaged voidage maps of the 3D runs",
         lambda p, n: figure_voidage(runs, p, n, depth_averaged=True)),
    ] if any(r.dimension == 3 for r in runs) else []) + [
        ("layers_particles.png", "Particles coloured by initial layer (Fig. 4a)",
         lambda p, n: figure_particles(runs, "layers", p, n)),
        ("species_particles.png", "Particles coloured by species",
         lambda p, n: figure_particles(runs, "species", p, n)),
        ("layers_tracers.png", "Cell tracer balls coloured by initial layer (Fig. 4b/c)",
         lambda p, n: figure_particles(runs, "tracers", p, n)),
        ("nose_height.png", "Bubble nose height",
         lambda p, n: figure_curves(runs, "bubble", "nose_height_m", "nose height (m)", "Bubble nose height", p, n)),
        ("rise_velocity.png", "Bubble rise velocity",
         lambda p, n: figure_curves(runs, "bubble", "rise_velocity_m_s", "rise velocity (m/s)",
                                    "Bubble rise velocity", p, n)),
        ("throughflow_ratio.png", "Throughflow ratio U_th/U_mf",
         lambda p, n: figure_curves(runs, "bubble", "throughflow_ratio", "U_th / U_mf", "Throughflow at the nose",
                                    p, n)),
        ("equivalent_diameter.png", "Bubble equivalent diameter",
         lambda p, n: figure_curves(runs, "bubble", "equivalent_diameter_m", "D = sqrt(4A/pi) (m)",
                                    "Bubble equivalent diameter", p, n)),
        ("rise_vs_correlation.png", "Rise velocity against the 2D correlation",
         lambda p, n: figure_rise_vs_correlation(runs, p, n)),
    ] + ([
        ("bubbling_statistics.png", "Freely bubbling statistics of the beds without a jet (post/bubble_stats.py)",
         lambda p, n: figure_bubbling_statistics(runs, p, n)),
    ] if any(r.has_jet() is False for r in runs) else []) + ([
        ("time_averages.png", "Time-averaged fields of the [averages] window (post/averages.py)",
         lambda p, n: figure_time_averages(runs, p, n)),
    ] if any(os.path.isfile(os.path.join(r.folder, "averages.csv")) for r in runs) else []) + [
        ("pressure_drop.png", "Bed pressure drop, with the bed weight per unit area (dashed)",
         lambda p, n: figure_pressure_drop(runs, p, n)),
        ("mixing_index.png", "Lacey mixing index",
         lambda p, n: figure_curves(runs, "monitor", "lacey*", "Lacey index M", "Mixing index", p, n)),
    ] + ([
        ("probes.png", "Probe time series (probes.csv)", lambda p, n: figure_probes(runs, p, n)),
        ("pressure_psd.png", "Pressure-fluctuation spectra of the pressure probes",
         lambda p, n: figure_pressure_psd(runs, p, n)),
    ] if any(r.probes is not None for r in runs) else []) + ([
        ("ensemble_bands.png", "Ensemble mean and spread (bands: ± 1 standard deviation over the members)",
         lambda p, n: figure_ensemble_bands(runs, groups, p, n)),
    ] if groups else [])
    md = ["# fluidbed report", ""]
    md.append("## Runs")
    md.append("")
    md.append("| run | case | model | jet | folder | notes |")
    md.append("|---|---|---|---|---|---|")
    for r in runs:
        jet = {True: "yes", False: "no", None: "unknown"}[r.has_jet()]
        md.append(f"| {r.label} | {r.name} | {r.model} | {jet} | {r.folder} | "
                  f"{'; '.join(r.notes) if r.notes else '–'} |")
    md += ["", "## Figures", ""]
    for fname, caption, make in figures:
        path = os.path.join(figdir, fname)
        notes = []
        try:
            why = make(path, notes)
        except Exception as e:  # a broken input file skips its figure, never the report
            why = f"failed: {type(e).__name__}: {e}"
            plt.close("all")
        if why is None:
            md.append(f"- {caption}: ![{caption}](figures/{fname})")
        else:
            md.append(f"- {caption}: skipped ({why}).")
        for n in notes:
            md.append(f"  - {n}")
    md += ["", "## Table 2: axial gas velocity at the nose, bubble (centroid) and nose rise velocity, U_th/U_mf", ""]
    md += table2(runs)
    if animate:
        md += ["", "## Animations", ""]
        for r in runs:
            name = f"animation-{''.join(c if c.isalnum() or c in '-_.' else '_' for c in r.label)}.gif"
            why = write_animation(r, os.path.join(figdir, name))
            md.append(f"- {r.label}: ![{r.label}](figures/{name})" if why is None else f"- {r.label}: skipped ({why})")
    if groups:
        md += ["", "## Ensembles: Table 2 as mean ± standard deviation", ""]
        md += ensemble_table2(runs, groups)
    if any(r.probes is not None for r in runs):
        md += ["", "## Pressure fluctuations (probes.csv)", ""]
        md += pressure_table(runs)
    entries, _ = bubbling_statistics(runs) if any(r.has_jet() is False for r in runs) else ([], [])
    if entries:
        md += ["", "## Freely bubbling statistics (beds without a jet; docs/analysis.md, \"Bubble statistics\")", ""]
        md += bubble_stats.table_runs(entries)
    md += ["", "## Bubble events", ""]
    md += bubble_events(runs)
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
    ap.add_argument("--label", action="append", default=None,
                    help="label of a run in legends and tables, once per folder in the order of the folders "
                         "(default: the folder name)")
    ap.add_argument("--animate", action="store_true",
                    help="also write figures/animation-<run>.gif: voidage and particles of every frame (Pillow)")
    args = ap.parse_args(argv)
    missing = [d for d in args.runs if not os.path.isdir(d)]
    if missing:
        print(f"report: not a folder: {', '.join(missing)}", file=sys.stderr)
        return 2
    if args.label is not None:
        if len(args.label) != len(args.runs):
            print(f"report: {len(args.label)} --label for {len(args.runs)} run folders: give one per folder, in "
                  "their order", file=sys.stderr)
            return 2
        dup = sorted({lab for lab in args.label if args.label.count(lab) > 1})
        if dup or any(not lab.strip() for lab in args.label):
            print(f"report: --label values must be non-empty and differ (repeated: {', '.join(dup) or 'an empty one'})",
                  file=sys.stderr)
            return 2
    write_report(args.runs, args.out, args.label, animate=args.animate)
    print(f"report written to {os.path.join(args.out, 'summary.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
