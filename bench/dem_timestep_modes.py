#!/usr/bin/python3
"""Time-step limit of the DEM update from the eigenvalues of the linearised contact network (issue 16).

Reads a settled 2D bed (fluidbed's particle CSV: id,x,y,vx,vy,omega,species), takes every touching pair and
wall contact as a sticking Cundall-Strack contact (normal spring k_n, tangential spring k_t at the contact
point), and finds by power iteration the largest eigenvalue omega_max^2 of M^-1 K for
  - the full system (x, y, spin of every sphere),
  - translation only (spins held),
  - spin only (centres held): the rotational mode.
Eq. 10's update (velocity first, then position with the new velocity; the tangential spring advanced with the
velocity of the step's start) is a symplectic Euler step: stable for omega_max dt < 2 without damping. The script
prints omega_max, dt_max = 2 / omega_max, and the spectral radius of the damped update's amplification matrix
for the top mode at the given steps. It also tries a per-sphere implicit spin update (each sphere's own
tangential stiffness k_t r^2 Z taken implicitly), to show what it buys and what it costs, and over a window of
the bed (--patch, the other spheres held) forms the undamped update matrices densely for Eq. 10, for spins
sub-cycled with the centres frozen, and for r-RESPA force splitting (tangential springs in two inner steps).

Usage: /usr/bin/python3 bench/dem_timestep_modes.py BED.csv [--width 0.6] [--kn 800] [--kt 800] [--patch X0 X1 Y0 Y1] [--window-only]
"""
import argparse
import math

import numpy as np


def contacts(x, y, r, width):
    """Touching pairs (cell search on a 2r grid) and wall contacts (left, right, floor)."""
    cell = 2.0 * r.max()
    cx = np.floor(x / cell).astype(np.int64)
    cy = np.floor(y / cell).astype(np.int64)
    key = {}
    for i, k in enumerate(zip(cx, cy)):
        key.setdefault(k, []).append(i)
    pi, pj = [], []
    for (a, b), members in key.items():
        for da in (-1, 0, 1):
            for db in (-1, 0, 1):
                other = key.get((a + da, b + db))
                if other is None:
                    continue
                for i in members:
                    for j in other:
                        if j > i and (x[i] - x[j]) ** 2 + (y[i] - y[j]) ** 2 < (r[i] + r[j]) ** 2:
                            pi.append(i)
                            pj.append(j)
    pi, pj = np.array(pi), np.array(pj)
    walls = []  # (sphere, outward normal from the sphere towards the wall)
    for i in range(len(x)):
        if x[i] < r[i]:
            walls.append((i, -1.0, 0.0))
        if x[i] > width - r[i]:
            walls.append((i, 1.0, 0.0))
        if y[i] < r[i]:
            walls.append((i, 0.0, -1.0))
    return pi, pj, walls


class Network:
    """K v for the linearised sticking contacts; DOFs per sphere: x, y, spin angle."""

    def __init__(self, x, y, r, m, inertia, width, kn, kt):
        self.n = len(x)
        self.pi, self.pj, walls = contacts(x, y, r, width)
        d = np.hypot(x[self.pj] - x[self.pi], y[self.pj] - y[self.pi])
        self.nx = (x[self.pj] - x[self.pi]) / d
        self.ny = (y[self.pj] - y[self.pi]) / d
        self.wi = np.array([w[0] for w in walls], dtype=np.int64)
        self.wnx = np.array([w[1] for w in walls])
        self.wny = np.array([w[2] for w in walls])
        self.r = r
        self.kn, self.kt = kn, kt
        self.minv = np.concatenate([1.0 / m, 1.0 / m, 1.0 / inertia])
        z = np.bincount(self.pi, minlength=self.n) + np.bincount(self.pj, minlength=self.n)
        z += np.bincount(self.wi, minlength=self.n)
        self.z = z

    def k_times(self, u):
        n = self.n
        ux, uy, th = u[:n], u[n:2 * n], u[2 * n:]
        out = np.zeros(3 * n)
        i, j, nx, ny = self.pi, self.pj, self.nx, self.ny
        tx, ty = -ny, nx
        # Relative motion of i's contact point against j's: normal closing and tangential slip.
        dn = (ux[i] - ux[j]) * nx + (uy[i] - uy[j]) * ny
        # Spin theta (counter-clockwise) moves i's contact point r_i n by r_i theta t, j's point (-r_j n) by -r_j theta t.
        dt_ = (ux[i] - ux[j]) * tx + (uy[i] - uy[j]) * ty - self.r[i] * th[i] - self.r[j] * th[j]
        fn, ft = self.kn * dn, self.kt * dt_
        fx, fy = fn * nx + ft * tx, fn * ny + ft * ty
        out += np.bincount(i, weights=fx, minlength=3 * n)
        out += np.bincount(j, weights=-fx, minlength=3 * n)
        out += np.bincount(n + i, weights=fy, minlength=3 * n)
        out += np.bincount(n + j, weights=-fy, minlength=3 * n)
        out += np.bincount(2 * n + i, weights=-self.r[i] * ft, minlength=3 * n)
        out += np.bincount(2 * n + j, weights=-self.r[j] * ft, minlength=3 * n)
        w, wx, wy = self.wi, self.wnx, self.wny
        wtx, wty = -wy, wx
        dn = ux[w] * wx + uy[w] * wy
        dt_ = ux[w] * wtx + uy[w] * wty - self.r[w] * th[w]
        fn, ft = self.kn * dn, self.kt * dt_
        out += np.bincount(w, weights=fn * wx + ft * wtx, minlength=3 * n)
        out += np.bincount(n + w, weights=fn * wy + ft * wty, minlength=3 * n)
        out += np.bincount(2 * n + w, weights=-self.r[w] * ft, minlength=3 * n)
        return out

    def top_eigen(self, mask, iters=3000, seed=1):
        """Largest omega^2 of M^-1 K restricted to the DOFs in mask (power iteration on M^-1/2 K M^-1/2)."""
        rng = np.random.default_rng(seed)
        s = np.sqrt(self.minv) * mask
        v = rng.standard_normal(3 * self.n) * mask
        v /= np.linalg.norm(v)
        lam = 0.0
        for _ in range(iters):
            w = s * self.k_times(s * v)
            lam_new = float(v @ w)
            v = w / np.linalg.norm(w)
            if abs(lam_new - lam) < 1e-10 * lam_new:
                break
            lam = lam_new
        return lam_new, v


def amplification_radius(w, dt, zeta):
    """Spectral radius of one Eq. 10 step for a mode x'' = -w^2 x - 2 zeta w x' (force from the step's start)."""
    a = np.array([[1.0 - w * w * dt * dt, dt * (1.0 - 2.0 * zeta * w * dt)],
                  [-w * w * dt, 1.0 - 2.0 * zeta * w * dt]])
    return max(abs(np.linalg.eigvals(a)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bed")
    ap.add_argument("--width", type=float, default=0.6)
    ap.add_argument("--diameter", type=float, default=0.004)
    ap.add_argument("--density", type=float, default=2700.0)
    ap.add_argument("--kn", type=float, default=800.0)
    ap.add_argument("--kt", type=float, default=800.0)
    ap.add_argument("--restitution", type=float, default=0.9)
    ap.add_argument("--patch", type=float, nargs=4, default=[0.26, 0.30, 0.10, 0.14],
                    help="x0 x1 y0 y1 of the window whose update matrices are formed densely (others held)")
    ap.add_argument("--window-only", action="store_true", help="skip the power iterations over the whole bed")
    a = ap.parse_args()
    data = np.genfromtxt(a.bed, delimiter=",", names=True)
    x, y = data["x"], data["y"]
    n = len(x)
    r = np.full(n, 0.5 * a.diameter)
    m = a.density * math.pi / 6.0 * a.diameter ** 3 * np.ones(n)
    inertia = 0.4 * m * r * r  # spheres, as ParticleStore
    net = Network(x, y, r, m, inertia, a.width, a.kn, a.kt)
    print(f"spheres {n}, pair contacts {len(net.pi)}, wall contacts {len(net.wi)}, "
          f"mean coordination {net.z.mean():.3f}, max {net.z.max()}")
    one = np.ones(n)
    zero = np.zeros(n)
    masks = {
        "full": np.concatenate([one, one, one]),
        "translation only (spins held)": np.concatenate([one, one, zero]),
        "spin only (centres held)": np.concatenate([zero, zero, one]),
    }
    lnr = math.log(1.0 / a.restitution)
    zeta_n = lnr / math.sqrt(math.pi ** 2 + lnr ** 2)  # Eq. 8's damping ratio of the normal pair mode
    print(f"single pair: omega_n = {math.sqrt(2 * a.kn / m[0]):.0f} 1/s, sticking tangential "
          f"omega_t = {math.sqrt(a.kt * (2 / m[0] + 2 * r[0] ** 2 / inertia[0])):.0f} 1/s")
    for name, mask in ({} if a.window_only else masks).items():
        lam, v = net.top_eigen(mask)
        w = math.sqrt(lam)
        spin_share = float(np.sum(v[2 * n:] ** 2))
        line = f"{name:32s} omega_max {w:8.0f} 1/s  dt_max = 2/omega {2.0 / w:.3e} s  spin share of mode {spin_share:.2f}"
        for dt in (1e-4, 2e-4):
            # The top mode's damping ratio is bounded by that of a tangential pair (eta from the normal mode's m_eff).
            zeta = zeta_n * math.sqrt(3.5)
            line += f"  |lambda|(dt={dt:g}) {amplification_radius(w, dt, zeta):.3f}"
        print(line)
    # A per-sphere implicit spin: dividing each spin increment by 1 + dt^2 k_t r^2 Z / I (the sphere's own
    # rotational stiffness) bounds omega_eff^2 dt^2 by 2 (Gershgorin: the spin block's row sums are at most twice
    # its diagonal), so the rotational mode becomes stable at any step, but it acts as a rotational inertia raised
    # by that factor for every motion, not only the spurious one.
    for dt in (1e-4, 2e-4):
        factor = 1.0 + dt * dt * a.kt * r[0] ** 2 * net.z / inertia
        print(f"implicit spin at dt={dt:g}: apparent inertia factor median {np.median(factor):.2f}, max {factor.max():.2f}")
    patch_schemes(net, x, y, a.patch, (1e-4, 1.5e-4, 2e-4))


def patch_schemes(net, x, y, box, steps):
    """Spectral radius of the undamped update over one window of spheres (the rest held), two schemes:
    Eq. 10 as it is, and the spin with its tangential springs sub-cycled in two half steps per step (the centres
    held at the step's start during the sub-steps, the translation driven by the spins of the step's start)."""
    n = net.n
    sel = np.nonzero((x >= box[0]) & (x < box[1]) & (y >= box[2]) & (y < box[3]))[0]
    dofs = np.concatenate([sel, n + sel, 2 * n + sel])
    k = np.zeros((len(dofs), len(dofs)))
    for c, d in enumerate(dofs):
        e = np.zeros(3 * n)
        e[d] = 1.0
        k[:, c] = net.k_times(e)[dofs]
    minv = net.minv[dofs]
    kt, kn = net.kt, net.kn

    def block(kn_, kt_):
        net.kn, net.kt = kn_, kt_
        out = np.zeros((len(dofs), len(dofs)))
        for c, d in enumerate(dofs):
            e = np.zeros(3 * n)
            e[d] = 1.0
            out[:, c] = net.k_times(e)[dofs]
        net.kn, net.kt = kn, kt
        return minv[:, None] * out

    a_nor = block(kn, 0.0)
    a_tan = block(0.0, kt)
    ns = len(sel)
    t = np.arange(2 * ns)
    s = np.arange(2 * ns, 3 * ns)
    a_full = minv[:, None] * k
    print(f"window {box}: {ns} spheres, omega_max {math.sqrt(max(np.linalg.eigvals(a_full).real)):.0f} 1/s")
    dim = len(dofs)
    for dt in steps:
        # State (q, v); Eq. 10: v' = v - dt A q, q' = q + dt v'.
        e10 = np.block([[np.eye(dim) - dt * dt * a_full, dt * np.eye(dim)], [-dt * a_full, np.eye(dim)]])
        # Sub-cycled spin: two half steps of the spin block with the centres at the step's start.
        h = 0.5 * dt
        sub = np.eye(2 * dim)
        for _ in range(2):
            m = np.eye(2 * dim)
            # v_s' = v_s - h (A_st q_t + A_ss q_s); q_s' = q_s + h v_s'
            kick = np.zeros((2 * dim, 2 * dim))
            kick[np.ix_(dim + s, t)] = -h * a_full[np.ix_(s, t)]
            kick[np.ix_(dim + s, s)] = -h * a_full[np.ix_(s, s)]
            m = m + kick
            drift = np.eye(2 * dim)
            drift[np.ix_(s, dim + s)] = h * np.eye(ns)
            sub = drift @ m @ sub
        # Translation: v_t' = v_t - dt (A_tt q_t + A_ts q_s0), q_t' = q_t + dt v_t', from the step's start state.
        tr = np.eye(2 * dim)
        tr[np.ix_(dim + t, t)] = -dt * a_full[np.ix_(t, t)]
        tr[np.ix_(dim + t, s)] = -dt * a_full[np.ix_(t, s)]
        drift = np.eye(2 * dim)
        drift[np.ix_(t, dim + t)] = dt * np.eye(2 * ns)
        # Translation kick uses the step's start, so apply it first, then the spin sub-steps (which read q_t of
        # the start: the kick leaves q_t unchanged), then the translation drift.
        sub_scheme = drift @ sub @ tr
        # Force splitting (r-RESPA, Tuckerman et al. 1992): the tangential springs, which carry the spin mode,
        # kicked in two inner velocity-Verlet steps of dt/2; the normal springs kicked half a step at each end.
        # Every stage is the exact flow of a Hamiltonian part, so the step stays symplectic.
        def kick(a, tau):
            m = np.eye(2 * dim)
            m[dim:, :dim] = -tau * a
            return m
        drift_all = np.eye(2 * dim)
        drift_all[:dim, dim:] = h * np.eye(dim)
        inner = kick(a_tan, 0.5 * h) @ drift_all @ kick(a_tan, 0.5 * h)
        respa = kick(a_nor, 0.5 * dt) @ inner @ inner @ kick(a_nor, 0.5 * dt)
        r1 = max(abs(np.linalg.eigvals(e10)))
        r2 = max(abs(np.linalg.eigvals(sub_scheme)))
        r3 = max(abs(np.linalg.eigvals(respa)))
        print(f"  dt={dt:g}: spectral radius, Eq. 10 {r1:.4f}; spin sub-cycled x2 {r2:.4f}; "
              f"tangential springs sub-cycled x2 (r-RESPA) {r3:.4f}")


if __name__ == "__main__":
    main()
