#!/usr/bin/python3
"""post/report.py on synthetic run folders: every figure is written and not blank, Table 2 and the detachment
time in summary.md are the bubble.csv values, a run without a bubble or without files does not break the report.

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


def write_vti(path, t, void_y):
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk

    img = vtk.vtkImageData()
    img.SetExtent(0, NX, 0, NY, 0, 0)
    img.SetOrigin(0.0, 0.0, 0.0)
    img.SetSpacing(DX, DX, 1.0)
    xc = (np.arange(NX) + 0.5) * DX
    yc = (np.arange(NY) + 0.5) * DX
    X, Y = np.meshgrid(xc, yc)  # [j, i], i fastest when flattened
    eps = np.where(Y < BED_TOP, 0.43, 1.0)
    eps = np.where(np.hypot(X - 0.3, Y - void_y) < 0.06, 1.0, eps)
    for name, data in [("voidage", eps.ravel()), ("pressure", (1.0 - Y).ravel())]:
        arr = numpy_to_vtk(np.ascontiguousarray(data, dtype=np.float64), deep=1)
        arr.SetName(name)
        img.GetCellData().AddArray(arr)
    vel = np.zeros((NX * NY, 3))
    vel[:, 1] = 1.8
    arr = numpy_to_vtk(vel, deep=1)
    arr.SetName("gas_velocity")
    img.GetCellData().AddArray(arr)
    w = vtk.vtkXMLImageDataWriter()
    w.SetFileName(path)
    w.SetInputData(img)
    assert w.Write() == 1


def write_vtu(path, rng, n=400):
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk

    pts = np.zeros((n, 3))
    pts[:, 0] = rng.uniform(0.01, 0.59, n)
    pts[:, 1] = rng.uniform(0.01, BED_TOP, n)
    grid = vtk.vtkUnstructuredGrid()
    p = vtk.vtkPoints()
    p.SetData(numpy_to_vtk(pts, deep=1))
    grid.SetPoints(p)
    for k in range(n):
        grid.InsertNextCell(vtk.VTK_VERTEX, 1, [k])
    arrays = {"id": np.arange(n, dtype=np.int64), "species": np.zeros(n, dtype=np.int32),
              "diameter": np.full(n, 0.004), "velocity": np.zeros((n, 3)), "angular_velocity": np.zeros(n),
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


def make_run(root, name, model, end, with_particles, with_bubble, rng):
    d = os.path.join(root, name)
    os.makedirs(d)
    with open(os.path.join(d, "case.toml"), "w") as f:
        f.write(f'[case]\nname = "{name}"\nmodel = "{model}"\n')
    if end > 0:
        os.makedirs(os.path.join(d, "fields"))
        os.makedirs(os.path.join(d, "tracers"))
        fields, parts = [], []
        if with_particles:
            os.makedirs(os.path.join(d, "particles"))
        for k in range(1, int(round(end / 0.1)) + 1):
            t = round(0.1 * k, 10)
            rel = f"fields/{k:06d}.vti"
            write_vti(os.path.join(d, rel), t, 0.1 + 0.8 * t)
            fields.append((t, rel))
            if with_particles:
                relp = f"particles/{k:06d}.vtu"
                write_vtu(os.path.join(d, relp), rng)
                parts.append((t, relp))
            with open(os.path.join(d, f"tracers/{k:06d}.csv"), "w") as f:
                f.write("ball_id,x,y,layer\n")
                for b in range(NX * 27):
                    i, j = b % NX, b // NX
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
        rows.append([repr(t), repr(nose), "" if k == 1 else repr(ub), repr(ug), "" if k == 1 else repr((ug - ub) / 1.8),
                     repr(area), "1" if t < 0.255 else "0", repr(math.sqrt(4 * area / math.pi)), repr(BED_TOP), "0",
                     "0", "0.3"])
    with open(os.path.join(d, "bubble.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time_s", "nose_height_m", "rise_velocity_m_s", "nose_gas_velocity_m_s", "throughflow_ratio",
                    "bubble_area_m2", "attached", "equivalent_diameter_m", "bed_height_m", "erupted", "bubble_id",
                    "nose_x_m"])
        w.writerows(rows)
    return d, rows


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


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
        # Table 2: columns are the runs with a bubble.csv, in order; three cells per run.
        checked = 0
        for t in [0.2, 0.3, 0.4, 0.5]:
            line = next((ln for ln in summary.splitlines() if ln.startswith(f"| {t} |")), None)
            if line is None:
                fail(f"Table 2 has no row for t = {t}")
            cells = [c.strip() for c in line.strip().strip("|").split("|")][1:]
            for r, rows in enumerate([dem_rows, tfm_rows, None]):
                got = cells[3 * r:3 * r + 3]
                if rows is None:
                    if got != ["– [0.2]", "–", "–"] and not all(g.startswith("–") for g in got):
                        fail(f"no-bubble run has values in Table 2: {got}")
                    continue
                k = int(np.argmin([abs(float(row[0]) - t) for row in rows]))
                want = [f"{float(rows[k][3]):.2f} [{float(rows[k][0]):.3f}]", f"{float(rows[k][2]):.2f}",
                            f"{float(rows[k][4]):.2f}"]
                if got != want:
                    fail(f"Table 2 at t = {t}, run {r}: {got} != {want}")
                checked += 1
        if checked != 8:
            fail(f"checked {checked} Table 2 entries, expected 8")
        # Detachment: the first row with attached = 0 after attached = 1.
        for name, rows in [("gera-dem", dem_rows), ("gera-tfm", tfm_rows)]:
            t_det = next(rows[k][0] for k in range(1, len(rows)) if rows[k][6] == "0" and rows[k - 1][6] == "1")
            if f"| {name} ({name[5:]}) | {float(t_det):.3f} |" not in summary:
                fail(f"detachment time {t_det} of {name} not in summary.md")
        if "no fields.pvd frames" not in summary:
            fail("the run without fields is not noted in summary.md")
        if "| gera-dem (dem) | 1500 | 400 | 1000 | 12.5 | 0.5 |" not in summary:
            fail("cost table does not show cost.json of gera-dem")

        # A report over a run that has nothing but a case file still succeeds.
        bare = os.path.join(tmp, "bare")
        os.makedirs(bare)
        res = subprocess.run([sys.executable, script, bare, "--out", os.path.join(tmp, "r2")], capture_output=True,
                             text=True)
        if res.returncode != 0 or not os.path.isfile(os.path.join(tmp, "r2", "summary.md")):
            fail(f"report of an empty folder failed: {res.stderr}")
    print("post report: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
