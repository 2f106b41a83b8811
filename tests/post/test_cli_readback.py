#!/usr/bin/python3
"""A real run's output folder read back as a user would (issue 6): a small CFD-DEM case run with the CLI, its
fields.pvd / particles.pvd read with VTK, monitor.csv and bubble.csv against the columns of shared/interface.md,
and the written case.toml checked and re-run to the same particles.

Usage (ctest): test_cli_readback.py FLUIDBED_BINARY REPO_ROOT. Exits non-zero on failure.
"""
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_check as vc  # noqa: E402

# 200 particles in a 0.1 x 0.2 m bed of 10 x 20 cells with a jet; 100 gas steps, a frame every 25.
NX, NY, N_PARTICLES = 10, 20, 200
END_TIME, INTERVAL, GAS_DT = 0.02, 0.005, 2e-4
CASE = f"""case.name = "readback"
case.end_time = {END_TIME}
case.seed = 3
domain.width = 0.1
domain.height = 0.2
particles.count = {N_PARTICLES}
particles.fill_height = 0.1
particles.layers = 2
settle.enabled = false
dem.time_step = 1e-4
grid.cell_width = 0.01
coupling.dem_substeps = 2
output.interval = {INTERVAL}
output.monitor_interval = 0.001
output.checkpoint_interval = 0.0
output.particles_csv = true
[[inlet.jet]]
centre = 0.055
width = 0.01
velocity = 20.0
"""
MONITOR_COLUMNS = ["time_s", "kinetic_energy_J", "pressure_drop_Pa", "max_overlap_m", "gas_mass_residual",
                   "solids_mass_kg", "wall_s"]
BUBBLE_COLUMNS = ["time_s", "nose_height_m", "rise_velocity_m_s", "nose_gas_velocity_m_s", "throughflow_ratio",
                  "bubble_area_m2", "attached"]


def run(args):
    res = subprocess.run(args, capture_output=True, text=True)
    vc.require(res.returncode == 0, f"{' '.join(args)} exited {res.returncode}:\n{res.stdout}\n{res.stderr}")
    return res


def read_csv(path):
    vc.require(os.path.isfile(path), f"{path}: missing")
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    vc.require(len(rows) >= 1, f"{path}: empty")
    return rows[0], rows[1:]


def check_fields(out):
    frames = vc.check_fields_series(os.path.join(out, "fields.pvd"), vectors=("gas_velocity", "solids_velocity"))
    vc.require(len(frames) == round(END_TIME / INTERVAL) + 1, f"{len(frames)} field frames")
    for k, (t, d) in enumerate(frames):
        # Frames are due at k * interval and stamped with that instant exactly (the gas step divides the
        # interval), in the .pvd and in the file itself: not a sum of steps such as 0.19001999999995264.
        vc.require(t == k * INTERVAL, f"field frame {k} at t = {t!r}, not {k * INTERVAL!r}")
        vc.require(d["dims"] == (NX, NY), f"t={t}: {d['dims']} cells, the case has {NX} x {NY}")
        vc.require(np.allclose(d["spacing"][:2], (0.01, 0.01), rtol=1e-12, atol=0), f"t={t}: spacing {d['spacing']}")
        eps = d["cell"]["voidage"]
        vc.require(np.all(np.isfinite(eps)) and np.all((eps > 0) & (eps <= 1)), f"t={t}: voidage outside (0, 1]")
        for name in ("pressure", "gas_velocity", "solids_velocity"):
            vc.require(np.all(np.isfinite(d["cell"][name])), f"t={t}: {name} not finite")
    return frames


def check_particles(out, field_frames):
    frames = vc.check_particles_series(os.path.join(out, "particles.pvd"))
    vc.require([t for t, _ in frames] == [t for t, _ in field_frames], "particle and field frames at other times")
    for k, (t, d) in enumerate(frames):
        vc.require(d["n"] == N_PARTICLES, f"t={t}: {d['n']} particles, {N_PARTICLES} placed")
        ids = d["point"]["id"]
        vc.require(np.array_equal(ids, np.arange(N_PARTICLES)), f"t={t}: ids are not 0..{N_PARTICLES - 1}")
        vc.require(np.all(d["point"]["diameter"] == 0.004), f"t={t}: diameters differ from the case's 4 mm")
        vc.require(set(np.unique(d["point"]["layer"])) <= {0, 1}, f"t={t}: layers outside 0..1")
        # The full-precision CSV of the same frame holds the same doubles (both are written from one store).
        header, rows = read_csv(os.path.join(out, "particles", f"{k:06d}.csv"))
        vc.require(header == ["id", "x", "y", "vx", "vy", "omega", "species"], f"particles CSV header {header}")
        a = np.array([[float(v) for v in r] for r in rows])
        vc.require(a.shape == (N_PARTICLES, 7), f"t={t}: particles CSV shape {a.shape}")
        a = a[np.argsort(a[:, 0], kind="stable")]
        vc.require(np.array_equal(a[:, 0], ids.astype(float)), f"t={t}: CSV ids differ from the .vtu ids")
        vc.require(np.array_equal(a[:, 1:3], d["points"][:, :2]), f"t={t}: CSV positions differ from the .vtu")
        vc.require(np.array_equal(a[:, 3:5], d["point"]["velocity"][:, :2]), f"t={t}: CSV velocities differ")
        vc.require(np.array_equal(a[:, 5], d["point"]["angular_velocity"]), f"t={t}: CSV spins differ")
        vc.require(np.array_equal(a[:, 6], d["point"]["species"].astype(float)), f"t={t}: CSV species differ")
        vc.require(np.all((a[:, 1] >= 0) & (a[:, 1] <= 0.1) & (a[:, 2] >= 0) & (a[:, 2] <= 0.2)),
                   f"t={t}: a particle outside the domain")
    # Something happened: the particles fell, so the frames are not all the same.
    vc.require(not np.array_equal(frames[0][1]["points"], frames[-1][1]["points"]), "particles did not move")
    return frames


def check_monitor(out):
    header, rows = read_csv(os.path.join(out, "monitor.csv"))
    vc.require(header[0] == "time_s", f"monitor.csv starts with {header[0]!r}, not time_s")
    missing = [c for c in MONITOR_COLUMNS if c not in header]
    vc.require(not missing, f"monitor.csv lacks {missing}; has {header}")
    vc.require(len(header) == len(set(header)), f"monitor.csv repeats a column: {header}")
    vc.require(len(rows) == round(END_TIME / 0.001) + 1, f"monitor.csv has {len(rows)} rows")
    times = []
    for r in rows:
        vc.require(len(r) == len(header), f"monitor.csv row of {len(r)} values for {len(header)} columns: {r}")
        values = {c: (float(v) if v != "" else None) for c, v in zip(header, r)}
        for c in MONITOR_COLUMNS:
            vc.require(values[c] is not None and np.isfinite(values[c]), f"monitor.csv {c} = {values[c]!r}")
        times.append(values["time_s"])
        # The mass of the particles is that of 200 spheres of 4 mm and 2700 kg/m^3, every row.
        mass = N_PARTICLES * 2700.0 * np.pi / 6 * 0.004 ** 3
        vc.require(abs(values["solids_mass_kg"] - mass) <= 1e-12 * mass, f"solids_mass_kg {values['solids_mass_kg']}")
    vc.require(all(b > a for a, b in zip(times, times[1:])), "monitor.csv times not increasing")
    off = [(k, t) for k, t in enumerate(times) if t != k * 0.001]
    vc.require(not off, f"monitor.csv times that are not k * 0.001 s exactly: {off[:3]}")


def check_bubble(out):
    path = os.path.join(out, "bubble.csv")
    vc.require(os.path.isfile(path), f"{path}: missing (interface.md: bubble.csv in every run folder)")
    header, rows = read_csv(path)
    vc.require(header[:len(BUBBLE_COLUMNS)] == BUBBLE_COLUMNS, f"bubble.csv header {header}")
    for r in rows:
        vc.require(len(r) == len(header), f"bubble.csv row of {len(r)} values for {len(header)} columns")
        vc.require(r[header.index("attached")] in ("0", "1", ""), f"bubble.csv attached = {r[6]!r}")


def main():
    if len(sys.argv) < 2:
        print("usage: test_cli_readback.py FLUIDBED_BINARY [REPO_ROOT]")
        return 2
    exe = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory(prefix="fluidbed_cli_readback_") as tmp:
        case = os.path.join(tmp, "readback.toml")
        with open(case, "w") as f:
            f.write(CASE)
        out = os.path.join(tmp, "out")
        run([exe, "run", case, "--out", out, "--quiet"])
        fields = check_fields(out)
        particles = check_particles(out, fields)
        check_monitor(out)
        check_bubble(out)

        # The written case.toml is complete: `check` accepts it and a run of it gives the same particles.
        resolved = os.path.join(out, "case.toml")
        run([exe, "check", resolved])
        again = os.path.join(tmp, "again")
        run([exe, "run", resolved, "--out", again, "--quiet"])
        for k in range(len(particles)):
            rel = os.path.join("particles", f"{k:06d}.csv")
            with open(os.path.join(out, rel), "rb") as a, open(os.path.join(again, rel), "rb") as b:
                vc.require(a.read() == b.read(), f"{rel} of the re-run case.toml differs")
        print(f"cli readback: {len(fields)} field and {len(particles)} particle frames read with VTK "
              f"{vc.vtk.vtkVersion.GetVTKVersion()}; monitor.csv, bubble.csv and case.toml as in interface.md")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except vc.CheckError as e:
        print(f"FAILED: {e}")
        sys.exit(1)
