#!/usr/bin/env python3
"""post/averages.py on a synthetic averages.csv: a 2D grid of 4 x 3 cells whose voidage is 0.4 + 0.1 i + 0.01 j and
whose particle-weighted vertical solids velocity is j - i, one cell without solids (empty values). read_averages must
put every value at its [j, i] exactly (the CSV carries the shortest round-trip text, so equality is exact), NaN for
the empty cell, read the window from averages.json; a 3D file is read on its mid-depth layer; the figure is
written. Usage (CTest): test_averages.py FLUIDBED_BINARY SOURCE_DIR"""
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(sys.argv[2], "post"))
import averages  # noqa: E402

failures = 0


def check(name, ok):
    global failures
    failures += not ok
    print(f"{name}: {'ok' if ok else 'FAIL'}")


def write(folder, dim):
    cols = ["i", "j"] + (["k"] if dim == 3 else []) + ["x_m", "y_m"] + (["z_m"] if dim == 3 else []) + ["voidage"]
    ax = "xyz"[:dim]
    cols += [f"ug_{a}_m_s" for a in ax] + [f"us_cell_{a}_m_s" for a in ax] + [f"us_particle_{a}_m_s" for a in ax]
    cols += ["granular_temperature_m2_s2", "solids_presence"]
    with open(os.path.join(folder, "averages.csv"), "w") as fh:
        fh.write(",".join(cols) + "\n")
        for k in range(3 if dim == 3 else 1):
            for j in range(3):
                for i in range(4):
                    v = {"i": i, "j": j, "k": k, "x_m": 0.01 + 0.02 * i, "y_m": 0.01 + 0.02 * j, "z_m": 0.01 + 0.02 * k,
                         "voidage": 0.4 + 0.1 * i + 0.01 * j + 0.001 * k, "granular_temperature_m2_s2": 0.01 * k,
                         "solids_presence": 1}
                    for a in ax:
                        v[f"ug_{a}_m_s"] = 1.0
                        v[f"us_cell_{a}_m_s"] = j - i
                        v[f"us_particle_{a}_m_s"] = j - i
                    row = [repr(float(v[c])) if c not in ("i", "j", "k") else str(v[c]) for c in cols]
                    if (i, j) == (3, 2):
                        row = [r if c in ("i", "j", "k", "x_m", "y_m", "z_m", "voidage", "solids_presence")
                               or c.startswith("ug_") else "" for c, r in zip(cols, row)]
                    fh.write(",".join(row) + "\n")
    with open(os.path.join(folder, "averages.json"), "w") as fh:
        json.dump({"samples": 5, "first_sample_s": 1.0, "last_sample_s": 2.0}, fh)


for dim in (2, 3):
    with tempfile.TemporaryDirectory() as d:
        write(d, dim)
        f, meta = averages.read_averages(d)
        k = 1 if dim == 3 else 0
        check(f"{dim}D: shape [j, i]", f["voidage"].shape == (3, 4))
        check(f"{dim}D: voidage at [j, i] (mid-depth layer in 3D)",
              all(f["voidage"][j, i] == 0.4 + 0.1 * i + 0.01 * j + 0.001 * k for j in range(3) for i in range(4)))
        check(f"{dim}D: particle-weighted v_y at [j, i]",
              all(f["us_particle_y_m_s"][j, i] == j - i for j in range(3) for i in range(4) if (i, j) != (3, 2)))
        check(f"{dim}D: a cell without solids is NaN", math.isnan(f["us_particle_y_m_s"][2, 3]))
        check(f"{dim}D: metadata", meta["samples"] == 5 and meta["dimension"] == dim)
        averages.figure([("synthetic", f, meta)], os.path.join(d, "a.png"))
        check(f"{dim}D: figure written", os.path.getsize(os.path.join(d, "a.png")) > 1000)
with tempfile.TemporaryDirectory() as d:
    check("no averages.csv: None", averages.read_averages(d) is None)
sys.exit(1 if failures else 0)
