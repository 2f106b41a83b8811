// Periodic gas: plane Poiseuille flow between the walls y = 0 and y = H, periodic along x (and z in 3D), driven by a
// body force G = rho_g g along the periodic axes, against u(y) = G y (H - y) / (2 mu); and a periodic CFD-DEM box
// whose particles and gas exchange x momentum through the drag only.
// Tolerances. Channel: central viscous fluxes are exact for a parabola, and the half-cell wall distance
// (wall shear mu u_0 / (dy / 2)) lifts the whole discrete profile by the constant C = G dy^2 / (8 mu): the error is
// C / u_max = (dy / H)^2 exactly (u_max = G H^2 / (8 mu)), so it must fall by 4 per halving of dy; we demand the
// measured error within 2% of (dy/H)^2 on two grids (SIMPLE and the steady-state stop leave < 1e-6). Periodicity:
// the profile must not depend on x (or z) to 1e-9 u_max, and the pressure must stay uniform (with walls instead,
// the body force would be carried by a pressure gradient and the gas would stay at rest).
// CFD-DEM box (2D periodic in x; 3D in x and z, particles moving along both): a lattice of one particle per cell,
// off the cell centres along x (and z), keeps every cell's voidage the
// same only if the deposition wraps (a clamped kernel loads the first and last column differently); the drag is
// the only force along x, so the total momentum is conserved up to the splitting of the step: the particles see the
// gas velocity of the last gas step, which lags by (dt / tau_g) of the exchanged momentum, tau_g = rho_g eps / beta
// the gas's relaxation time. We check |change of total momentum| < 2 (dt / tau_g) x (momentum the gas gained) and
// that halving dt halves that error (first order).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "coupling/cfd_dem.hpp"
#include "fluid/gas_solver.hpp"
#include "../dem/dem_closed_form.hpp"

namespace fluidbed {
namespace {

constexpr double kRho = 1.0;
constexpr double kMu = 0.1;
constexpr double kH = 1.0;

GasConfig channel_gas(Vec3 g) {
  GasConfig cfg;
  cfg.rho_g = kRho;
  cfg.mu_g = kMu;
  cfg.gravity = g;
  cfg.viscous = ViscousStress::Laplacian;
  cfg.boundary.jets.clear();
  cfg.boundary.inlet_velocity = 0.0;
  cfg.boundary.top = TopBoundary::Wall;
  cfg.boundary.top_wall = WallKind::NoSlip;
  cfg.boundary.bottom_wall = WallKind::NoSlip;
  return cfg;
}

struct ChannelResult {
  double error = 0.0;       // max over faces |u - u_exact| / u_max, over the driven components
  double predicted = 0.0;   // (dy / H)^2
  double along = 0.0;       // max spread of u along the periodic axes / u_max
  double cross = 0.0;       // max |v| / u_max
  double pressure = 0.0;    // (max P - min P) / (rho g_max H)
};

template <int Dim>
ChannelResult run_periodic_channel(int ny, Vec3 g) {
  const int nx = 4;
  Vec<Dim> extent{};
  Index<Dim> n{};
  for (int a = 0; a < Dim; ++a) {
    extent[a] = 1.0;
    n[a] = a == 1 ? ny : nx;
  }
  Grid<Dim> grid = Grid<Dim>::uniform(extent, n);
  grid.periodic[0] = true;
  if constexpr (Dim == 3) grid.periodic[2] = true;
  GasSolver<Dim> gas(grid, channel_gas(g));
  const Field<Dim> eps(grid.domain, 0, 1.0);
  const Field<Dim> zero(grid.domain, 0, 0.0);
  CellVector<Dim> us;
  for (Field<Dim>& f : us) f = zero;
  // tau = H^2 / (pi^2 nu) ~ 1 s: backward Euler with dt = 5 s damps the slowest mode by 6 per step.
  const double dt = 5.0;
  bool steady = false;
  for (int step = 1; step <= 200 && !steady; ++step) {
    const std::vector<double> before = gas.fields().u[0].data();
    gas.advance(step * dt, dt, eps, eps, zero, us);
    double change = 0.0;
    for (std::size_t k = 0; k < before.size(); ++k)
      change = std::max(change, std::abs(before[k] - gas.fields().u[0].data()[k]));
    steady = change / dt < 1e-12;
  }
  EXPECT_TRUE(steady);
  ChannelResult r;
  const double g_max = std::max(std::abs(g.x), std::abs(g.z));
  const double u_max = kRho * g_max * kH * kH / (8.0 * kMu);
  r.predicted = std::pow(grid.h[1] / kH, 2);
  for (int a = 0; a < Dim; ++a) {
    if (a == 1) continue;
    const double ga = a == 0 ? g.x : g.z;
    const Field<Dim>& u = gas.fields().u[a];
    for (int j = 0; j < ny; ++j) {
      const double y = grid.centre(1, j);
      const double exact = kRho * ga * y * (kH - y) / (2.0 * kMu);
      double lo = 1e300, hi = -1e300;
      for_each(u.box(), [&](const Index<Dim>& c) {
        if (c[1] != j) return;
        r.error = std::max(r.error, std::abs(u[c] - exact) / u_max);
        lo = std::min(lo, u[c]);
        hi = std::max(hi, u[c]);
      });
      r.along = std::max(r.along, (hi - lo) / u_max);
    }
  }
  for_each(gas.fields().u[1].box(), [&](const Index<Dim>& c) {
    r.cross = std::max(r.cross, std::abs(gas.fields().u[1][c]) / u_max);
  });
  double p_lo = 1e300, p_hi = -1e300;
  for_each(grid.domain, [&](const Index<Dim>& c) {
    p_lo = std::min(p_lo, gas.fields().p[c]);
    p_hi = std::max(p_hi, gas.fields().p[c]);
  });
  r.pressure = (p_hi - p_lo) / (kRho * g_max * kH);
  std::printf("[ periodic ] %dD, %2d cells across: max |u - u_exact| / u_max = %.4e, predicted (dy/H)^2 = %.4e, "
              "rel. difference %.2e; spread along the periodic axes %.1e, |v| %.1e, P spread %.1e\n",
              Dim, ny, r.error, r.predicted, std::abs(r.error / r.predicted - 1.0), r.along, r.cross, r.pressure);
  return r;
}

template <int Dim>
void expect_channel(Vec3 g) {
  const ChannelResult c8 = run_periodic_channel<Dim>(8, g);
  const ChannelResult c16 = run_periodic_channel<Dim>(16, g);
  for (const ChannelResult& r : {c8, c16}) {
    EXPECT_NEAR(r.error / r.predicted, 1.0, 0.02);
    EXPECT_LT(r.along, 1e-9);
    EXPECT_LT(r.cross, 1e-9);
    EXPECT_LT(r.pressure, 1e-9);
  }
  EXPECT_NEAR(c8.error / c16.error, 4.0, 0.1) << "second order: the error must fall by 4 per halving of dy";
}

TEST(PeriodicGas, PoiseuilleBetweenWallsPeriodicInX2D) { expect_channel<2>({0.8, 0.0, 0.0}); }

// x and z periodic, driven along both (G_z = G_x / 2): each component its own parabola, so both periodic axes wrap.
TEST(PeriodicGas, PoiseuilleBetweenWallsPeriodicInXAndZ3D) { expect_channel<3>({0.8, 0.0, 0.4}); }

TEST(PeriodicGas, RefusesAPeriodicAxisOfTwoCellsAndHypre) {
  Grid<2> grid = Grid<2>::uniform({1.0, 1.0}, {2, 4});
  grid.periodic[0] = true;
  const GasConfig cfg = channel_gas({0.8, 0.0, 0.0});
  EXPECT_THROW(GasSolver<2>(grid, cfg), Error);
  Grid<2> ok = Grid<2>::uniform({1.0, 1.0}, {4, 4});
  ok.periodic[0] = true;
  GasConfig hypre = cfg;
  hypre.pressure_solver = PressureBackend::HyprePfmg;
  EXPECT_THROW(GasSolver<2>(ok, hypre), Error);
}

// ---- CFD-DEM box periodic in x (and z in 3D)

struct Exchange {
  double exchanged = 0.0;  // momentum the gas gained along x, N s (2D: over the particles' monolayer depth)
  double error = 0.0;      // change of particle + gas momentum along x
  double error_z = 0.0;    // the same along z, relative to the gas's gain along z (3D)
  double bound = 0.0;      // 2 dt / tau_g x exchanged
  double voidage_spread = 0.0;
  double gas_spread = 0.0;  // spread of the cell gas velocity along x / its mean
  int crossed = 0;          // times a particle wrapped across x = 0 = W
};

// Gas momentum along axis a: rho_g eps_face u V over the n faces of each periodic row (face n is face 0).
template <int Dim>
double gas_momentum(const CfdDemSimulation<Dim>& sim, int a) {
  const GasSolver<Dim>& gas = sim.gas();
  const Grid<Dim>& g = gas.grid();
  const Field<Dim>& u = gas.fields().u[a];
  // The gas feels the clipped voidage on its faces, the mean of the two cells (wrapped), as the solver builds it.
  const Field<Dim>& eps = sim.voidage();
  const double e_min = sim.coupling().eps_min;
  const double vol = g.cell_measure() * (Dim == 2 ? sim.depth() : 1.0);
  double m = 0.0;
  for_each(g.domain, [&](const Index<Dim>& c) {
    Index<Dim> lo = c;
    lo[a] = g.wrap(a, c[a] - 1);
    const double ef = 0.5 * (std::max(eps[lo], e_min) + std::max(eps[c], e_min));
    m += gas.config().rho_g * ef * u[c] * vol;
  });
  return m;
}

template <int Dim>
double particle_momentum(const ParticleStore<Dim>& p, int a) {
  double m = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) m += p.mass[i] * p.velocity(a)[i];
  return m;
}

template <int Dim>
Exchange run_box(double dt, double t_end) {
  const test::ScopedThreads one(1);
  const double W = 0.05, H = 0.05, D = 0.03, h = 0.01, v0 = 0.5;
  DemConfig dc = test::one_species_config(0.004, 2700.0, 800.0, 0.9, 0.3, dt, {0.0, 0.0}, W, H,
                                          WallConfig{false, false, true, true, false, false, false});
  dc.domain.periodic = {true, false, Dim == 3};
  if constexpr (Dim == 3) {
    dc.domain.dimension = 3;
    dc.domain.depth = D;
  }
  dc.skin = 4e-4;
  const int nz = Dim == 3 ? 3 : 1;
  const std::size_t count = static_cast<std::size_t>(25 * nz);
  ParticleStore<Dim> p;
  const Species sp = dc.species[0];
  // One particle per cell, 0.3 h from the cell's low face along x (and z): each cell gets 0.8 of its own and 0.2 of
  // its low neighbour's volume along the axis, the first column's from the last one, across x = 0 = W.
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        Vec<Dim> x{}, v{};
        x[0] = (i + 0.3) * h;
        x[1] = (j + 0.5) * h;
        v[0] = v0;
        if constexpr (Dim == 3) {
          x[2] = (k + 0.3) * h;
          v[2] = 0.5 * v0;
        }
        p.add((k * 5 + j) * 5 + i, 0, sp, x, v);
      }
  GasConfig gc;
  gc.gravity = {0.0, 0.0, 0.0};
  gc.boundary.jets.clear();
  gc.boundary.inlet_velocity = 0.0;  // the top stays the paper's pressure outlet
  Vec<Dim> extent{};
  Index<Dim> n{};
  for (int a = 0; a < Dim; ++a) {
    extent[a] = a == 0 ? W : a == 1 ? H : D;
    n[a] = a == 2 ? nz : 5;
  }
  Grid<Dim> grid = Grid<Dim>::uniform(extent, n);
  grid.periodic[0] = true;
  if constexpr (Dim == 3) grid.periodic[2] = true;
  CfdDemSimulation<Dim> sim(DemSolver<Dim>(dc, std::move(p)), GasSolver<Dim>(grid, gc), CouplingConfig{});
  sim.initialize();
  const auto total = [&](int a) { return particle_momentum(sim.dem().particles(), a) + gas_momentum(sim, a); };
  const double m0 = total(0);
  const double g0 = gas_momentum(sim, 0);
  const double m0_z = Dim == 3 ? total(Dim - 1) : 0.0;
  const double g0_z = Dim == 3 ? gas_momentum(sim, Dim - 1) : 0.0;
  double beta_sum = 0.0;
  int samples = 0;
  Exchange ex;
  // Last x of each particle by id (the store is re-sorted in space, so storage indices move).
  std::vector<double> x_prev(count);
  const auto by_id = [&](const ParticleStore<Dim>& q, auto&& f) {
    for (std::size_t i = 0; i < q.size(); ++i) f(static_cast<std::size_t>(q.id[i]), q.x[i]);
  };
  by_id(sim.dem().particles(), [&](std::size_t id, double x) { x_prev[id] = x; });
  double vol = W * H * (Dim == 3 ? D : sim.depth());
  while (sim.time() < t_end - 0.5 * dt) {
    sim.advance();
    const ParticleStore<Dim>& q = sim.dem().particles();
    by_id(q, [&](std::size_t id, double x) {
      if (x < x_prev[id]) ++ex.crossed;
      x_prev[id] = x;
    });
    double k = 0.0;
    for (double v : q.drag_k) k += v;
    beta_sum += k / vol;
    ++samples;
  }
  ex.exchanged = gas_momentum(sim, 0) - g0;
  ex.error = total(0) - m0;
  if constexpr (Dim == 3) ex.error_z = (total(Dim - 1) - m0_z) / (gas_momentum(sim, Dim - 1) - g0_z);
  const double cells = static_cast<double>(grid.cells());
  double eps_mean = 0.0, lo = 1e300, hi = -1e300;
  for (double e : sim.voidage().data()) {
    eps_mean += e / cells;
    lo = std::min(lo, e);
    hi = std::max(hi, e);
  }
  ex.voidage_spread = hi - lo;
  double u_lo = 1e300, u_hi = -1e300, u_mean = 0.0;
  for (double u : sim.gas_velocity()[0].data()) {
    u_lo = std::min(u_lo, u);
    u_hi = std::max(u_hi, u);
    u_mean += u / cells;
  }
  ex.gas_spread = (u_hi - u_lo) / u_mean;
  const double tau_g = sim.gas().config().rho_g * eps_mean / (beta_sum / samples);
  ex.bound = 2.0 * dt / tau_g * std::abs(ex.exchanged);
  std::printf("[ periodic ] %dD CFD-DEM box, dt = %.1e s to t = %.3f s: x momentum exchanged %.4e N s, total change "
              "%.3e N s (%.2e of the exchange; bound 2 dt/tau_g = %.2e, tau_g = %.4f s)%s; voidage spread %.1e, "
              "gas velocity spread %.1e, %d crossings of x = W\n",
              Dim, dt, sim.time(), ex.exchanged, ex.error, std::abs(ex.error / ex.exchanged), 2.0 * dt / tau_g, tau_g,
              Dim == 3 ? fmt::format("; z: {:.2e} of the exchange", std::abs(ex.error_z)).c_str() : "",
              ex.voidage_spread, ex.gas_spread, ex.crossed);
  return ex;
}

template <int Dim>
void expect_box_conserves_momentum() {
  const Exchange a = run_box<Dim>(1e-4, 0.1);
  const Exchange b = run_box<Dim>(5e-5, 0.1);
  const int count = Dim == 3 ? 75 : 25;
  for (const Exchange& e : {a, b}) {
    EXPECT_GT(e.exchanged, 0.0) << "the moving particles must drag the gas along";
    EXPECT_LT(std::abs(e.error), e.bound);
    EXPECT_LT(std::abs(e.error_z), 2.0 * e.bound / e.exchanged);
    EXPECT_LT(e.voidage_spread, 1e-12) << "the wrapped deposition loads every cell alike";
    EXPECT_LT(e.gas_spread, 1e-6) << "the gas moves as one across the periodic plane";
    EXPECT_EQ(e.crossed, count) << "every particle crosses x = W once in 0.1 s at 0.5 m/s";
  }
  EXPECT_NEAR(a.error / b.error, 2.0, 0.3) << "the splitting error is first order in dt";
}

TEST(PeriodicGas, CfdDemBoxConservesMomentumAlongThePeriodicAxis2D) { expect_box_conserves_momentum<2>(); }

// Periodic in x and z, the particles moving along both: each column wraps in both directions.
TEST(PeriodicGas, CfdDemBoxConservesMomentumAlongThePeriodicAxes3D) { expect_box_conserves_momentum<3>(); }

}  // namespace
}  // namespace fluidbed
