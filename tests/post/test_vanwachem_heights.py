#!/usr/bin/env python3
"""cases/vanwachem2001/height_definitions.py's camera on synthetic particle frames (discs of d = 1.545 mm in the
90 mm wide column, seen through its depth), against what a silhouette must give:
- a slab of discs so dense (centres 0.3 d apart) that it is black from the bottom to its top H: the camera's height
  is H to within a quarter diameter (the averaging window's edge against the slab's ragged top);
- the same slab lowered by 10 mm: the height falls by 10 mm to within one pixel (the image is shifted, nothing else);
- a few particles thrown above the slab, each alone in its averaging window (less than half of it dark): the
  height does not change at all;
- an empty column reads 0.
Usage (CTest): test_vanwachem_heights.py FLUIDBED_BINARY SOURCE_DIR"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(sys.argv[2], "cases", "vanwachem2001"))
from height_definitions import camera_height  # noqa: E402

d, pixel, coverage = 1.545e-3, 2.5e-4, 0.5
failures = 0


def check(name, ok, detail):
    global failures
    failures += not ok
    print(f"{name}: {detail}", "ok" if ok else "FAIL")


def slab(top):
    """Centres on a lattice 0.3 d apart from the bottom to top - d/2 (the discs' tops reach `top`)."""
    xs = np.arange(0.5 * d, 0.09 - 0.5 * d + 1e-12, 0.3 * d)
    ys = np.arange(0.5 * d, top - 0.5 * d + 1e-12, 0.3 * d)
    x, y = np.meshgrid(xs, ys)
    x, y = x.ravel(), y.ravel()
    y = y + (top - 0.5 * d - y.max())  # the highest row's tops exactly at `top`
    return x, y, np.full(x.size, d)


x, y, dd = slab(0.1)
h = camera_height(x, y, dd, pixel, coverage)
check("a dense slab to 100 mm", abs(h - 0.1) <= 0.25 * d, f"camera {h * 1e3:.3f} mm")
x2, y2, d2 = slab(0.09)
h2 = camera_height(x2, y2, d2, pixel, coverage)
check("the slab lowered by 10 mm", abs((h - h2) - 0.01) <= pixel, f"camera {h2 * 1e3:.3f} mm, moved {(h - h2) * 1e3:.3f} mm")
flying_x = np.array([0.01, 0.03, 0.05, 0.07])
flying_y = np.array([0.11, 0.115, 0.12, 0.13])
h3 = camera_height(np.concatenate([x, flying_x]), np.concatenate([y, flying_y]), np.full(x.size + 4, d), pixel, coverage)
check("four particles thrown above it", h3 == h, f"camera {h3 * 1e3:.3f} mm")
h4 = camera_height(np.array([]), np.array([]), np.array([d]), pixel, coverage)
check("an empty column", h4 == 0.0, f"camera {h4}")
sys.exit(1 if failures else 0)
