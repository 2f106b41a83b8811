#!/usr/bin/env python3
"""Bubbles of a run of cases/bubbling, from its voidage frames (Python standard library only).

    python3 cases/bubbling/voids.py OUT_DIR T0 T1

Per frame in [T0, T1]: the bed surface of each column is its highest cell with eps < 0.6; a void is a connected
region (4-neighbours) of at least 2 cells with eps > 0.8 below the surface; a void spanning 80% of the width or
more is counted as a slug, the others as bubbles. Also prints the mean pressure drop of monitor.csv over
[T0, T1] against the weight per area of the particles still in the domain.
"""
import math
import os
import re
import struct
import sys
import zlib


def read_cell_array(path, name):
    """A Float64 cell array of a .vti with zlib-compressed appended data (UInt64 block headers)."""
    data = open(path, 'rb').read()
    head = data[:data.index(b'<AppendedData')].decode()
    ext = [int(v) for v in re.search(r'WholeExtent="([^"]+)"', head).group(1).split()]
    nx, ny = ext[1] - ext[0], ext[3] - ext[2]
    offset = int(re.search(r'Name="%s"[^>]*offset="(\d+)"' % name, head).group(1))
    start = data.index(b'_', data.index(b'<AppendedData')) + 1 + offset
    blocks = struct.unpack_from('<Q', data, start)[0]
    sizes = struct.unpack_from('<%dQ' % blocks, data, start + 24)
    pos, raw = start + 24 + 8 * blocks, b''
    for s in sizes:
        raw += zlib.decompress(data[pos:pos + s])
        pos += s
    return nx, ny, struct.unpack('<%dd' % (len(raw) // 8), raw)


def voids(path):
    nx, ny, eps = read_cell_array(path, 'voidage')
    top = [max([j for j in range(ny) if eps[j * nx + i] < 0.6], default=-1) for i in range(nx)]
    inside = lambda i, j: j < top[i] and eps[j * nx + i] > 0.8
    seen, found = set(), []
    for i in range(nx):
        for j in range(ny):
            if (i, j) in seen or not inside(i, j):
                continue
            stack, cells = [(i, j)], []
            seen.add((i, j))
            while stack:
                a, b = stack.pop()
                cells.append((a, b))
                for c, d in ((a + 1, b), (a - 1, b), (a, b + 1), (a, b - 1)):
                    if 0 <= c < nx and 0 <= d < ny and (c, d) not in seen and inside(c, d):
                        seen.add((c, d))
                        stack.append((c, d))
            if len(cells) >= 2:
                xs = [c[0] for c in cells]
                found.append(max(xs) - min(xs) + 1)
    return nx, found


def main():
    run, t0, t1 = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    pvd = open(os.path.join(run, 'fields.pvd')).read()
    frames = [(float(t), f) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd) if t0 <= float(t) <= t1]
    bubbles = slugs = 0
    for _, f in frames:
        nx, widths = voids(os.path.join(run, f))
        slugs += sum(1 for w in widths if w >= 0.8 * nx)
        bubbles += sum(1 for w in widths if w < 0.8 * nx)
    n = max(len(frames), 1)
    print(f"{len(frames)} frames in [{t0}, {t1}] s: {bubbles / n:.2f} bubbles and {slugs / n:.2f} slugs per frame")
    rows = [l.strip().split(',') for l in open(os.path.join(run, 'monitor.csv'))]
    col = {k: i for i, k in enumerate(rows[0])}
    dp = [float(r[col['pressure_drop_Pa']]) for r in rows[1:] if t0 <= float(r[0]) <= t1]
    mass = float(rows[-1][col['solids_mass_kg']])
    case = open(os.path.join(run, 'case.toml')).read()
    width = float(re.search(r'^width = (\S+)', case, re.M).group(1))
    depth = float(re.search(r'^depth = (\S+)', case, re.M).group(1))
    mean = sum(dp) / len(dp)
    sd = math.sqrt(sum((x - mean) ** 2 for x in dp) / len(dp))
    weight = mass * 9.81 / (width * depth)
    print(f"pressure drop {mean:.0f} Pa (sd {sd:.0f}, {min(dp):.0f} to {max(dp):.0f}) against the bed's weight per "
          f"area {weight:.0f} Pa ({100 * (mean / weight - 1):+.1f}%); {rows[-1][col['particles_lost']]} particles lost")


if __name__ == '__main__':
    main()
