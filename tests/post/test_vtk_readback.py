"""Read fluidbed's VTK output back with python-vtk (as ParaView would) and compare with the values written.

argv[1]: the fluidbed binary (its folder holds tests/test_unit_io), argv[2]: the repository root.
The unit test VtkWriter.WritesSampleSeriesForReadback writes a small series (sample formulas in vtk_check.py,
sample_series.hpp) into $FLUIDBED_VTK_SAMPLE_DIR; this script checks names, shapes, times and values.
Values are compared exactly: the writers store float64 losslessly (zlib), and both sides compute them with the
same IEEE operations in the same order. Every file must declare vtkZLibDataCompressor with UInt64 headers.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_check as vc  # noqa: E402


# A real run (the small bed of test_cli_readback.py): field frames every 5 ms, particle frames every 10 ms.
RUN_CASE = """case.name = "particle-interval"
case.end_time = 0.02
case.seed = 3
domain.width = 0.1
domain.height = 0.2
particles.count = 200
particles.fill_height = 0.1
settle.enabled = false
dem.time_step = 1e-4
grid.cell_width = 0.01
coupling.dem_substeps = 2
output.interval = 0.005
output.particle_interval = 0.01
output.monitor_interval = 0.001
output.checkpoint_interval = 0.005
output.particles_csv = true
[[inlet.jet]]
centre = 0.055
width = 0.01
velocity = 20.0
"""


def run_cli(args, expect=0):
    res = subprocess.run(args, capture_output=True, text=True)
    vc.require(res.returncode == expect, f"{' '.join(args)} exited {res.returncode}, expected {expect}:\n"
                                         f"{res.stdout}\n{res.stderr}")
    return res


def check_particle_interval(exe, tmp):
    """output.particle_interval: particle frames (.vtu and .csv) at every second field frame, with the field
    frame's number and instant, also after a restart from a checkpoint between two particle frames; every file of
    the run is zlib-compressed and read by VTK. Returns the number of particle frames."""
    case = os.path.join(tmp, "pi.toml")
    with open(case, "w") as f:
        f.write(RUN_CASE)
    out = os.path.join(tmp, "pi")
    run_cli([exe, "run", case, "--out", out, "--quiet"])

    def check(folder):
        fields = vc.check_fields_series(os.path.join(folder, "fields.pvd"), vectors=("gas_velocity",))
        parts = vc.check_particles_series(os.path.join(folder, "particles.pvd"))
        vc.require([round(t / 0.005) for t, _ in fields] == [0, 1, 2, 3, 4], f"field frames at {[t for t, _ in fields]}")
        vc.require([t for t, _ in parts] == [t for t, _ in fields][::2], f"particle frames at {[t for t, _ in parts]}")
        field_files = dict(vc.read_pvd(os.path.join(folder, "fields.pvd")))
        for t, f in vc.read_pvd(os.path.join(folder, "particles.pvd")):
            vc.require(os.path.basename(f)[:6] == os.path.basename(field_files[t])[:6],
                       f"particle frame {f} is not numbered as the field frame {field_files[t]} of t = {t}")
        names = sorted(os.listdir(os.path.join(folder, "particles")))
        vc.require(names == [f"{k:06d}.{e}" for k in (0, 2, 4) for e in ("csv", "vtu")], f"particles/: {names}")
        for sub in ("fields", "particles"):
            for name in os.listdir(os.path.join(folder, sub)):
                if name.endswith((".vti", ".vtu")):
                    vc.require_compressed(os.path.join(folder, sub, name))
        return parts

    first = check(out)
    # Continue from the checkpoint at 5 ms (frame 1, no particle frame): frames 2 and 4 are written again.
    checkpoint = os.path.join(out, "checkpoints", "t0.005000.h5")
    vc.require(os.path.isfile(checkpoint), f"no checkpoint {checkpoint}: {os.listdir(os.path.join(out, 'checkpoints'))}")
    run_cli([exe, "run", case, "--out", out, "--quiet", "--restart", checkpoint])
    second = check(out)
    for (t, a), (_, b) in zip(first, second):
        vc.require(np.array_equal(a["points"], b["points"]), f"t = {t}: the restart gives other positions")

    # Not a whole multiple of the field interval: exit 2 naming the key.
    bad = run_cli([exe, "check", case, "--set", "output.particle_interval=0.0075"], expect=2)
    vc.require("output.particle_interval" in bad.stderr and "0.005" in bad.stderr, f"message: {bad.stderr}")
    return len(first)


def main():
    if len(sys.argv) < 2:
        print("usage: test_vtk_readback.py FLUIDBED_BINARY [REPO_ROOT]")
        return 2
    gtest = os.path.join(os.path.dirname(os.path.abspath(sys.argv[1])), "tests", "test_unit_io")
    vc.require(os.path.isfile(gtest), f"{gtest}: not built (build the test_unit_io target)")

    with tempfile.TemporaryDirectory(prefix="fluidbed_vtk_readback_") as out:
        env = dict(os.environ, FLUIDBED_VTK_SAMPLE_DIR=out)
        run = subprocess.run([gtest, "--gtest_filter=VtkWriter.WritesSampleSeriesForReadback"], env=env,
                             capture_output=True, text=True)
        vc.require(run.returncode == 0, f"{gtest} failed:\n{run.stdout}\n{run.stderr}")
        vc.require("[  PASSED  ] 1 test" in run.stdout, f"the sample test did not run:\n{run.stdout}")

        fields = vc.check_fields_series(os.path.join(out, "fields.pvd"))
        vc.require(len(fields) == vc.SAMPLE_FRAMES, f"{len(fields)} field frames, {vc.SAMPLE_FRAMES} written")
        g = vc.SAMPLE_GRID
        for k, (t, d) in enumerate(fields):
            vc.require(t == vc.sample_time(k), f"frame {k}: time {t!r}, written {vc.sample_time(k)!r}")
            vc.require(d["dims"] == (g["nx"], g["ny"]), f"frame {k}: {d['dims']} cells")
            vc.require(d["extent"] == (0, g["nx"], 0, g["ny"], 0, 0), f"frame {k}: extent {d['extent']}")
            vc.require(tuple(d["origin"][:2]) == (g["x0"], g["y0"]), f"frame {k}: origin {d['origin']}")
            vc.require(tuple(d["spacing"][:2]) == (g["dx"], g["dy"]), f"frame {k}: spacing {d['spacing']}")
            expected = vc.sample_fields(t)
            for name, values in expected.items():
                got = d["cell"][name]
                vc.require(got.dtype == np.float64, f"frame {k}: {name} is {got.dtype}")
                vc.require(np.array_equal(got, values), f"frame {k}: {name} differs:\n{got}\nexpected\n{values}")

        particles = vc.check_particles_series(os.path.join(out, "particles.pvd"))
        vc.require(len(particles) == vc.SAMPLE_FRAMES, f"{len(particles)} particle frames")
        for k, (t, d) in enumerate(particles):
            expected = vc.sample_particles(t)
            vc.require(d["n"] == 5, f"frame {k}: {d['n']} particles")
            vc.require(np.array_equal(d["points"], expected.pop("points")), f"frame {k}: positions differ")
            for name, values in expected.items():
                got = d["point"][name]
                vc.require(got.dtype == values.dtype, f"frame {k}: {name} is {got.dtype}, expected {values.dtype}")
                vc.require(np.array_equal(got, values), f"frame {k}: {name} differs: {got} vs {values}")

        # Every file is zlib-compressed; VTK reads them value for value, arrays of several blocks included.
        for name in sorted(os.listdir(os.path.join(out, "fields"))):
            vc.require_compressed(os.path.join(out, "fields", name))
        for name in sorted(os.listdir(os.path.join(out, "particles"))):
            vc.require_compressed(os.path.join(out, "particles", name))
        t1 = vc.sample_time(1)
        large = vc.read_vti(os.path.join(out, "large.vti"))
        vc.require_compressed(os.path.join(out, "large.vti"))
        lg = vc.SAMPLE_LARGE_GRID
        vc.require(large["dims"] == (lg["nx"], lg["ny"]) and large["time"] == t1, f"large.vti: {large['dims']}")
        for name, values in vc.sample_fields(t1, lg).items():
            got = large["cell"][name]
            vc.require(got.dtype == np.float64 and np.array_equal(got, values), f"large.vti: {name} differs")
        big = vc.read_vtu(os.path.join(out, "large.vtu"))
        vc.require_compressed(os.path.join(out, "large.vtu"))
        expected = vc.sample_particles(t1, vc.SAMPLE_LARGE_PARTICLES)
        vc.require(big["n"] == vc.SAMPLE_LARGE_PARTICLES, f"large.vtu: {big['n']} particles")
        vc.require(np.array_equal(big["points"], expected.pop("points")), "large.vtu: positions differ")
        for name, values in expected.items():
            got = big["point"][name]
            vc.require(got.dtype == values.dtype and np.array_equal(got, values), f"large.vtu: {name} differs")
        empty = vc.read_vtu(os.path.join(out, "empty.vtu"))
        vc.require(empty["n"] == 0 and empty["n_cells"] == 0, f"empty.vtu: {empty['n']} points")

        print(f"vtk readback: {len(fields)} .vti and {len(particles)} .vtu frames, and frames of "
              f"{vc.SAMPLE_LARGE_PARTICLES} particles and {lg['nx']} x {lg['ny']} cells, read with VTK "
              f"{vc.vtk.vtkVersion.GetVTKVersion()}; names, shapes, times and values match exactly")
        n = check_particle_interval(os.path.abspath(sys.argv[1]), out)
        print(f"output.particle_interval: {n} particle frames at every second field frame, also after a restart")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except vc.CheckError as e:
        print(f"FAILED: {e}")
        sys.exit(1)
