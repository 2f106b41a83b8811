#!/usr/bin/env python3
"""Turn a 2D fluidbed particle CSV (id,x,y,vx,vy,omega,species) into a 3D one (id,x,y,z,vx,vy,vz,omega_x,
omega_y,omega_z,species) with every sphere in the mid-plane z = depth / 2, at rest across the depth, spinning
about z: the 2D bed as a slab between front and back walls (cases/pseudo2d/slab1d.toml)."""
import csv
import sys

COLUMNS = ["id", "x", "y", "z", "vx", "vy", "vz", "omega_x", "omega_y", "omega_z", "species"]


def main() -> None:
    if len(sys.argv) not in (3, 4):
        sys.exit("usage: slab_from_2d.py BED_2D.csv OUT_3D.csv [DEPTH_M=0.004]")
    src, dst = sys.argv[1], sys.argv[2]
    z = repr(float(sys.argv[3]) / 2) if len(sys.argv) == 4 else repr(0.004 / 2)
    with open(src, newline="") as f:
        rows = list(csv.DictReader(f))
    with open(dst, "w") as out:
        out.write(",".join(COLUMNS) + "\n")
        for r in rows:
            # The 2D values are copied as text, so the 3D run starts from the same doubles.
            out.write(",".join([r["id"], r["x"], r["y"], z, r["vx"], r["vy"], "0", "0", "0", r["omega"], r["species"]]) + "\n")
    print(f"{len(rows)} particles at z = {z} m -> {dst}")


if __name__ == "__main__":
    main()
