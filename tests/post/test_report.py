#!/usr/bin/python3
"""post/report.py on synthetic run folders: every figure is written and not blank, Table 2 and the detachment
time in summary.md are the bubble.csv values, a run without a bubble or without files does not break the report.
Issue 11 (item 17): runs of one case in two folders get distinct labels (folder names, or --label); a bed without
a jet has no Table 2 column and no detachment row; a run without frames at the paper's instants keeps its row in
voidage.png and summary.md says why; a two-species run gets a figure coloured by species; a tall narrow bed gets
panels of its own shape and a bounded height.

Usage (ctest): test_report.py FLUIDBED_BINARY REPO_ROOT. Exits non-zero on failure.
"""

import csv
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

NX, NY, DX = 30, 50, 0.02
BED_TOP = 0.54
JET = '[inlet]\nvelocity = 1.8\n[[inlet.jet]]\ncentre = 0.31\nwidth = 0.02\nvelocity = 30.0\nstart = 0.0\nend = 0.4\n'
NO_JET = '[inlet]\nvelocity = 3.6\n'


def write_vti(path, t, void_y, nx=NX, ny=NY):
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk

    img = vtk.vtkImageData()
    img.SetExtent(0, nx, 0, ny, 0, 0)
    img.SetOrigin(0.0, 0.0, 0.0)
    img.SetSpacing(DX, DX, 1.0)
    xc = (np.arange(nx) + 0.5) * DX
    yc = (np.arange(ny) + 0.5) * DX
    X, Y = np.meshgrid(xc, yc)  # [j, i], i fastest when flattened
    eps = np.where(Y < BED_TOP, 0.43, 1.0)
    eps = np.where(np.hypot(X - 0.5 * nx * DX, Y - void_y) < 0.06, 1.0, eps)
    for name, data in [("voidage", eps.ravel()), ("pressure", (1.0 - Y).ravel())]:
        arr = numpy_to_vtk(np.ascontiguousarray(data, dtype=np.float64), deep=1)
        arr.SetName(name)
        img.GetCellData().AddArray(arr)
    vel = np.zeros((nx * ny, 3))
    vel[:, 1] = 1.8
    arr = numpy_to_vtk(vel, deep=1)
    arr.SetName("gas_velocity")
    img.GetCellData().AddArray(arr)
    w = vtk.vtkXMLImageDataWriter()
    w.SetFileName(path)
    w.SetInputData(img)
    assert w.Write() == 1


def write_vtu(path, rng, n=400, species=1, width=0.6):
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk

    pts = np.zeros((n, 3))
    pts[:, 0] = rng.uniform(0.01, width - 0.01, n)
    pts[:, 1] = rng.uniform(0.01, BED_TOP, n)
    grid = vtk.vtkUnstructuredGrid()
    p = vtk.vtkPoints()
    p.SetData(numpy_to_vtk(pts, deep=1))
    grid.SetPoints(p)
    for k in range(n):
        grid.InsertNextCell(vtk.VTK_VERTEX, 1, [k])
    sp = (np.arange(n) % species).astype(np.int32)
    arrays = {"id": np.arange(n, dtype=np.int64), "species": sp,
              "diameter": np.where(sp == 0, 0.004, 0.008), "velocity": np.zeros((n, 3)), "angular_velocity": np.zeros(n),
              "layer": (pts[:, 1] / 0.09).astype(np.int32)}
    for name, data in arrays.items():
        arr = numpy_to_vtk(data, deep=1)
        arr.SetName(name)
        grid.GetPointData().AddArray(arr)
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(path)
    w.SetInputData(grid)
    assert w.Write() == 1


def write_pvd(path, entries):
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n')
        for t, rel in entries:
            f.write(f'<DataSet timestep="{t!r}" group="" part="0" file="{rel}"/>\n')
        f.write("</Collection>\n</VTKFile>\n")


def make_run(root, name, model, end, with_particles, with_bubble, rng, jet=True, case_name=None, species=1,
             nx=NX, ny=NY, frame_times=None):
    d = os.path.join(root, name)
    os.makedirs(d)
    with open(os.path.join(d, "case.toml"), "w") as f:
        f.write(f'[case]\nname = "{case_name or name}"\nmodel = "{model}"\n')
        f.write(f"[domain]\nwidth = {nx * DX}\nheight = {ny * DX}\n")
        f.write(JET if jet else NO_JET)
        for k in range(species):
            f.write(f"[[species]]\ndiameter = {0.004 * (k + 1)}\ndensity = 2700.0\n")
    if end > 0:
        os.makedirs(os.path.join(d, "fields"))
        os.makedirs(os.path.join(d, "tracers"))
        fields, parts = [], []
        if with_particles:
            os.makedirs(os.path.join(d, "particles"))
        times = frame_times or [round(0.1 * k, 10) for k in range(1, int(round(end / 0.1)) + 1)]
        for k, t in enumerate(times, start=1):
            rel = f"fields/{k:06d}.vti"
            write_vti(os.path.join(d, rel), t, 0.1 + 0.8 * t, nx, ny)
            fields.append((t, rel))
            if with_particles:
                relp = f"particles/{k:06d}.vtu"
                write_vtu(os.path.join(d, relp), rng, species=species, width=nx * DX)
                parts.append((t, relp))
            with open(os.path.join(d, f"tracers/{k:06d}.csv"), "w") as f:
                f.write("ball_id,x,y,layer\n")
                for b in range(nx * 27):
                    i, j = b % nx, b // nx
                    f.write(f"{b},{(i + 0.5) * DX + 0.01 * t},{(j + 0.5) * DX},{j // 3}\n")
        write_pvd(os.path.join(d, "fields.pvd"), fields)
        if with_particles:
            write_pvd(os.path.join(d, "particles.pvd"), parts)
        with open(os.path.join(d, "monitor.csv"), "w") as f:
            f.write("time_s,kinetic_energy_J,pressure_drop_Pa,max_overlap_m,gas_mass_residual,solids_mass_kg,"
                    "wall_s,lacey_index\n")
            for k in range(0, int(round(end / 0.01)) + 1):
                t = 0.01 * k
                f.write(f"{t!r},{0.1 * t!r},{7000 + 300 * math.sin(20 * t)!r},1e-5,1e-9,3.5,{2 * t!r},"
                        f"{min(1.0, t)!r}\n")
        with open(os.path.join(d, "cost.json"), "w") as f:
            json.dump({"cells": NX * NY, "particles": 400 if with_particles else 0, "time_steps": 1000,
                       "wall_s": 12.5, "simulated_s": end}, f)
    rows = []
    n = int(round(max(end, 0.6) / 0.01))
    for k in range(1, n + 1):
        t = 0.01 * k
        if not with_bubble:
            rows.append([repr(t), "", "", "", "", "", "", "", repr(BED_TOP), "0", "", ""])
            continue
        nose = 0.05 + 0.9 * t + 0.001 * rng.standard_normal()
        ub = 0.9 + 0.05 * rng.standard_normal()
        ug = 2.0 + rng.uniform()
        area = 0.003 + 0.002 * t
        uc = 0.5 * ub  # the centroid of a bubble growing on the jet rises about half as fast as its nose
        rows.append([repr(t), repr(nose), "" if k == 1 else repr(ub), repr(ug), "" if k == 1 else repr((ug - ub) / 1.8),
                     repr(area), "1" if t < 0.255 else "0", repr(math.sqrt(4 * area / math.pi)), repr(BED_TOP), "0",
                     "0", "0.3", repr(0.5 * nose), "" if k == 1 else repr(uc)])
    with open(os.path.join(d, "bubble.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time_s", "nose_height_m", "rise_velocity_m_s", "nose_gas_velocity_m_s", "throughflow_ratio",
                    "bubble_area_m2", "attached", "equivalent_diameter_m", "bed_height_m", "erupted", "bubble_id",
                    "nose_x_m", "centroid_y_m", "centroid_rise_velocity_m_s"])
        w.writerows(rows)
    return d, rows


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


def capture_figures(report):
    """Replace report.save by one that records, per figure file, the figure size and every axes' labels,
    legend, artists and drawn size (inches), then saves as before."""
    figs = {}
    original = report.save

    def save(fig, path):
        fig.canvas.draw()
        axes = []
        for ax in fig.axes:
            box = ax.get_window_extent()
            legend = ax.get_legend()
            axes.append({"ylabel": ax.get_ylabel(), "title": ax.get_title(), "images": len(ax.images),
                         "colours": [c.get_facecolors() for c in ax.collections], "on": ax.axison,
                         "w_in": box.width / fig.dpi, "h_in": box.height / fig.dpi,
                         "legend": [t.get_text() for t in legend.get_texts()] if legend else []})
        figs[os.path.basename(path)] = {"size": tuple(fig.get_size_inches()), "axes": axes}
        original(fig, path)

    report.save = save
    return figs


def rows_of(fig):
    """The run labels of a bed figure's rows (the first column's y labels: 'RUN\ny (m)' of a panel, 'RUN' of a '–'
    panel; not the colour bar's)."""
    return [a["ylabel"].split("\n")[0] for a in fig["axes"] if a["ylabel"] and "voidage" not in a["ylabel"]]


def check_issue11(repo, tmp, rng):
    sys.path.insert(0, os.path.join(repo, "post"))
    import report
    from matplotlib.colors import to_rgba

    figs = capture_figures(report)
    root = os.path.join(tmp, "i11")
    # A --set sweep: two folders of the same case; two more whose folder names only differ higher up.
    u20, _ = make_run(root, "u-2.0", "dem", 0.5, True, True, rng, case_name="bubbling")
    u25, _ = make_run(root, "u-2.5", "dem", 0.5, True, True, rng, case_name="bubbling")
    free, _ = make_run(root, "free", "tfm", 0.5, False, True, rng, jet=False)
    short, _ = make_run(root, "short", "tfm", 0.065, False, True, rng,
                        frame_times=[0.013, 0.026, 0.039, 0.052, 0.065])
    binary, _ = make_run(root, "binary", "dem", 0.3, True, True, rng, species=2)
    out = os.path.join(tmp, "r11")
    report.write_report([u20, u25, free, short, binary], out)
    summary = open(os.path.join(out, "summary.md")).read()

    # Labels: folder names, distinct although the case is the same; in the tables and in the legends.
    for lab in ("u-2.0", "u-2.5"):
        if f"| {lab} | bubbling | dem | yes |" not in summary:
            fail(f"runs table has no row labelled {lab}:\n{summary}")
    legend = next(a["legend"] for a in figs["nose_height.png"]["axes"] if a["legend"])
    if legend[:2] != ["u-2.0", "u-2.5"] or len(set(legend)) != len(legend):
        fail(f"nose_height.png legend {legend}")
    if rows_of(figs["voidage.png"])[:2] != ["u-2.0", "u-2.5"]:
        fail(f"voidage.png rows {rows_of(figs['voidage.png'])}")

    # No jet: no Table 2 column, no detachment row, and the reason.
    table2 = summary.split("## Table 2")[1].split("## Bubble events")[0]
    events = summary.split("## Bubble events")[1].split("## Cost")[0]
    if "free:" in table2 or "| free |" in events:
        fail(f"the bed without a jet has Table 2 or detachment entries:\n{table2}\n{events}")
    for part in (table2, events):
        if "beds without a jet" not in part or "free" not in part:
            fail(f"the bed without a jet is not named as left out:\n{part}")
    if "| u-2.0: axial gas velocity" not in table2 or "| u-2.0 |" not in events:
        fail("a bed with a jet lost its Table 2 or detachment entries")

    # No frame at the paper's instants that the other runs reach: the run keeps its row, '–' at every instant (its
    # own frames are not put under instants they are not at), and summary.md says why.
    if "short" not in rows_of(figs["voidage.png"]):
        fail(f"the run without frames at the paper's instants is not in voidage.png: {rows_of(figs['voidage.png'])}")
    if "short: no field frames within half its frame interval of the paper's instants" not in summary:
        fail(f"summary.md does not say why short has no panel:\n{summary}")
    titles = [a["title"] for a in figs["voidage.png"]["axes"] if a["images"]]
    if any(f"t = {t} s" in titles for t in ("0.013", "0.026", "0.039", "0.052", "0.065")):
        fail(f"short's own frames are shown under the paper's instants: {titles}")
    # Alone (no run reaches the paper's instants), the same run shows its own instants.
    report.write_report([short], os.path.join(tmp, "r11-short"))
    titles = [a["title"] for a in figs["voidage.png"]["axes"] if a["images"]]
    if "t = 0.013 s" not in titles or "t = 0.065 s" not in titles:
        fail(f"short's own instants are not the panel times: {titles}")
    # The runs shorter than 1 s have their missing instants named.
    if "binary: no panel at t = 0.4" not in summary:
        fail("the panels a short run lacks are not named")

    # Species: a figure of the two-species run coloured by species, in the species' colours, with a legend.
    if not os.path.isfile(os.path.join(out, "figures", "species_particles.png")):
        fail("no species_particles.png for the two-species run")
    sp = figs["species_particles.png"]
    if rows_of(sp) != ["binary"]:
        fail(f"species_particles.png rows {rows_of(sp)} (only the two-species run mixes species)")
    drawn = np.concatenate([c for a in sp["axes"] for c in a["colours"] if len(c)])
    for k in (0, 1):
        want = np.array(to_rgba(report.SPECIES_COLOURS[k]))
        if not np.any(np.all(np.abs(drawn - want) < 1e-6, axis=1)):
            fail(f"species {k} colour {report.SPECIES_COLOURS[k]} not drawn")
    labels = [t for a in sp["axes"] for t in a["legend"]]
    if labels != ["species 0: d = 4 mm, 2700 kg/m^3", "species 1: d = 8 mm, 2700 kg/m^3"]:
        fail(f"species legend {labels}")
    if "u-2.0: left out, its particles are all of one species" not in summary:
        fail("single-species runs are not named as left out of the species figure")
    lay = figs["layers_particles.png"]
    if rows_of(lay) != ["u-2.0", "u-2.5", "binary"]:
        fail(f"layers_particles.png rows {rows_of(lay)}")

    # A tall narrow bed (0.1 x 1.0 m): panels keep its shape at a bounded height.
    tall, _ = make_run(root, "tall", "tfm", 0.3, False, True, rng, nx=5, ny=50)
    report.write_report([tall], os.path.join(tmp, "r11-tall"))
    v = figs["voidage.png"]
    maps = [a for a in v["axes"] if a["images"]]
    if v["size"][1] > 6.0:
        fail(f"voidage.png of one tall bed is {v['size'][1]:.1f} in tall")
    for a in maps:
        if not (2.5 < a["h_in"] < 5.0) or abs(a["h_in"] / a["w_in"] - 10.0) > 0.5:
            fail(f"a tall bed panel is {a['w_in']:.2f} x {a['h_in']:.2f} in (the bed is 0.1 x 1.0 m)")
    t = figs["layers_tracers.png"]
    if t["size"][1] > 6.0:
        fail(f"layers_tracers.png of one tall bed is {t['size'][1]:.1f} in tall")

    # --label: one per folder; a wrong count or a repeated label is exit 2.
    script = os.path.join(repo, "post", "report.py")
    lab_out = os.path.join(tmp, "r11-label")
    res = subprocess.run([sys.executable, script, u20, u25, "--label", "U = 2.0 m/s", "--label", "U = 2.5 m/s",
                          "--out", lab_out], capture_output=True, text=True)
    if res.returncode != 0:
        fail(f"report with --label exited {res.returncode}: {res.stderr}")
    labelled = open(os.path.join(lab_out, "summary.md")).read()
    if "| U = 2.0 m/s | bubbling |" not in labelled or "| U = 2.5 m/s | bubbling |" not in labelled:
        fail(f"--label not used:\n{labelled}")
    for bad in (["--label", "one"], ["--label", "same", "--label", "same"]):
        res = subprocess.run([sys.executable, script, u20, u25, *bad, "--out", lab_out], capture_output=True, text=True)
        if res.returncode != 2 or "--label" not in res.stderr:
            fail(f"{bad}: exit {res.returncode}, {res.stderr!r}")
    # Folders named alike (a/run, b/run) are told apart by their parents.
    a_run, _ = make_run(os.path.join(root, "a"), "run", "tfm", 0.2, False, False, rng)
    b_run, _ = make_run(os.path.join(root, "b"), "run", "tfm", 0.2, False, False, rng)
    if report.unique_labels([a_run, b_run]) != ["a/run", "b/run"]:
        fail(f"labels of a/run, b/run: {report.unique_labels([a_run, b_run])}")


def main():
    repo = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "..", "..")
    script = os.path.join(repo, "post", "report.py")
    rng = np.random.default_rng(7)
    with tempfile.TemporaryDirectory() as tmp:
        dem, dem_rows = make_run(tmp, "gera-dem", "dem", 0.5, True, True, rng)
        tfm, tfm_rows = make_run(tmp, "gera-tfm", "tfm", 1.0, False, True, rng)
        quiet, _ = make_run(tmp, "no-bubble", "tfm", 0.0, False, False, rng)
        out = os.path.join(tmp, "report")
        res = subprocess.run([sys.executable, script, dem, tfm, quiet, "--out", out], capture_output=True, text=True)
        if res.returncode != 0:
            fail(f"report.py exited {res.returncode}\n{res.stdout}\n{res.stderr}")

        import matplotlib.image as mpimg

        expected = ["voidage.png", "layers_particles.png", "layers_tracers.png", "nose_height.png",
                    "rise_velocity.png", "throughflow_ratio.png", "equivalent_diameter.png", "rise_vs_correlation.png",
                    "pressure_drop.png", "mixing_index.png"]
        for name in expected:
            path = os.path.join(out, "figures", name)
            if not os.path.isfile(path):
                fail(f"missing figure {name}")
            img = mpimg.imread(path)
            if not float(np.var(img[..., :3])) > 0.0:
                fail(f"blank figure {name}")

        with open(os.path.join(out, "summary.md")) as f:
            summary = f.read()
        # Table 2: columns are the runs with a bubble.csv, in order; four cells per run: gas velocity at the nose,
        # centroid rise velocity U_b, U_th/U_mf from U_b (U_mf = 1.8 m/s, the default), nose rise velocity.
        checked = 0
        for t in [0.2, 0.3, 0.4, 0.5]:
            line = next((ln for ln in summary.splitlines() if ln.startswith(f"| {t} |")), None)
            if line is None:
                fail(f"Table 2 has no row for t = {t}")
            cells = [c.strip() for c in line.strip().strip("|").split("|")][1:]
            for r, rows in enumerate([dem_rows, tfm_rows, None]):
                got = cells[4 * r:4 * r + 4]
                if rows is None:
                    if not all(g.startswith("–") for g in got):
                        fail(f"no-bubble run has values in Table 2: {got}")
                    continue
                k = int(np.argmin([abs(float(row[0]) - t) for row in rows]))
                uc = rows[k][13]
                want = [f"{float(rows[k][3]):.2f} [{float(rows[k][0]):.3f}]",
                        f"{float(uc):.2f}" if uc else "–",
                        f"{(float(rows[k][3]) - float(uc)) / 1.8:.2f}" if uc else "–",
                        f"{float(rows[k][2]):.2f}" if rows[k][2] else "–"]
                if got != want:
                    fail(f"Table 2 at t = {t}, run {r}: {got} != {want}")
                checked += 1
        if checked != 8:
            fail(f"checked {checked} Table 2 entries, expected 8")
        # Detachment: the first row with attached = 0 after attached = 1.
        for name, rows in [("gera-dem", dem_rows), ("gera-tfm", tfm_rows)]:
            t_det = next(rows[k][0] for k in range(1, len(rows)) if rows[k][6] == "0" and rows[k - 1][6] == "1")
            if f"| {name} | {float(t_det):.3f} |" not in summary:
                fail(f"detachment time {t_det} of {name} not in summary.md")
        if "no fields.pvd frames" not in summary:
            fail("the run without fields is not noted in summary.md")
        if "| gera-dem | 1500 | 400 | 1000 | 12.5 | 0.5 |" not in summary:
            fail("cost table does not show cost.json of gera-dem")

        # A report over a run that has nothing but a case file still succeeds.
        bare = os.path.join(tmp, "bare")
        os.makedirs(bare)
        res = subprocess.run([sys.executable, script, bare, "--out", os.path.join(tmp, "r2")], capture_output=True,
                             text=True)
        if res.returncode != 0 or not os.path.isfile(os.path.join(tmp, "r2", "summary.md")):
            fail(f"report of an empty folder failed: {res.stderr}")
        check_issue11(repo, tmp, rng)
    print("post report: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
