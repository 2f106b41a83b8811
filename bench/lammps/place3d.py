#!/usr/bin/env python3
"""One random, non-overlapping placement of equal spheres in a 3D box, written both as a fluidbed particle CSV
(3D columns) and as a LAMMPS data file (atom_style sphere), so that both codes start from the same doubles.

Sites of a cubic lattice of pitch d + gap fill the box; `count` of them are drawn at random (seeded) and each
sphere is shifted by a random jitter of at most 0.45 gap / 2 per axis, so that no two spheres touch and none
touches a wall. Velocities and spins are zero.
"""
import argparse
import random

# fluidbed's 3D particle CSV header (src/io/csv.cpp adds z, vz and the three spin components in 3D).
CSV_COLUMNS = ["id", "x", "y", "z", "vx", "vy", "vz", "omega_x", "omega_y", "omega_z", "species"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--count", type=int, required=True)
    ap.add_argument("--width", type=float, required=True, help="x, m")
    ap.add_argument("--height", type=float, required=True, help="y (up), m")
    ap.add_argument("--depth", type=float, required=True, help="z, m")
    ap.add_argument("--diameter", type=float, default=0.004)
    ap.add_argument("--density", type=float, default=2700.0)
    ap.add_argument("--gap", type=float, default=0.0004, help="lattice pitch minus diameter, m")
    ap.add_argument("--seed", type=int, default=1998)
    ap.add_argument("--csv", required=True, help="fluidbed particle CSV to write")
    ap.add_argument("--data", help="LAMMPS data file to write")
    a = ap.parse_args()

    pitch = a.diameter + a.gap
    nx, ny, nz = (int(length // pitch) for length in (a.width, a.height, a.depth))
    sites = nx * ny * nz
    if a.count > sites:
        raise SystemExit(f"{a.count} spheres do not fit: the box holds {sites} lattice sites "
                         f"({nx} x {ny} x {nz} of pitch {pitch} m)")
    rng = random.Random(a.seed)
    chosen = sorted(rng.sample(range(sites), a.count))
    jitter = 0.45 * a.gap / 2
    # Centre the lattice in the box so the margin to every wall is at least pitch / 2 - jitter > radius.
    off = [(length - n * pitch) / 2 + pitch / 2 for length, n in ((a.width, nx), (a.height, ny), (a.depth, nz))]
    pos = []
    for s in chosen:
        i, rest = s % nx, s // nx
        k, j = rest % nz, rest // nz   # j (height) slowest: ids rise with height
        pos.append((off[0] + i * pitch + rng.uniform(-jitter, jitter),
                    off[1] + j * pitch + rng.uniform(-jitter, jitter),
                    off[2] + k * pitch + rng.uniform(-jitter, jitter)))

    with open(a.csv, "w") as f:
        f.write(",".join(CSV_COLUMNS) + "\n")
        for n, (x, y, z) in enumerate(pos):
            f.write(f"{n},{x!r},{y!r},{z!r},0,0,0,0,0,0,0\n")
    if a.data:
        with open(a.data, "w") as f:
            f.write(f"random placement (place3d.py, seed {a.seed}), same as {a.csv}\n\n{a.count} atoms\n1 atom types\n\n")
            f.write(f"0.0 {a.width!r} xlo xhi\n0.0 {a.height!r} ylo yhi\n0.0 {a.depth!r} zlo zhi\n\n")
            f.write("Atoms # sphere\n\n")
            for n, (x, y, z) in enumerate(pos):
                f.write(f"{n + 1} 1 {a.diameter!r} {a.density!r} {x!r} {y!r} {z!r}\n")
    fill = a.count * 3.141592653589793 * a.diameter ** 3 / 6 / (a.width * a.height * a.depth)
    print(f"{a.count} spheres on {sites} sites ({nx} x {ny} x {nz}), solids fraction {fill:.3f}")


if __name__ == "__main__":
    main()
