#!/usr/bin/env python3
"""Lower bounds of issue 31's rows from counted work (docs/performance.md section 38).

Every pass of a step is counted as the bytes it must move (each array it reads or writes once a unit; a
neighbour's values taken as cached, since the store is sorted by cell and the grid is small), its floating-point
operations, and its square roots and divisions (a core issues one of those every few cycles, so they are counted
apart). A pass's time is at least the larger of its bytes over the bandwidth of the cache level its working set
lives in and its operations at the core's scalar rate; a step's bound is the sum over its passes. Scalar, because
the build targets the x86-64 baseline (two-lane SSE2 at most) and the counted loops are not vectorised, except
where a count says so. On two threads the bound assumes perfect sharing of both the operations and the
bandwidth: it ignores the serial parts and the imbalance, which are what sections 34-37 measure.

The machine's rates come from `bench_micro_machine` (section 38 gives its log), the beds' entries and contacts a
particle from `bench/contact_counts.py`, the gas's iterations from the runs; all are arguments with the values
measured in section 38 as defaults. Usage:

    python3 bench/bounds.py                       # every row with the section's inputs
    python3 bench/bounds.py --detail              # and each pass's bytes, operations and bound
    python3 bench/bounds.py --bicgstab 3 --simple 4.0 ...   # other inputs
"""
import argparse
from dataclasses import dataclass


@dataclass
class Pass:
    """One pass's work per unit (a particle, a pair, a cell row) and its units per step."""
    name: str
    units: float
    bytes: float
    ops: float          # additions, multiplications, compares, selects
    sqrt: float = 0.0
    div: float = 0.0
    pow: float = 0.0    # libm calls (std::pow)
    lanes: int = 1      # what the compiled loop gains from vectors (1: scalar)


@dataclass
class Machine:
    ops_per_ns: float   # scalar operations a nanosecond, a core (balanced multiplies and additions)
    sqrt_ns: float      # throughput, a core
    div_ns: float
    pow_ns: float
    bw: dict            # GB/s (bytes a nanosecond) by (level, threads)

    def seconds(self, p, level, threads):
        memory = p.units * p.bytes / self.bw[(level, threads)] * 1e-9
        ns = (p.ops / self.ops_per_ns + p.sqrt * self.sqrt_ns + p.div * self.div_ns) / p.lanes + p.pow * self.pow_ns
        compute = p.units * ns * 1e-9 / threads
        return max(memory, compute), memory, compute


def dem_passes(dim, n, entries, contacts, builds, coupled, law):
    """One DEM step of n particles (E entries and C contacts a particle, a list build every 1 / builds steps)."""
    spin = 1 if dim == 2 else 3  # components of a spin
    w = 8
    # Update (Eq. 10): reads x, v, omega, f, torque, the build positions, 1/m, 1/I; writes x, v, omega. A CFD-DEM
    # step also reads the drag coefficient, the gas velocity and the fluid force.
    upd_read = (4 * dim + 2 * spin + 2) * w + ((1 + 2 * dim) * w if coupled else 0)
    upd = Pass("update", n, upd_read + (2 * dim + spin) * w, 10 * dim + 5 * spin + (4 * dim if coupled else 0))
    # Scan: own position, radius, offsets; per upper entry its index, partner and contact mark; the touch test.
    scan = Pass("touching-pair scan", n, (dim + 2) * w + 12 * entries / 2, (2 * dim + 2) * entries / 2)
    # Pair pass, per touching pair: the contact and its mirror, the spring read and written (one record each),
    # both marks, the force and two torque records; the law's operations, over two lanes (section 32: the law's
    # loop is vectorised, SSE2 at the baseline).
    pair_bytes = 8 + 4 + 2 * dim * w + 8 + (dim + 2 * spin) * w
    pair = Pass("pair pass (the law)", n * contacts / 2, pair_bytes, law[0], sqrt=law[1], div=law[2], lanes=2)
    # Sums: per entry its mark, per contact a force and torque record; f and torque written. Over every entry.
    sums = Pass("force and torque sums", n, 4 * entries + (dim + spin) * w * contacts + (dim + spin) * w,
                (dim + spin) * entries)
    # A build: bins and copies of the positions and radii, list partners and marks, the half list, the held
    # springs out by partner id and back (id, spring); about 9 (2D) or 27 (3D) bins of candidates tested.
    cand = 25 if dim == 2 else 60
    build = Pass("list build", n * builds,
                 (3 * dim + 3) * w + 12 * entries + (4 + 4 + dim * w) * 2 * contacts,
                 cand * (2 * dim + 3))
    return [upd, scan, pair, sums, build]


# The laws' (operations, square roots, divisions) a pair, counted on dem/contact_law.hpp: separation, its length
# and inverse, the normal and tangential relative velocities, the spring turned into the tangent plane and
# advanced, the normal and tangential forces, the Coulomb limit (a square root and a division), the torques.
LINEAR_2D = (60, 2, 2)
LINEAR_3D = (110, 2, 3)          # section 31
HERTZ_MINDLIN_3D = (180, 5, 3)   # and sqrt(R* delta) of the stiffnesses, sqrt(m k) of Tsuji's dashpot, the
                                 # rolling torque's direction (a square root and a division)


def coupling_passes(dim, n, pows):
    """One gas step's coupling, n particles, 2^dim cells a particle (the bilinear kernel); `pows` calls of
    std::pow a particle in the drag law (Ergun's branch of Eqs. 13-14 has none, Wen and Yu's two, Di Felice's
    exponent a pow and an exp)."""
    k = 2 ** dim
    w = 8
    weights = (4 + k * 12)  # a particle's cell weights: count, cells and weights
    return [
        Pass("kernel weights", n, (dim + 1) * w + weights, 6 * dim + 3 * k),
        # Counting sort of the shares by cell (count, place), then per cell the sums of volume, K and K-weighted
        # velocity over its shares (the particle's radius, velocity and K read once).
        Pass("deposition", n, 2 * weights + k * 12 + k * 12 + (dim + 2) * w, k * (4 + 2 * dim)),
        # Interpolation: voidage, gas velocity and pressure gradient gathered with the weights; the drag law (a
        # slip speed, three divisions, `pows` pow calls); K, the gas velocity and the fluid force written.
        Pass("interpolation and drag", n, weights + (dim + 1) * w + (1 + 2 * dim) * w,
             (1 + 2 * dim) * 2 * k + 40, sqrt=1, div=3, pow=pows),
    ]


def gas_passes(dim, cells, simple, bicgstab, band):
    """One gas step on `cells` cells: `simple` SIMPLE iterations (each component's momentum assembly and BiCGSTAB
    of `bicgstab` iterations), a pressure solve per iteration and one closing correction (the coupling bound),
    the band LDL^T factorised once (half-width `band`) and reused as the preconditioner of one-iteration CG."""
    w = 8
    d = dim
    stencil = 2 * dim + 1
    rows = cells * d  # one momentum row a face, about one face a cell per component
    solves = simple + 1
    return [
        # Per row: the component, its old value, voidage (new, old), drag coefficient, solids velocity, the mass
        # fluxes along and across, the cell voidage and pressure, the unknown number, the row's place; written:
        # the stencil's values (through their offsets), rhs, x, a_P, d. Operations: four (2D) or six faces of
        # convection, diffusion and the van Leer correction (two divisions a face), the row's sources, 1/alpha,
        # the SIMPLE coefficient d.
        Pass("momentum assembly", rows * simple, 11 * w + 4 + 8 + stencil * 12 + 4 * w,
             2 * dim * 24 + 20, div=2 * (2 * dim) + 2),
        # b - A x (CSR: values, columns, x, b), |r|_1, sum a_P.
        Pass("momentum residual", rows * simple, stencil * 12 + 4 * w, 2 * stencil + 2),
        # BiCGSTAB (Eigen's algorithm): two products by diagonals, two Jacobi applications, four dot products and
        # four vector updates an iteration; the product is cloned for AVX-512 (8 lanes, counted as 4).
        Pass("BiCGSTAB (products)", rows * simple * bicgstab, 2 * (stencil * w + 2 * w), 2 * 2 * stencil, lanes=4),
        Pass("BiCGSTAB (vectors)", rows * simple * bicgstab, 2 * 3 * w + 4 * 2 * w + 4 * 3.5 * w, 2 + 8 + 12, lanes=2),
        # The increment written back, the iterate copied, the mass fluxes (2 a SIMPLE iteration and the closing
        # one), continuity, the flux changes of the coupling bound.
        Pass("velocity and flux bookkeeping", rows * simple, 4 * w + 2 * w + 2 * 3 * w + 4 * w, 1 + 4 + 6),
        Pass("continuity", cells * solves, (2 + d + 1) * w, 2 * d + 3),
        # Pressure correction: the coefficients rho eps A d, the band's assembly, p += p', u += d grad p'.
        Pass("pressure correction", cells * solves, d * 3 * w + 3 * w + (2 + d) * w + 3 * w + d * 4 * w,
             3 * d + 2 * d + 2 + 3 * d),
        # The factorisation, once a step: band^2 operations a row, the band read and written once, vectorised
        # (AVX-512 clone, 8 lanes counted as 4).
        Pass("band LDL^T factorisation", cells, 2 * (band + 1) * w, band * band, div=1, lanes=4),
        # Each solve: forward and back substitution over the band (4 band operations a row, read twice), and
        # in the reused solves two products and the vector work of one CG iteration.
        Pass("band substitutions", cells * solves, 2 * (band + 1) * w, 4 * band, div=1, lanes=4),
        Pass("CG products and vectors", cells * simple, 2 * (stencil + 2) * w + 6 * 2 * w, 2 * 2 * stencil + 12),
    ]


def bound(machine, passes, level, threads, detail, title):
    """The passes' bound (seconds), and its memory and operations parts."""
    total = total_mem = total_cmp = 0.0
    for p in passes:
        t, m, c = machine.seconds(p, level, threads)
        total += t
        total_mem += m
        total_cmp += c
        if detail:
            print(f"  {title:22s} {p.name:30s} {p.units:9.0f} x {p.bytes:5.0f} B {p.ops:6.0f} ops {p.sqrt:3.0f} sqrt "
                  f"{p.div:3.0f} div {p.pow:3.0f} pow -> {t * 1e3:8.4f} ms (memory {m * 1e3:.4f}, ops {c * 1e3:.4f})")
    return total, total_mem, total_cmp


def cell_iteration(passes, cell_iterations):
    """The gas's totals a cell and SIMPLE iteration (everything of the step over cells x iterations)."""
    tot = {k: sum(p.units * getattr(p, k) for p in passes) / cell_iterations for k in ("bytes", "ops", "div", "sqrt")}
    print(f"  the gas, a cell-iteration: {tot['bytes']:.0f} B, {tot['ops']:.0f} operations, {tot['div']:.1f} "
          f"divisions, {tot['sqrt']:.1f} square roots")


def rows(o, m):
    """Issue 31's rows: (name, bound, memory part, operations part, measured, particle-steps or None)."""
    out = []
    # Row 1: 3D settle, 100,000 spheres, 2,000 steps, one thread; 25 MB of store and 20 MB of list: memory.
    e, c, b = o.settle3d
    t = bound(m, dem_passes(3, 100_000, e, c, b, False, LINEAR_3D), "mem", 1, o.detail, "3D settle")
    out.append(("3D settle, 100,000 spheres, 2,000 steps, 1 thread", *[2000 * x for x in t], o.measured[0],
                2000 * 100_000))
    # Row 2: 2D settle-22k, 5,000 steps, one thread; a few MB: the L3.
    e, c, b = o.settle2d
    t = bound(m, dem_passes(2, 22_000, e, c, b, False, LINEAR_2D), "L3", 1, o.detail, "2D settle")
    out.append(("2D settle-22k, 5,000 steps, 1 thread", *[5000 * x for x in t], o.measured[1], 5000 * 22_000))
    # Row 3: the paper's case, a simulated second: 5,000 gas steps of 2 DEM steps, 22,000 discs, 30 x 50 cells
    # (the gas's arrays and band, about 1 MB, in the L2s).
    e, c, b = o.paper
    for threads, measured in ((1, o.measured[2]), (2, o.measured[3])):
        detail = o.detail and threads == 1
        dem = bound(m, dem_passes(2, 22_000, e, c, b, True, LINEAR_2D), "L3", threads, detail, "paper: DEM step")
        cpl = bound(m, coupling_passes(2, 22_000, 0), "L3", threads, detail, "paper: coupling")
        gas = bound(m, gas_passes(2, 1500, o.simple, o.bicgstab, 30), "L2", threads, detail, "paper: gas step")
        per = [2 * dem[i] + cpl[i] + gas[i] for i in range(3)]
        if detail:
            print(f"  paper, a gas step: DEM {2 * dem[0] * 1e3:.3f} ms, coupling {cpl[0] * 1e3:.3f}, "
                  f"gas {gas[0] * 1e3:.3f}")
            cell_iteration(gas_passes(2, 1500, o.simple, o.bicgstab, 30), 1500 * o.simple)
        out.append((f"the paper's case, a simulated second, {threads} thread{'s' if threads > 1 else ''}",
                    *[5000 * x for x in per], measured, None))
    # Row 4: the van Wachem bed, 6 s: 17,562 spheres, DEM steps of 1/175,000 s, the gas every 35 on 20 x 120 x 2
    # cells (cases/vanwachem2001/dem.toml), the band 40 rows wide; Di Felice's drag.
    e, c, b = o.vanwachem
    steps = 6.0 * 175_000
    dem = bound(m, dem_passes(3, 17_562, e, c, b, True, HERTZ_MINDLIN_3D), "L3", 2, o.detail, "van Wachem: DEM")
    gas = bound(m, gas_passes(3, 20 * 120 * 2, o.simple, o.bicgstab, 40), "L2", 2, o.detail, "van Wachem: gas")
    cpl = bound(m, coupling_passes(3, 17_562, 1), "L3", 2, o.detail, "van Wachem: coupling")
    per = [dem[i] + (gas[i] + cpl[i]) / 35 for i in range(3)]
    out.append(("van Wachem bed, 6 s, 2 threads", *[steps * x for x in per], o.measured[4], None))
    return out


def state_bytes(entries, contacts):
    """The least a 3D sphere must hold between steps: position, velocity, spin, force, torque, the positions of
    the last build, radius, 1/m, 1/I, id and species (176 B); its share of a half list (a 4-byte partner a pair)
    and of the contacts' springs (24 B and the partner)."""
    return 15 * 8 + 24 + 3 * 8 + 4 + 4 + 4 * entries / 2 + (24 + 4) * contacts / 2


def main():
    a = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    a.add_argument("--ops-per-ns", type=float, default=12.46, help="scalar operations a ns, a core")
    a.add_argument("--sqrt-ns", type=float, default=2.16)
    a.add_argument("--div-ns", type=float, default=1.14)
    a.add_argument("--pow-ns", type=float, default=10.0)
    a.add_argument("--bw", type=float, nargs=6, default=[39.3, 71.2, 81.6, 161.9, 134.9, 253.2],
                   metavar=("MEM1", "MEM2", "L3_1", "L3_2", "L2_1", "L2_2"),
                   help="GB/s at each level on 1 and 2 threads (the fastest kernel measured there)")
    a.add_argument("--settle3d", type=float, nargs=3, default=[9.3, 3.0, 0.236], metavar=("E", "C", "BUILDS"),
                   help="entries and contacts a particle, list builds a step")
    a.add_argument("--settle2d", type=float, nargs=3, default=[5.2, 3.65, 0.193], metavar=("E", "C", "BUILDS"))
    a.add_argument("--paper", type=float, nargs=3, default=[5.85, 1.32, 0.1265], metavar=("E", "C", "BUILDS"))
    a.add_argument("--vanwachem", type=float, nargs=3, default=[11.43, 1.73, 0.0063], metavar=("E", "C", "BUILDS"))
    a.add_argument("--simple", type=float, default=4.0, help="SIMPLE iterations a gas step")
    a.add_argument("--bicgstab", type=float, default=2.0, help="BiCGSTAB iterations a momentum solve")
    a.add_argument("--measured", type=float, nargs=5, default=[56.8, 11.2, 36.6, 25.7, 2250.0],
                   metavar=("S3D", "S2D", "PAPER1", "PAPER2", "VW"), help="measured seconds of each row")
    a.add_argument("--memory", type=float, default=414.0, help="measured bytes a 3D particle (peak RSS)")
    a.add_argument("--detail", action="store_true", help="each pass's count and bound")
    o = a.parse_args()
    bw = dict(zip([(lv, t) for lv in ("mem", "L3", "L2") for t in (1, 2)], o.bw))
    m = Machine(o.ops_per_ns, o.sqrt_ns, o.div_ns, o.pow_ns, bw)
    print(f"{'row':52s} {'bound':>9s} {'memory':>9s} {'ops':>9s} {'measured':>9s} {'of bound':>8s}")
    for name, tb, tm, tc, meas, units in rows(o, m):
        extra = f"  ({tb / units * 1e9:.1f} ns a particle-step)" if units else ""
        print(f"{name:52s} {tb:8.2f}s {tm:8.2f}s {tc:8.2f}s {meas:8.1f}s {tb / meas:8.0%}{extra}")
    least = state_bytes(*o.settle3d[:2])
    print(f"{'memory a 3D particle (the least state, E, C of row 1)':52s} {least:8.0f}B {'':9s} {'':9s} "
          f"{o.memory:8.0f}B {least / o.memory:8.0%}")


if __name__ == "__main__":
    main()
