"""Read fluidbed's 3D VTK frames back with python-vtk (as ParaView would) and compare with the values written.

argv[1]: the fluidbed binary (its folder holds tests/test_unit_io). The unit test
VtkWriter.WritesSample3dForReadback writes 3d.vti (4 x 3 x 2 cells: voidage, pressure, a 3-component gas
velocity) and 3d.vtu (five spheres stored out of id order: 3D positions, velocities and spin vectors) into
$FLUIDBED_VTK_SAMPLE_DIR; the formulas are repeated in vtk_check.py (sample_*_3d). Values are compared exactly:
the writer stores float64 losslessly (zlib) and both sides compute them with the same IEEE operations.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_check as vc  # noqa: E402


def main():
    if len(sys.argv) < 2:
        print("usage: test_vtk_readback_3d.py FLUIDBED_BINARY [REPO_ROOT]")
        return 2
    gtest = os.path.join(os.path.dirname(os.path.abspath(sys.argv[1])), "tests", "test_unit_io")
    vc.require(os.path.isfile(gtest), f"{gtest}: not built (build the test_unit_io target)")
    with tempfile.TemporaryDirectory(prefix="fluidbed_vtk_readback_3d_") as out:
        env = dict(os.environ, FLUIDBED_VTK_SAMPLE_DIR=out)
        run = subprocess.run([gtest, "--gtest_filter=VtkWriter.WritesSample3dForReadback"], env=env,
                             capture_output=True, text=True)
        vc.require(run.returncode == 0, f"{gtest} failed:\n{run.stdout}\n{run.stderr}")
        vc.require("[  PASSED  ] 1 test" in run.stdout, f"the sample test did not run:\n{run.stdout}")
        t = vc.sample_time(2)

        path = os.path.join(out, "3d.vti")
        vc.require_compressed(path)
        d = vc.read_vti(path)
        g = vc.SAMPLE_GRID_3D
        vc.require(d["dims3"] == g["n"], f"3d.vti: {d['dims3']} cells, written {g['n']}")
        vc.require(d["n_cells"] == np.prod(g["n"]), f"3d.vti: {d['n_cells']} cells")
        vc.require(tuple(d["origin"]) == g["origin"], f"3d.vti: origin {d['origin']}")
        vc.require(tuple(d["spacing"]) == g["h"], f"3d.vti: spacing {d['spacing']}")
        vc.require(d["time"] == t, f"3d.vti: time {d['time']!r}, written {t!r}")
        for name, values in vc.sample_fields_3d(t).items():
            got = d["cell"][name]
            vc.require(got.dtype == np.float64 and got.shape == values.shape, f"3d.vti: {name} {got.dtype} {got.shape}")
            vc.require(np.array_equal(got, values), f"3d.vti: {name} differs:\n{got}\nexpected\n{values}")
        # The cell at (i, j, k) = (3, 2, 1) is where VTK puts it: the z layers are stacked, i fastest.
        cell = d["cell"]["voidage"].reshape(g["n"][2], g["n"][1], g["n"][0])[1, 2, 3]
        vc.require(cell == 0.4 + 0.01 * 3 + 2 / 30.0 + 1 / 7.0 + t, f"3d.vti: cell (3, 2, 1) holds {cell}")

        path = os.path.join(out, "3d.vtu")
        vc.require_compressed(path)
        p = vc.read_vtu(path)
        expected = vc.sample_particles_3d(t)
        vc.require(p["n"] == 5 and p["n_cells"] == 5, f"3d.vtu: {p['n']} points, {p['n_cells']} cells")
        vc.require(np.all(p["cell_types"] == vc.vtk.VTK_VERTEX), "3d.vtu: cells are not all VTK_VERTEX")
        vc.require(np.array_equal(p["points"], expected.pop("points")), f"3d.vtu: positions differ:\n{p['points']}")
        for name, values in expected.items():
            got = p["point"][name]
            vc.require(got.dtype == values.dtype and got.shape == values.shape,
                       f"3d.vtu: {name} is {got.dtype} {got.shape}, expected {values.dtype} {values.shape}")
            vc.require(np.array_equal(got, values), f"3d.vtu: {name} differs:\n{got}\nexpected\n{values}")
        print(f"vtk readback 3D: 3d.vti ({g['n'][0]} x {g['n'][1]} x {g['n'][2]} cells, 3-component gas velocity) "
              f"and 3d.vtu (5 spheres: positions, velocities, spin vectors) read with VTK "
              f"{vc.vtk.vtkVersion.GetVTKVersion()}; shapes, times and values match exactly")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except vc.CheckError as e:
        print(f"FAILED: {e}")
        sys.exit(1)
