"""Reusable readers and checks for fluidbed's VTK output (.pvd, .vti, .vtu), built on python3-vtk9.

Used by tests/post/test_vtk_readback.py on a sample series written by the unit tests; the same helpers
serve CLI-driven checks of a real output folder (check_fields_series, check_particles_series).
"""
import os
import xml.etree.ElementTree as ET

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


class CheckError(AssertionError):
    pass


def require(condition, message):
    if not condition:
        raise CheckError(message)


def read_pvd(path):
    """Entries of a ParaView collection as a list of (time, absolute file path), in file order."""
    root = ET.parse(path).getroot()
    require(root.tag == "VTKFile" and root.get("type") == "Collection", f"{path}: not a VTK collection")
    folder = os.path.dirname(os.path.abspath(path))
    entries = []
    for ds in root.iter("DataSet"):
        entries.append((float(ds.get("timestep")), os.path.join(folder, ds.get("file"))))
    return entries


def _time_value(data, path):
    arr = data.GetFieldData().GetArray("TimeValue")
    require(arr is not None, f"{path}: no FieldData TimeValue")
    require(arr.GetNumberOfTuples() == 1, f"{path}: TimeValue has {arr.GetNumberOfTuples()} tuples")
    return arr.GetValue(0)


def _arrays(attributes):
    out = {}
    for k in range(attributes.GetNumberOfArrays()):
        arr = attributes.GetArray(k)
        out[arr.GetName()] = vtk_to_numpy(arr)
    return out


def read_vti(path):
    """An ImageData file as a dict: dims (nx, ny) in cells, origin, spacing, time, cell {name: array}."""
    require(os.path.isfile(path), f"{path}: missing")
    reader = vtk.vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    require(data is not None and data.GetNumberOfCells() > 0, f"{path}: no cells read")
    ext = data.GetExtent()
    return {
        "dims": (ext[1] - ext[0], ext[3] - ext[2]),
        "dims3": (ext[1] - ext[0], ext[3] - ext[2], ext[5] - ext[4]),
        "extent": tuple(ext),
        "origin": data.GetOrigin(),
        "spacing": data.GetSpacing(),
        "time": _time_value(data, path),
        "cell": _arrays(data.GetCellData()),
        "n_cells": data.GetNumberOfCells(),
    }


def read_vtu(path):
    """An UnstructuredGrid file as a dict: n, points (n x 3), cell_types, time, point {name: array}."""
    require(os.path.isfile(path), f"{path}: missing")
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    n = data.GetNumberOfPoints()
    points = vtk_to_numpy(data.GetPoints().GetData()) if n > 0 else np.zeros((0, 3))
    types = np.array([data.GetCellType(k) for k in range(data.GetNumberOfCells())], dtype=np.int64)
    return {"n": n, "points": points, "cell_types": types, "time": _time_value(data, path),
            "point": _arrays(data.GetPointData()), "n_cells": data.GetNumberOfCells()}


FIELD_SCALARS = ("voidage", "pressure")
FIELD_VECTORS = ("gas_velocity",)
PARTICLE_ARRAYS = {"id": 1, "species": 1, "diameter": 1, "velocity": 3, "angular_velocity": 1, "layer": 1}


def check_series(pvd_path, reader):
    """Every entry of a collection exists, is readable, times increase, and each file's TimeValue equals the
    .pvd timestep exactly (both are written with 17 significant digits). Returns [(time, data)]."""
    entries = read_pvd(pvd_path)
    require(len(entries) > 0, f"{pvd_path}: empty collection")
    times = [t for t, _ in entries]
    require(all(b > a for a, b in zip(times, times[1:])), f"{pvd_path}: times not increasing: {times}")
    out = []
    for t, f in entries:
        d = reader(f)
        require(d["time"] == t, f"{f}: TimeValue {d['time']!r} differs from the .pvd timestep {t!r}")
        out.append((t, d))
    return out


def check_fields_series(pvd_path, scalars=FIELD_SCALARS, vectors=FIELD_VECTORS):
    """A fields.pvd series: the named cell arrays exist, with nx*ny tuples (vectors 3 components, z = 0)."""
    frames = check_series(pvd_path, read_vti)
    for t, d in frames:
        ncell = d["dims"][0] * d["dims"][1]
        require(d["n_cells"] == ncell, f"t={t}: {d['n_cells']} cells for extent {d['extent']}")
        for name in scalars:
            require(name in d["cell"], f"t={t}: no cell array {name}; has {sorted(d['cell'])}")
            require(d["cell"][name].shape == (ncell,), f"t={t}: {name} shape {d['cell'][name].shape}")
        for name in vectors:
            require(name in d["cell"], f"t={t}: no cell array {name}; has {sorted(d['cell'])}")
            require(d["cell"][name].shape == (ncell, 3), f"t={t}: {name} shape {d['cell'][name].shape}")
            require(np.all(d["cell"][name][:, 2] == 0.0), f"t={t}: {name} has a non-zero z component")
    return frames


def check_particles_series(pvd_path):
    """A particles.pvd series: one vertex per particle, the contract's point arrays, ids sorted and unique."""
    frames = check_series(pvd_path, read_vtu)
    for t, d in frames:
        require(d["n_cells"] == d["n"], f"t={t}: {d['n_cells']} cells for {d['n']} points")
        require(np.all(d["cell_types"] == vtk.VTK_VERTEX), f"t={t}: cells are not all VTK_VERTEX")
        for name, comps in PARTICLE_ARRAYS.items():
            require(name in d["point"], f"t={t}: no point array {name}; has {sorted(d['point'])}")
            shape = (d["n"],) if comps == 1 else (d["n"], comps)
            require(d["point"][name].shape == shape, f"t={t}: {name} shape {d['point'][name].shape}")
        ids = d["point"]["id"]
        require(np.all(np.diff(ids) > 0), f"t={t}: ids not strictly increasing")
        require(np.all(d["points"][:, 2] == 0.0), f"t={t}: points have a non-zero z")
    return frames


# The sample series of tests/unit/io/sample_series.hpp (VtkWriter.WritesSampleSeriesForReadback);
# the formulas repeat the C++ ones operation for operation, so the values agree bit for bit.
SAMPLE_FRAMES = 3
SAMPLE_GRID = {"nx": 4, "ny": 3, "dx": 0.0025, "dy": 0.005, "x0": 0.0, "y0": 0.0}


def sample_time(k):
    return 0.1 * k / 3.0


# The large sample (sample_large_grid, sample_large_particles): several compression blocks per array.
SAMPLE_LARGE_GRID = {"nx": 128, "ny": 64, "dx": 0.0025, "dy": 0.005, "x0": 0.0, "y0": 0.0}
SAMPLE_LARGE_PARTICLES = 20000


def sample_fields(t, g=SAMPLE_GRID):
    n = g["nx"] * g["ny"]
    out = {"voidage": np.zeros(n), "pressure": np.zeros(n), "gas_velocity": np.zeros((n, 3))}
    for j in range(g["ny"]):
        for i in range(g["nx"]):
            c = j * g["nx"] + i
            out["voidage"][c] = 0.4 + 0.01 * i + j / 30.0 + t
            out["pressure"][c] = 101325.0 + 1000.0 * j - t * i
            out["gas_velocity"][c, 0] = i * t
            out["gas_velocity"][c, 1] = -1.0 * j + 0.5
    return out


def sample_particles(t, n=5):
    """Point arrays in id order (ids 0..n-1)."""
    ids = np.arange(n, dtype=np.int64)
    d = ids.astype(np.float64)
    return {
        "id": ids,
        "species": (ids % 2).astype(np.int32),
        "layer": (ids // 2).astype(np.int32),
        "diameter": np.full(n, 2.0 * (0.5 * 0.004)),
        "velocity": np.stack([0.5 * d, np.full(n, -t), np.zeros(n)], axis=1),
        "angular_velocity": 10.0 * d - 1.0,
        "points": np.stack([0.001 * (d + 1.0), 0.002 * d + t, np.zeros(n)], axis=1),
    }


# The 3D sample of tests/unit/io/sample_series.hpp (VtkWriter.WritesSample3dForReadback): 4 x 3 x 2 cells, five
# spheres with z, vz and a spin vector.
SAMPLE_GRID_3D = {"n": (4, 3, 2), "h": (0.0025, 0.005, 0.004), "origin": (0.1, 0.0, 0.002)}


def sample_fields_3d(t):
    nx, ny, nz = SAMPLE_GRID_3D["n"]
    n = nx * ny * nz
    out = {"voidage": np.zeros(n), "pressure": np.zeros(n), "gas_velocity": np.zeros((n, 3))}
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                c = (k * ny + j) * nx + i
                out["voidage"][c] = 0.4 + 0.01 * i + j / 30.0 + k / 7.0 + t
                out["pressure"][c] = 1000.0 * j - k
                out["gas_velocity"][c] = (i * t, 0.5 - j, 0.25 * k - t)
    return out


def sample_particles_3d(t, n=5):
    """Point arrays in id order (ids 0..n-1) of the 3D sample."""
    ids = np.arange(n, dtype=np.int64)
    d = ids.astype(np.float64)
    return {
        "id": ids,
        "species": (ids % 2).astype(np.int32),
        "layer": (ids // 2).astype(np.int32),
        "diameter": 2.0 * (0.002 + 0.0005 * d),
        "velocity": np.stack([0.5 * d, np.full(n, -t), 0.25 * d], axis=1),
        "angular_velocity": np.stack([d, -2.0 * d, 10.0 * d - 1.0], axis=1),
        "points": np.stack([0.001 * (d + 1.0), 0.002 * d + t, 0.003 * d], axis=1),
    }


ZLIB_HEADER = 'header_type="UInt64" compressor="vtkZLibDataCompressor"'


def require_compressed(path):
    """The file declares VTK's zlib block compression with UInt64 headers (what fluidbed writes)."""
    with open(path, "rb") as f:
        head = f.read(512).decode("ascii", errors="replace")
    require(ZLIB_HEADER in head, f"{path}: not zlib-compressed with UInt64 headers:\n{head[:200]}")
