// Verification of the Bingham solids rheology (issue 34): the regularised law against its limits, plane
// Poiseuille and Couette flow of the solids phase through the whole two-fluid step against the closed forms of an
// ideal Bingham fluid (converging with the grid and with the regularisation), a bed held by its yield stress, and the
// rheology with no yield stress being the constant-viscosity one to the bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "closures/drag.hpp"
#include "tfm/solids_stress.hpp"
#include "tfm/tfm_solver.hpp"

namespace fluidbed::tfm {
namespace {

TEST(BinghamLaw, LimitsOfThePapanastasiouForm) {
  const double mu_p = 2.0, tau_y = 50.0, m = 100.0;
  // At rest: mu_p + tau_y m, and continuous into the series branch.
  EXPECT_DOUBLE_EQ(bingham_viscosity(mu_p, tau_y, m, 0.0), mu_p + tau_y * m);
  const double g_small = 1e-11, g_above = 2e-10;  // m g on either side of the series' 1e-8
  EXPECT_NEAR(bingham_viscosity(mu_p, tau_y, m, g_small), mu_p + tau_y * m * (1.0 - 0.5 * m * g_small), 1e-9);
  EXPECT_NEAR(bingham_viscosity(mu_p, tau_y, m, g_above), mu_p + tau_y * m * (1.0 - 0.5 * m * g_above), 1e-6);
  // Yielded: the stress is tau_y + mu_p g up to tau_y exp(-m g).
  for (double g : {0.05, 0.2, 1.0, 10.0}) {
    const double stress = bingham_viscosity(mu_p, tau_y, m, g) * g;
    EXPECT_NEAR(stress, tau_y + mu_p * g, tau_y * std::exp(-m * g) * (1.0 + 1e-12) + 1e-12 * stress) << g;
  }
  // No yield stress: the plastic viscosity exactly.
  EXPECT_EQ(bingham_viscosity(mu_p, 0.0, m, 3.0), mu_p);
}

// Solids flowing along x between two no-slip walls at z = 0 and z = D: a 3D channel periodic in x, 3 cells high
// between a closed bottom and a lid, gravity along x and the bed uniform (eps = 0.45, above eps*, so the Eq. 20
// pressure is uniform). The gas has no viscous stress and no pressure gradient along the periodic x, so in the
// steady state the drag passes the gas's weight to the solids and their shear stress carries the mixture's:
// d tau / dz = -G, G = (eps_s rho_s + eps rho_g) g.
struct Channel {
  double depth = 0.08;    ///< D [m]
  double g = 9.81;        ///< along x [m/s^2]
  double eps = 0.45;
  double mu_p = 20.0;     ///< plastic viscosity [Pa s]
  double tau_y = 0.0;     ///< [Pa]
  double m = 100.0;       ///< regularisation [s]
  double cap = 1e7;       ///< mu_s_max [Pa s]
  double wall_speed = 0.0;  ///< the wall at z = D slides along x at this speed [m/s] (Couette)
};

TfmConfig channel_config(const Channel& ch, int cells_across) {
  TfmConfig c;
  const double h = ch.depth / cells_across;
  c.domain.dimension = 3;
  c.cell_size = h;
  c.domain.width = 3 * h;
  c.domain.height = 3 * h;
  c.domain.depth = ch.depth;
  c.domain.periodic = {true, false, false};
  c.domain.gravity = {ch.g, 0.0, 0.0};
  c.boundary.inlet_velocity = 0.0;
  c.boundary.jets.clear();
  c.boundary.top = TopBoundary::Wall;
  c.eps_initial = ch.eps;
  c.packed_height = c.domain.height;
  c.rheology = SolidsRheology::Bingham;
  c.mu_s_constant = ch.mu_p;
  c.yield_stress = ch.tau_y;
  c.yield_regularisation = ch.m;
  c.mu_s_max = ch.cap;
  c.solids_no_slip_walls = true;
  c.sliding_wall = {ch.wall_speed, 0.0, 0.0};
  return c;
}

// The ideal Bingham fluid's velocity at distance zeta from the channel's centre (half-width b, plug half-width
// z0 = tau_y / G): u = G / (2 mu_p) (b^2 - zeta^2) - tau_y / mu_p (b - |zeta|) outside the plug, the plug's speed
// G / (2 mu_p) (b - z0)^2 inside.
double bingham_poiseuille(double zeta, double b, double G, double mu_p, double tau_y) {
  const double z0 = std::min(tau_y / G, b);
  const double a = std::max(std::abs(zeta), z0);
  return G / (2.0 * mu_p) * (b * b - a * a) - tau_y / mu_p * (b - a);
}

// The shear rate at which the law with the viscosity cap carries the stress tau (signed, as tau): the inverse of the
// monotone min(mu_max, mu(g)) g, by bisection to rounding.
double regularised_shear_rate(double tau, const Channel& ch) {
  const double a = std::abs(tau);
  double lo = 0.0, hi = a / ch.mu_p + 1.0;
  for (int i = 0; i < 200; ++i) {
    const double g = 0.5 * (lo + hi);
    (std::min(ch.cap, bingham_viscosity(ch.mu_p, ch.tau_y, ch.m, g)) * g < a ? lo : hi) = g;
  }
  return std::copysign(0.5 * (lo + hi), tau);
}

// Simpson's rule for f over [a, b] with n (even) intervals.
template <class F>
double simpson(F&& f, double a, double b, int n) {
  const double dz = (b - a) / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) sum += ((i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0)) * f(a + i * dz);
  return sum * dz / 3.0;
}

// The steady profile of the regularised law with the viscosity cap, as the solver's fluid obeys it: the stress
// tau = -G zeta is fixed by the momentum balance, the shear rate is its inverse under the law, and u(zeta) the
// integral from |zeta| to b of it (2000 intervals).
double regularised_poiseuille(double zeta, double b, double G, const Channel& ch) {
  return simpson([&](double s) { return regularised_shear_rate(G * s, ch); }, std::abs(zeta), b, 2000);
}

// The steady profile with the wall at z = D sliding at U (plane Couette-Poiseuille flow) at heights zs from the fixed
// wall: the stress is tau_0 - G z, the shear rate its inverse under the law, u(z) the integral from the fixed wall
// (1000 intervals), and tau_0 the one that gives u(D) = U (bisection; u(D) grows with tau_0).
std::vector<double> regularised_couette_poiseuille(const std::vector<double>& zs, double D, double G, const Channel& ch) {
  auto speed = [&](double tau0, double z) {
    return simpson([&](double s) { return regularised_shear_rate(tau0 - G * s, ch); }, 0.0, z, 1000);
  };
  double lo = -G * D - 10.0 * (ch.tau_y + ch.cap * std::abs(ch.wall_speed) / D + 1.0), hi = -lo;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (speed(mid, D) < ch.wall_speed ? lo : hi) = mid;
  }
  std::vector<double> u;
  for (double z : zs) u.push_back(speed(0.5 * (lo + hi), z));
  return u;
}

// The channel from the regularised law's steady profile (every phase, every face along x) run to t_end: the discrete
// steady state lies within the discretisation error of it, so a short run settles there (from rest or from another
// profile the momentum step's point-implicit viscous diagonal makes the large plug viscosity relax like Jacobi
// sweeps: about a thousand steps an e-fold at 16 cells). `change`: the largest change of the profile over the run's
// last tenth, to show that it settled.
struct ProfileError {
  double max_error = 0.0;   ///< largest |u - u_exact| over the cells, over the exact profile's largest speed
  double change = 0.0;      ///< largest change over the last tenth of the run, over the same
  double plug_speed = 0.0;  ///< the computed centreline speed [m/s]
  double exact_plug = 0.0;  ///< the exact profile's largest speed [m/s]
};

ProfileError run_channel(const Channel& ch, int cells_across, double t_end) {
  TfmSolver<3> s(channel_config(ch, cells_across));
  const double G = ((1.0 - ch.eps) * s.config().rho_s + ch.eps * s.config().rho_g) * ch.g;
  const double h = ch.depth / cells_across, b = 0.5 * ch.depth;
  std::vector<double> exact(static_cast<std::size_t>(cells_across)), zs;
  for (int k = 0; k < cells_across; ++k) {
    exact[static_cast<std::size_t>(k)] = regularised_poiseuille((k + 0.5) * h - b, b, G, ch);
    zs.push_back((k + 0.5) * h);
  }
  if (ch.wall_speed != 0.0) exact = regularised_couette_poiseuille(zs, ch.depth, G, ch);
  std::vector<NamedArray> state = s.save_state();
  for (NamedArray& a : state) {
    if (a.name != "us" && a.name != "ug") continue;
    for (int k = 0; k < a.nz; ++k)
      for (int j = 0; j < a.ny; ++j)
        for (int i = 0; i < a.nx; ++i) a.values[static_cast<std::size_t>(i + a.nx * (j + a.ny * k))] = exact[static_cast<std::size_t>(k)];
  }
  s.restore_state(state);
  auto profile = [&] {
    std::vector<double> u(static_cast<std::size_t>(cells_across));
    for (int k = 0; k < cells_across; ++k) u[static_cast<std::size_t>(k)] = s.state().us[0][Index<3>{0, 1, k}];
    return u;
  };
  s.advance_to(0.9 * t_end);
  const std::vector<double> before = profile();
  s.advance_to(t_end);
  const std::vector<double> u = profile();
  ProfileError e;
  for (double v : exact) e.exact_plug = std::max(e.exact_plug, std::abs(v));
  for (std::size_t k = 0; k < u.size(); ++k) {
    e.max_error = std::max(e.max_error, std::abs(u[k] - exact[k]) / e.exact_plug);
    e.change = std::max(e.change, std::abs(u[k] - before[k]) / e.exact_plug);
  }
  e.plug_speed = u[u.size() / 2];
  return e;
}

TEST(BinghamLaw, RegularisedChannelFlowConvergesToTheIdealBinghamFluid) {
  // No solver here: the regularised law's own steady channel flow against the ideal one, as m (and the cap, kept
  // at tau_y m so that it never binds) grows. The plug creeps at a shear rate ~ 1 / m, so its speed error falls
  // as 1 / m.
  Channel ch;
  ch.tau_y = 290.0;
  const double b = 0.5 * ch.depth, G = ((1.0 - ch.eps) * 2700.0 + ch.eps * 1.205) * ch.g;
  double last = 0.0;
  for (double m : {10.0, 100.0, 1000.0}) {
    ch.m = m;
    ch.cap = 1e12;
    double worst = 0.0;
    for (int i = 0; i <= 40; ++i) {
      const double zeta = -b + i * (2.0 * b / 40);
      worst = std::max(worst, std::abs(regularised_poiseuille(zeta, b, G, ch) - bingham_poiseuille(zeta, b, G, ch.mu_p, ch.tau_y)));
    }
    const double rel = worst / bingham_poiseuille(0.0, b, G, ch.mu_p, ch.tau_y);
    std::printf("regularised channel, m = %g s: largest error %.3e of the plug speed%s\n", m, rel,
                last > 0.0 ? (" (order " + std::to_string(std::log10(last / rel)) + ")").c_str() : "");
    if (last > 0.0) {
      EXPECT_NEAR(std::log10(last / rel), 1.0, 0.1) << m;
    }
    last = rel;
  }
}

TEST(BinghamChannel, PoiseuilleFlowConvergesToTheRegularisedProfileAtSecondOrder) {
  // The plug half-width tau_y / G is a quarter of the channel; the law at the rheology's defaults (m = 100 s, the
  // cap mu_s_max = 100 Pa s). 8 and 16 cells across (32 settles too slowly for a unit test: docs/model-tfm.md gives
  // it). The wall cells' shear rate is one-sided inside the domain, the stencil's error is second order.
  Channel ch;
  ch.tau_y = 290.0;
  ch.cap = 100.0;
  const ProfileError coarse = run_channel(ch, 8, 2.0), fine = run_channel(ch, 16, 4.0);
  const double order = std::log2(coarse.max_error / fine.max_error);
  std::printf("Bingham channel: plug %.4f m/s (regularised exact %.4f); largest error over the plug speed 8 cells "
              "%.3e (last tenth changed %.1e), 16 cells %.3e (%.1e): order %.2f\n",
              fine.plug_speed, fine.exact_plug, coarse.max_error, coarse.change, fine.max_error, fine.change, order);
  EXPECT_LT(coarse.change, 0.05 * coarse.max_error);  // settled: what is left is the grid's error
  EXPECT_LT(fine.change, 0.05 * fine.max_error);
  EXPECT_LT(fine.max_error, 0.08);
  EXPECT_GT(order, 1.7);
}

TEST(BinghamChannel, CouettePoiseuilleFlowWithASlidingWall) {
  // The wall at z = D slides against the flow at 0.3 m/s: the stress is no longer symmetric, the plug shifts
  // towards the sliding wall (plane Couette-Poiseuille flow). Plain Couette flow (no gravity) is checked too: its
  // stress is uniform, so its profile is linear under any law (what it tests is the sliding wall itself).
  Channel ch;
  ch.tau_y = 290.0;
  ch.cap = 100.0;
  ch.wall_speed = -0.3;
  const ProfileError coarse = run_channel(ch, 8, 2.0), fine = run_channel(ch, 16, 4.0);
  const double order = std::log2(coarse.max_error / fine.max_error);
  std::printf("Bingham Couette-Poiseuille channel: largest speed %.4f m/s; largest error 8 cells %.3e (changed %.1e), "
              "16 cells %.3e (%.1e): order %.2f\n",
              fine.exact_plug, coarse.max_error, coarse.change, fine.max_error, fine.change, order);
  EXPECT_LT(coarse.change, 0.05 * coarse.max_error);
  EXPECT_LT(fine.change, 0.05 * fine.max_error);
  EXPECT_LT(fine.max_error, 0.08);
  EXPECT_GT(order, 1.5);
  Channel couette = ch;
  couette.g = 0.0;
  couette.wall_speed = 0.2;
  const ProfileError linear = run_channel(couette, 8, 1.0);
  std::printf("Bingham plane Couette: largest error %.2e of the wall speed\n", linear.max_error);
  EXPECT_LT(linear.max_error, 1e-6);
}

// A packed bed between two walls 6 cm apart, periodic along x, with gravity tilted by 3 degrees towards +x and no
// inflow: the Eq. 20 solids pressure carries the weight, the solids shear stress the pull along x, G_x b = 24 Pa at
// the walls. A yield stress above it holds the bed: it creeps as the regularised law's steady channel flow below
// the yield stress, a fluid of viscosity min(mu_s_max, mu_p + tau_y m) (at the defaults the cap, 100 Pa s); without
// one (the constant-viscosity fluid, the same law at tau_y = 0) it flows a hundred times faster. (At minimum
// fluidisation the tilted bed does not come to rest in this model: the pull along x changes the drag's slip, the bed
// compacts, and the compaction's strain rate yields the regularised material; docs/model-tfm.md.)
TfmConfig tilted_bed(double tau_y) {
  TfmConfig c;
  c.domain.dimension = 3;
  c.cell_size = 0.01;
  c.domain.width = 0.03;
  c.domain.height = 0.3;
  c.domain.depth = 0.06;
  c.domain.periodic = {true, false, false};
  const double tilt = 3.0 * 3.14159265358979323846 / 180.0;
  c.domain.gravity = {9.81 * std::sin(tilt), -9.81 * std::cos(tilt), 0.0};
  c.packed_height = 0.2;
  c.boundary.jets.clear();
  c.boundary.inlet_velocity = 0.0;
  c.rheology = SolidsRheology::Bingham;
  c.yield_stress = tau_y;
  c.solids_no_slip_walls = true;
  return c;
}

TEST(BinghamBed, YieldStressHoldsATiltedPackedBed) {
  const double tau_y = 50.0, t_end = 1.0;
  TfmSolver<3> held(tilted_bed(tau_y)), free(tilted_bed(0.0));
  held.advance_to(t_end);
  free.advance_to(t_end);
  const TfmConfig& c = held.config();
  const double g_x = c.domain.gravity.x, b = 0.03;
  // The bulk: rows 0-14 of the 20-row bed, below the surface's rows.
  double eps = 0.0, centre = 0.0;
  for (int j = 0; j < 15; ++j) {
    eps += held.state().eps[Index<3>{1, j, 3}] / 15.0;
    centre = std::max(centre, 0.5 * (held.state().us[0][Index<3>{1, j, 2}] + held.state().us[0][Index<3>{1, j, 3}]));
  }
  const double G = ((1.0 - eps) * c.rho_s + eps * c.rho_g) * g_x;
  const double mu_creep = std::min(c.mu_s_max, c.mu_s_constant + tau_y * c.yield_regularisation);
  const double creep = G * b * b / (2.0 * mu_creep);  // the centre's speed in the steady creep
  TfmSolver<3> later(tilted_bed(tau_y));
  later.restore_state(held.save_state());
  later.advance_to(t_end + 0.1);
  const double change = std::abs(later.state().us[0][Index<3>{1, 7, 3}] - held.state().us[0][Index<3>{1, 7, 3}]);
  const double free_centre = free.state().us[0][Index<3>{1, 7, 3}];
  std::printf("tilted packed bed, wall stress %.1f Pa: tau_y %.0f Pa, centre %.3e m/s (steady creep %.3e, change "
              "over 0.1 s %.1e); tau_y 0: %.3e m/s\n",
              G * b, tau_y, centre, creep, change, free_centre);
  EXPECT_GT(tau_y, G * b);
  // The creep, to the 6-cell profile's error (the channel's at 8 cells: 23%), and settled.
  EXPECT_NEAR(centre / creep, 1.0, 0.25);
  EXPECT_LT(change, 0.01 * creep);
  EXPECT_GT(free_centre, 50.0 * creep);
}

TEST(BinghamBed, NoYieldStressIsTheConstantViscosityRheologyToTheBit) {
  TfmConfig c;
  c.domain.width = 0.2;
  c.domain.height = 0.4;
  c.packed_height = 0.2;
  c.boundary.jets = {InletJet{0.1, 0.04, 20.0, 0.0, 1.0}};
  c.rheology = SolidsRheology::ConstantViscosity;
  TfmSolver<2> constant(c);
  c.rheology = SolidsRheology::Bingham;
  c.yield_stress = 0.0;
  TfmSolver<2> bingham(c);
  constant.advance_to(0.03);
  bingham.advance_to(0.03);
  EXPECT_GT(constant.max_solids_speed(), 1e-2);
  EXPECT_EQ(constant.state().steps, bingham.state().steps);
  for_each(constant.state().eps.box(), [&](const Index<2>& cell) {
    ASSERT_EQ(constant.state().eps[cell], bingham.state().eps[cell]);
    ASSERT_EQ(constant.state().p[cell], bingham.state().p[cell]);
  });
}

}  // namespace
}  // namespace fluidbed::tfm
