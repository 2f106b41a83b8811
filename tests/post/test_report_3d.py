#!/usr/bin/python3
"""post/report.py on a synthetic 3D run folder (issue 12): the voidage figure shows the mid-depth slice, a
depth-averaged figure is added, particle panels show the spheres the mid-depth plane cuts, summary.md says so;
a 2D report has no depth-averaged figure. The run is 3D by case.toml's case.dimension, or, without it, by its field
frames' extent (z cells).

The voidage has a bubble only in the back half of the depth (k >= nz / 2), so the mid-depth slice (the mean of the
two layers either side of z = D/2 for even nz) and the depth average differ from every single layer and from each
other: both are checked exactly against numpy on the values written.

Usage (ctest): test_report_3d.py FLUIDBED_BINARY REPO_ROOT. Exits non-zero on failure.
"""

import os
import sys
import tempfile

import numpy as np

NX, NY, NZ, H = 10, 20, 4, 0.02
DEPTH = NZ * H


def fail(msg):
    print(f"FAILED: {msg}")
    sys.exit(1)


def voidage(t):
    """(nz, ny, nx) voidage: a bed up to 0.2 m, a bubble in the back half of the depth."""
    z = (np.arange(NZ) + 0.5) * H
    y = (np.arange(NY) + 0.5) * H
    x = (np.arange(NX) + 0.5) * H
    Z, Y, X = np.meshgrid(z, y, x, indexing="ij")
    eps = np.where(Y < 0.2, 0.43, 1.0)
    return np.where((np.hypot(X - 0.1, Y - 0.1 - t) < 0.05) & (Z > 0.5 * DEPTH), 0.95, eps)


def write_vti(path, t):
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk

    img = vtk.vtkImageData()
    img.SetExtent(0, NX, 0, NY, 0, NZ)
    img.SetOrigin(0.0, 0.0, 0.0)
    img.SetSpacing(H, H, H)
    arr = numpy_to_vtk(np.ascontiguousarray(voidage(t).ravel(), dtype=np.float64), deep=1)  # i fastest
    arr.SetName("voidage")
    img.GetCellData().AddArray(arr)
    w = vtk.vtkXMLImageDataWriter()
    w.SetFileName(path)
    w.SetInputData(img)
    assert w.Write() == 1


def write_vtu(path, rng, n=600):
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk

    pts = np.stack([rng.uniform(0, NX * H, n), rng.uniform(0, 0.2, n), rng.uniform(0, DEPTH, n)], axis=1)
    poly = vtk.vtkPoints()
    poly.SetData(numpy_to_vtk(pts, deep=1))
    grid = vtk.vtkUnstructuredGrid()
    grid.SetPoints(poly)
    for k in range(n):
        grid.InsertNextCell(vtk.VTK_VERTEX, 1, [k])
    for name, data in [("layer", (pts[:, 1] / 0.05).astype(np.int32)), ("species", np.zeros(n, np.int32)),
                       ("diameter", np.full(n, 0.004)), ("id", np.arange(n, dtype=np.int64))]:
        a = numpy_to_vtk(data, deep=1)
        a.SetName(name)
        grid.GetPointData().AddArray(a)
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(path)
    w.SetInputData(grid)
    assert w.Write() == 1
    return pts


def make_run(folder, with_dimension, rng):
    os.makedirs(os.path.join(folder, "fields"))
    os.makedirs(os.path.join(folder, "particles"))
    case = f'[case]\nname = "slab"\nmodel = "dem"\n'
    if with_dimension:
        case += "dimension = 3\n"
    case += f"[domain]\nwidth = {NX * H}\nheight = {NY * H}\ndepth = {DEPTH}\n"
    with open(os.path.join(folder, "case.toml"), "w") as f:
        f.write(case)
    entries_f, entries_p = [], []
    for k, t in enumerate([0.1, 0.2]):
        write_vti(os.path.join(folder, "fields", f"{k:06d}.vti"), t)
        write_vtu(os.path.join(folder, "particles", f"{k:06d}.vtu"), rng)
        entries_f.append(f'<DataSet timestep="{t}" group="" part="0" file="fields/{k:06d}.vti"/>')
        entries_p.append(f'<DataSet timestep="{t}" group="" part="0" file="particles/{k:06d}.vtu"/>')
    # Tracer balls of a 3D run (ball_id,x,y,z,layer): one per cell of the lower half, two layers.
    os.makedirs(os.path.join(folder, "tracers"))
    for k in range(2):
        with open(os.path.join(folder, "tracers", f"{k:06d}.csv"), "w") as f:
            f.write("ball_id,x,y,z,layer\n")
            n = 0
            for kz in range(NZ):
                for j in range(NY // 2):
                    for i in range(NX):
                        f.write(f"{n},{(i + 0.5) * H},{(j + 0.5) * H},{(kz + 0.5) * H},{j * 2 // (NY // 2)}\n")
                        n += 1
    for name, entries in (("fields", entries_f), ("particles", entries_p)):
        with open(os.path.join(folder, f"{name}.pvd"), "w") as f:
            f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                    + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")


def not_blank(path):
    import matplotlib.image as mpimg

    img = mpimg.imread(path)
    return img.std() > 0.01


def main():
    root = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "..", "..")
    sys.path.insert(0, os.path.join(root, "post"))
    import report

    rng = np.random.default_rng(12)
    with tempfile.TemporaryDirectory(prefix="fluidbed_report_3d_") as tmp:
        run = os.path.join(tmp, "slab")
        make_run(run, True, rng)
        f = report.read_vti(os.path.join(run, "fields", "000000.vti"))
        eps3 = voidage(0.1)
        if f["dimension"] != 3 or f["eps3"].shape != (NZ, NY, NX):
            fail(f"read_vti: dimension {f['dimension']}, shape {f['eps3'].shape}")
        slice_expected = 0.5 * (eps3[NZ // 2 - 1] + eps3[NZ // 2])
        if not np.array_equal(f["eps"], slice_expected):
            fail("the mid-depth slice is not the mean of the two layers either side of z = D/2")
        if not np.array_equal(f["eps_mean"], eps3.mean(axis=0)):
            fail("the depth average differs from numpy's mean over k")
        if np.array_equal(f["eps"], f["eps_mean"]) or any(np.array_equal(f["eps"], eps3[k]) for k in range(NZ)):
            fail("the sample does not tell the slice from the average or from a layer")
        print(f"mid-depth slice: max {f['eps'].max():.3f} (bubble half seen), depth average: max "
              f"{f['eps_mean'].max():.4f}; both exact")

        out = os.path.join(tmp, "report")
        runs = report.write_report([run], out)
        if runs[0].dimension != 3 or runs[0].depth != DEPTH:
            fail(f"run dimension {runs[0].dimension}, depth {runs[0].depth}")
        summary = open(os.path.join(out, "summary.md")).read()
        for name in ("voidage.png", "voidage_depth_averaged.png", "layers_particles.png", "layers_tracers.png"):
            path = os.path.join(out, "figures", name)
            if not os.path.isfile(path) or not not_blank(path):
                fail(f"{name} missing or blank; summary:\n{summary}")
        if "no tracer frames" in summary:
            fail(f"the 3D run's tracer frames were not read:\n{summary}")
        for text in ("its panels show the mid-depth slice z = D/2", "the spheres the mid-depth plane z = D/2 cuts",
                     "Depth-averaged voidage maps of the 3D runs: ![" ):
            if text not in summary:
                fail(f"summary.md lacks '{text}':\n{summary}")

        # Without case.dimension (an older case.toml), the frames' extent says 3D.
        older = os.path.join(tmp, "older")
        make_run(older, False, rng)
        if report.Run(older).dimension != 3:
            fail("a run with 3D frames and no case.dimension is not seen as 3D")

        # A 2D run gets no depth-averaged figure.
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import test_report as t2d

        flat = os.path.join(tmp, "flat")
        os.makedirs(os.path.join(flat, "fields"))
        t2d.write_vti(os.path.join(flat, "fields", "000000.vti"), 0.1, 0.3)
        with open(os.path.join(flat, "fields.pvd"), "w") as fh:
            fh.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                     '<DataSet timestep="0.1" group="" part="0" file="fields/000000.vti"/>\n</Collection>\n</VTKFile>\n')
        out2 = os.path.join(tmp, "report2")
        report.write_report([flat], out2)
        s2 = open(os.path.join(out2, "summary.md")).read()
        if "epth-averaged" in s2 or "mid-depth" in s2 or os.path.exists(os.path.join(out2, "figures",
                                                                                    "voidage_depth_averaged.png")):
            fail(f"a 2D report mentions depth:\n{s2}")
    print("report 3D: mid-depth slice and depth-averaged voidage figures, particle slice, notes; 2D report unchanged")
    return 0


if __name__ == "__main__":
    sys.exit(main())
