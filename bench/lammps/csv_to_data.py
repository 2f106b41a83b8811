#!/usr/bin/env python3
"""Write a fluidbed particles CSV (id,x,y,vx,vy,omega,species) as a LAMMPS data file for atom_style sphere."""
import csv
import sys


def main() -> None:
    if len(sys.argv) != 6:
        sys.exit("usage: csv_to_data.py PARTICLES.csv OUT.data WIDTH HEIGHT DIAMETER")
    src, dst, width, height, diameter = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
    with open(src, newline="") as f:
        rows = list(csv.DictReader(f))
    with open(dst, "w") as out:
        out.write(f"fluidbed placement from {src}\n\n{len(rows)} atoms\n1 atom types\n\n")
        out.write(f"0.0 {width!r} xlo xhi\n0.0 {height!r} ylo yhi\n{-diameter / 2!r} {diameter / 2!r} zlo zhi\n\n")
        # The density column is overwritten by `set type 1 mass` in the input script.
        out.write("Atoms # sphere\n\n")
        for k, r in enumerate(rows):
            out.write(f"{k + 1} 1 {diameter!r} 1.0 {r['x']} {r['y']} 0.0\n")
        out.write("\nVelocities\n\n")
        for k, r in enumerate(rows):
            out.write(f"{k + 1} {r['vx']} {r['vy']} 0.0 0.0 0.0 {r['omega']}\n")


if __name__ == "__main__":
    main()
