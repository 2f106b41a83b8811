#!/usr/bin/env python3
"""The performance model of docs/parallel.md: the time of a DEM (or CFD-DEM) step on P ranks with n particles
each (weak scaling), from figures measured on this machine (bench/parallel.sh, bench/mpi_costs.cpp, the runs'
parallel summary) and a cluster's network figures (assumed, said so). Prints the weak-scaling efficiency at the
requested rank counts and the check against the 2-rank runs measured here.

Per DEM step and rank (3D):
  T = imb * [t_c n (1 + kappa g) + t_b n / s]                 compute, ghosts' share, rebuild bookkeeping
      + m alpha + beta B_f g n                                 ghosts' positions forward (m messages)
      + (2 m alpha + beta R (g + mu) n) / s                    list builds: sizes, then records
      + alpha_r ceil(log2 P) (1 + 2 / s) + beta 16 P / s       the step's reduction; per build the far check and
                                                               the balance check (2 doubles a rank)
  CFD-DEM adds per DEM step, the gas solved on every rank on the whole grid (this version):
      (t_g c n P + t_cp n (1 + g_cfd) + alpha ceil(log2 P) + beta 8 Dim' c n P) / k
  and the one-rank reference is t_c n + (t_g c n + t_cp n) / k. The projection with the gas decomposed on the same
  blocks replaces the replicated gas by its own cells, a halo a SIMPLE iteration, and per CG iteration of the
  pressure solve (cg-multigrid) its exact reductions and the V-cycle's halos: on each level split among the ranks
  2 x 2 x sweeps + 1 face halos (6 neighbours) and 2 transfer halos (26), levels split while a rank keeps 2 cells
  per axis; the coarse level gathered below them (an allgather of its cells).
g: ghosts per owned particle for a cube of n particles at solids fraction phi with neighbours on every side,
scaled by the surface factor of a Hilbert piece; m = 26 neighbours (fewer below 27 ranks).
The two-fluid model's projection (tfm_step) is described there.
Usage: python3 bench/parallel_model.py [--n 20000] [--ranks 64 1024 8192] [--key value ...]
"""
import argparse
import math

p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
a = p.add_argument
a("--n", type=float, default=20000, help="particles per rank")
a("--ranks", type=int, nargs="+", default=[64, 256, 1024, 8192])
a("--d", type=float, default=0.004, help="particle diameter, m")
a("--phi", type=float, default=0.6, help="solids fraction of the packed bed")
a("--reach", type=float, default=0.006, help="ghost reach for contacts: d + skin, m")
a("--reach-cfd", type=float, default=0.012, help="ghost reach of CFD-DEM: half a 2 cm cell + skin, m")
a("--surface", type=float, default=1.3, help="a Hilbert piece's surface over a cube's (assumed)")
# Measured here (docs/parallel.md, Performance): settle-100k-3d and bubbling-100k-3d.
a("--t-c", type=float, default=400e-9, help="DEM compute per particle-step, one rank, s (dense bubbling bed)")
a("--kappa", type=float, default=0.35, help="compute of a ghost over an owned particle's (its pairs across the cut)")
a("--t-b", type=float, default=130e-9, help="rebuild bookkeeping per owned particle and build, s")
a("--s", type=float, default=6.0, help="steps per list build")
a("--imb", type=float, default=1.04, help="slowest over mean rank compute (time balancing, threshold 1.2)")
a("--bf", type=float, default=72.0, help="bytes per ghost forwarded a step (9 doubles)")
a("--rec", type=float, default=235.0, help="bytes per record at a list build")
a("--mu", type=float, default=0.01, help="migrating particles per owned particle and build")
a("--t-g", type=float, default=3.9e-6, help="gas solve per cell and gas step, one rank, s")
a("--t-cp", type=float, default=115e-9, help="coupling per particle and gas step (deposit, interpolate, drag), s")
a("--cells", type=float, default=0.018, help="gas cells per particle (bubbling-100k-3d: 1800 / 100,000)")
a("--k", type=float, default=2.0, help="DEM steps per gas step")
a("--simple", type=float, default=9.0, help="SIMPLE iterations per gas step (the paper's case: 8.7)")
# The decomposed pressure solve (cg-multigrid, docs/parallel.md): measured on 216,000 cells, 9 solves to 1e-12.
a("--krylov", type=float, default=10.0, help="CG iterations per pressure solve (cg-multigrid: 93 in 9 solves)")
a("--reductions", type=float, default=3.0, help="exact reductions per CG iteration (p.q, r.r, r.z)")
a("--sweeps", type=float, default=2.0, help="red-black sweep pairs before and after the coarse correction")
a("--t-exact", type=float, default=2.0, help="cost of an exact (reproducible) reduction over a plain one")
a("--t-mg", type=float, default=43e-9, help="cg-multigrid compute per cell and CG iteration, one rank, s (216,000 "
  "cells: 870 ms for 93 iterations)")
a("--solve-cells", type=float, default=50000, help="cells per rank of the pressure solve alone (issue 30: 50,000)")
# The two-fluid model on blocks (issue 30), measured on cases/tfm3d/column.toml (16 x 50 x 16, cg-multigrid, one
# thread, 0.05 s: 150 steps, 1.8 us a cell-step; perf shares: P' solves 40%, BiCGSTAB solves 9%, the rest 51%).
a("--tfm-cells", type=float, default=50000, help="TFM cells per rank (issue 30: 50,000)")
a("--t-tfm", type=float, default=0.92e-6, help="TFM compute per cell-step outside the linear solves, s")
a("--t-bicg", type=float, default=13e-9, help="StencilBicgstab compute per cell and iteration, s")
a("--tfm-cg", type=float, default=20.4, help="CG iterations of the two P' solves of a TFM step (column: 2 x 10.2)")
a("--tfm-bicg", type=float, default=12.4, help="BiCGSTAB iterations of a TFM step (column: E' 4.9, 3 x 2.5)")
a("--tfm-halo-layers", type=float, default=35.0, help="field layers a TFM step exchanges across each cut face "
  "(the stages' halos, counted in docs/parallel.md)")
a("--tfm-rounds", type=float, default=12.0, help="halo rounds of a TFM step outside the solves")
a("--tfm-collectives", type=float, default=14.0, help="small collectives of a TFM step outside the Krylov "
  "iterations (dt, packing sweeps, health, residual, the solves' finiteness checks)")
# A cluster's interconnect (assumed: InfiniBand HDR class, not measured here).
a("--alpha", type=float, default=1.5e-6, help="point-to-point latency, s")
a("--alpha-r", type=float, default=2.0e-6, help="allreduce latency per tree level, s")
a("--beta", type=float, default=1 / 12e9, help="seconds per byte")
# The check against this machine: N particles on P ranks (strong scaling of a bench bed), the ghosts per owned
# particle and partner count measured by the run, the shared-memory latency and bandwidth of bench_mpi_costs.
a("--check-N", type=float, default=100000, help="particles of the bench bed")
a("--check-g", type=float, nargs="*", default=[], help="measured ghosts per owned particle at 2, 3, 4 ... ranks")
a("--check-alpha", type=float, default=0.75e-6, help="shared-memory latency, s (bench_mpi_costs)")
a("--check-beta", type=float, default=1 / 8e9, help="shared-memory seconds per byte (bench_mpi_costs)")
args = p.parse_args()


def ghosts(n, reach):
    side = (n * math.pi / 6 * args.d**3 / args.phi) ** (1 / 3)
    return args.surface * ((1 + 2 * reach / side) ** 3 - 1)


def dem_step(P, n):
    if P == 1:
        return args.t_c * n, {}
    g = ghosts(n, args.reach)
    m = min(26, P - 1)
    levels = math.ceil(math.log2(P))
    parts = {
        "compute": args.imb * args.t_c * n * (1 + args.kappa * g),
        "bookkeeping": args.imb * args.t_b * n / args.s,
        "forward": m * args.alpha + args.beta * args.bf * g * n,
        "builds": (2 * m * args.alpha + args.beta * args.rec * (g + args.mu) * n) / args.s,
        "reductions": args.alpha_r * levels * (1 + 2 / args.s) + args.beta * 16 * P / args.s,
    }
    return sum(parts.values()), parts


def cfd_step(P, n):
    t, parts = dem_step(P, n)
    if P == 1:
        return t + (args.t_g * args.cells * n + args.t_cp * n) / args.k, parts
    gc = ghosts(n, args.reach_cfd)
    levels = math.ceil(math.log2(P))
    parts = dict(parts)
    parts["gas (replicated)"] = args.t_g * args.cells * n * P / args.k
    parts["coupling"] = args.t_cp * n * (1 + gc) / args.k
    parts["cell allgather"] = (args.alpha * levels + args.beta * 8 * 8 * args.cells * n * P) / args.k
    return sum(parts.values()), parts


def pressure_comm(P, cells):
    """Communication of one CG iteration of cg-multigrid with `cells` cells a rank: the V-cycle's halos on the
    levels split while a rank's side keeps 2 cells (face halos: the smoother and the products; transfer halos:
    edges and corners too), the exact reductions, and the gather of the first level not split."""
    side = cells ** (1 / 3)
    fine_side = side
    split = 0
    while side >= 4:
        side /= 2
        split += 1
    face_halos = split * (4 * args.sweeps + 1) + 1
    msgs = face_halos * min(6, P - 1) + split * 2 * min(26, P - 1)
    levels = math.ceil(math.log2(P))
    return {
        "halos": msgs * args.alpha + args.beta * 8 * 6 * face_halos * fine_side**2 * 8 / 7,
        "reductions": args.reductions * args.t_exact * args.alpha_r * levels,
        "gather": args.alpha_r * levels + args.beta * 8 * P * side**3,
    }


def cfd_distributed_step(P, n):
    """The gas decomposed on the same blocks (issue 30): each rank solves its cells, a halo of one layer a SIMPLE
    iteration, and two reproducible reductions a Krylov iteration."""
    t, parts = dem_step(P, n)
    if P == 1:
        return t + (args.t_g * args.cells * n + args.t_cp * n) / args.k, parts
    gc = ghosts(n, args.reach_cfd)
    cells = args.cells * n
    halo = args.surface * ((1 + 2 / cells ** (1 / 3)) ** 3 - 1) * cells
    levels = math.ceil(math.log2(P))
    parts = dict(parts)
    parts["gas (own cells)"] = args.t_g * cells * (1 + 0.5 * halo / cells) / args.k
    parts["coupling"] = args.t_cp * n * (1 + gc) / args.k
    parts["gas halos"] = args.simple * (min(26, P - 1) * args.alpha + args.beta * 8 * 8 * halo) / args.k
    for name, t in pressure_comm(P, cells).items():
        parts["pressure " + name] = args.simple * args.krylov * t / args.k
    return sum(parts.values()), parts


def tfm_step(P, c):
    """The two-fluid model on blocks of c cells a rank, x never cut (the BiCGSTAB inner products sum whole lines
    along x), so the blocks are x-long columns of side s = sqrt(c / nx) in y and z with 4 face neighbours and 8
    with the edges: the stages' halos, the shared face planes computed by both ranks, the P' solves (cg-multigrid,
    pressure_comm) and the BiCGSTAB solves (2 face halos and 3 collectives of two 71-word exact sums an
    iteration)."""
    nx = 60.0  # a column of industrial interest: 60 cells across (issue 30)
    side = math.sqrt(c / nx)
    t_solve = args.tfm_cg * args.t_mg * c + args.tfm_bicg * args.t_bicg * c
    if P == 1:
        return args.t_tfm * c + t_solve, {}
    levels = math.ceil(math.log2(P))
    face = nx * side  # cells on one cut face of the block
    parts = {
        "compute": args.t_tfm * c * (1 + 2 / side) + t_solve,
        "stage halos": args.tfm_rounds * min(8, P - 1) * args.alpha + args.beta * 8 * 4 * face * args.tfm_halo_layers,
        "collectives": args.tfm_collectives * args.alpha_r * levels,
        "bicgstab comm": args.tfm_bicg * (2 * (min(4, P - 1) * args.alpha + args.beta * 8 * 4 * face)
                                          + 3 * (args.alpha_r + args.beta * 2 * 71 * 8) * levels),
    }
    for name, t in pressure_comm(P, c).items():
        parts["P' " + name] = args.tfm_cg * t
    return sum(parts.values()), parts


n = args.n
print(f"{n:.0f} particles per rank; ghosts per owned particle: {ghosts(n, args.reach):.3f} (contact reach), "
      f"{ghosts(n, args.reach_cfd):.3f} (CFD-DEM reach)")
for name, f in (("DEM only", dem_step), ("CFD-DEM, gas replicated (this version)", cfd_step),
                ("CFD-DEM, gas decomposed (projected: issue 30)", cfd_distributed_step)):
    t1, _ = f(1, n)
    print(f"\n{name}: one rank {1e3 * t1:.3f} ms a step")
    print(f"{'ranks':>6} {'ms/step':>9} {'efficiency':>10}  largest parts")
    for P in args.ranks:
        t, parts = f(P, n)
        top = sorted(parts.items(), key=lambda kv: -kv[1])[:4]
        print(f"{P:>6} {1e3 * t:>9.3f} {t1 / t:>10.2f}  " + ", ".join(f"{k} {1e3 * v:.3f}" for k, v in top))

c = args.solve_cells
t1 = args.t_mg * c
print(f"\nThe pressure solve alone (cg-multigrid), {c:.0f} cells per rank: one rank {1e6 * t1:.0f} us a CG iteration")
print(f"{'ranks':>6} {'us/iter':>9} {'efficiency':>10}  parts")
for P in args.ranks:
    parts = pressure_comm(P, c)
    t = t1 + sum(parts.values())
    print(f"{P:>6} {1e6 * t:>9.0f} {t1 / t:>10.2f}  " + ", ".join(f"{k} {1e6 * v:.0f}" for k, v in parts.items()))

c = args.tfm_cells
t1, _ = tfm_step(1, c)
print(f"\nThe two-fluid model (projected: issue 30), {c:.0f} cells per rank: one rank {1e3 * t1:.1f} ms a step")
print(f"{'ranks':>6} {'ms/step':>9} {'efficiency':>10}  largest parts")
for P in args.ranks:
    t, parts = tfm_step(P, c)
    top = sorted(parts.items(), key=lambda kv: -kv[1])[:5]
    print(f"{P:>6} {1e3 * t:>9.2f} {t1 / t:>10.2f}  " + ", ".join(f"{k} {1e3 * v:.2f}" for k, v in top))

if args.check_g:
    print(f"\ncheck on this machine: {args.check_N:.0f} particles, DEM only")
    t1 = args.t_c * args.check_N
    for P, g in enumerate(args.check_g, start=2):
        n = args.check_N / P
        m = 1 if P == 2 else 2
        t = (args.imb * (args.t_c * n * (1 + args.kappa * g) + args.t_b * n / args.s)
             + m * args.check_alpha + args.check_beta * args.bf * g * n
             + (2 * m * args.check_alpha + args.check_beta * args.rec * (g + args.mu) * n) / args.s
             + 2 * args.check_alpha * (1 + 2 / args.s))
        print(f"{P} ranks: ghosts {g:.3f} per owned particle, predicted speed-up {t1 / t:.2f}")
