#!/usr/bin/env python3
"""Split a perf profile of a CFD-DEM run into DEM / gas / coupling / output / OpenMP+kernel / other
(docs/performance.md section 22). Usage: perf report -i perf.data --no-children --sort dso,sym --stdio -g none \
  | python3 bench/profile_split.py"""
import re
import sys

RULES = [  # first match wins
    ("coupling", r"CfdDemSimulation|Deposition|particle_cell_weights|cell_weights|beta_ergun|drag|gather\b|voidage"),
    ("output", r"libz|write_vtu|vtk|hdf5|H5|adler|deflate|crc32|lacey|fmt::|monitor|_IO_|__write|bubble|zlib"),
    ("DEM", r"DemSolver|merge_sort|move_merge|neighbor|bin_points|link_mirrors|fill_wall_tangential|insert"),
    ("gas", r"GasSolver|Eigen|Checked|StructuredSolver|Stencil|backward_error|fill_\w*ghost|fill_zero_gradient|"
            r"load_cells|pressure|inlet_superficial|fill_velocity|fill_periodic|tvd|cells_to_faces"),
    ("OpenMP, kernel, libc", r"GOMP|gomp|\[k\]|futex|memset|memmove|memcpy|malloc|free|_int_"),
]


def category(symbol):
    return next((c for c, rx in RULES if re.search(rx, symbol)), "other")


def without_templates(symbol):
    """The symbol without its template arguments (innermost first, so nested ones go too)."""
    while True:
        shorter = re.sub(r"<[^<>]*>", "", symbol)
        if shorter == symbol:
            return symbol
        symbol = shorter


def main():
    shares = {}
    for line in sys.stdin:
        m = re.match(r"\s*([0-9.]+)%\s+(\S.*)", line)
        if not m:
            continue
        pct, text = float(m.group(1)), m.group(2)
        cat = category(text)
        shares[cat] = shares.get(cat, 0.0) + pct
    for c in [r[0] for r in RULES] + ["other"]:
        print(f"{c:24s} {shares.get(c, 0.0):6.1f}%")


if __name__ == "__main__":
    main()
