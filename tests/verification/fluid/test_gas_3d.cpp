// The gas solver in three dimensions (GasSolver<3>): developed laminar flow in a square duct against the series
// solution, a packed bed against Ergun, the gas mass balance with a breathing blob and a disc jet, and a 3D run
// that is uniform in z reproducing the 2D solver.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <tuple>

#include "closures/drag.hpp"
#include "fluid/gas_solver.hpp"

namespace fluidbed {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kD = 0.004;  // Table 1: 4 mm particles

Field<3> cells(const Grid<3>& g, double value) { return Field<3>(g.domain, 0, value); }
CellVector<3> zero_velocity(const Grid<3>& g) { return {cells(g, 0.0), cells(g, 0.0), cells(g, 0.0)}; }

// White, Viscous Fluid Flow (3rd ed., 2006), Eq. 3-48 for the duct |x| <= h, |z| <= h: the developed velocity
// per unit (-dP/dy) / mu, and the flow rate Q per unit (-dP/dy) / mu.
double duct_velocity(double x, double z, double h) {
  double s = 0.0;
  for (int i = 1; i < 200; i += 2) {
    const double sign = ((i - 1) / 2) % 2 == 0 ? 1.0 : -1.0;
    s += sign * (1.0 - std::cosh(i * kPi * z / (2.0 * h)) / std::cosh(i * kPi / 2.0)) *
         std::cos(i * kPi * x / (2.0 * h)) / (i * i * i);
  }
  return 16.0 * h * h / (kPi * kPi * kPi) * s;
}
double duct_flow_rate(double h) {
  double s = 0.0;
  for (int i = 1; i < 200; i += 2) s += std::tanh(i * kPi / 2.0) / std::pow(i, 5);
  return 4.0 * h * h * h * h / 3.0 * (1.0 - 192.0 / std::pow(kPi, 5) * s);
}

struct DuctResult {
  double centre = 0.0;    // centre-line velocity
  double gradient = 0.0;  // dP/dy
  double centre_exact = 0.0;
  double gradient_exact = 0.0;  // at the imposed flow rate
  double flow_rate = 0.0;  // through the mid cross-section
};

DuctResult run_duct(int n) {
  // Side a = 1, length 3, U = 1, rho = 1, mu = 1: Re = 1, developed within about 0.6 a of the inlet. Uniform
  // inflow through the bottom, pressure outlet at the top, no-slip on all four walls, no gravity.
  const Grid<3> grid = Grid<3>::uniform({1.0, 3.0, 1.0}, {n, 3 * n, n});
  GasConfig cfg;
  cfg.rho_g = 1.0;
  cfg.mu_g = 1.0;
  cfg.gravity = {0.0, 0.0, 0.0};
  cfg.viscous = ViscousStress::Laplacian;
  cfg.boundary.jets.clear();
  cfg.boundary.inlet_velocity = 1.0;
  cfg.boundary.side_walls = WallKind::NoSlip;
  cfg.boundary.front_back_walls = WallKind::NoSlip;
  GasSolver<3> gas(grid, cfg);
  const Field<3> eps = cells(grid, 1.0);
  const Field<3> zero = cells(grid, 0.0);
  const CellVector<3> us = zero_velocity(grid);
  const double dt = 1.0;
  bool steady = false;
  for (int step = 1; step <= 300 && !steady; ++step) {
    const std::vector<double> before = gas.fields().u[1].data();
    gas.advance(step * dt, dt, eps, eps, zero, us);
    double change = 0.0;
    for (std::size_t k = 0; k < before.size(); ++k)
      change = std::max(change, std::abs(before[k] - gas.fields().u[1].data()[k]));
    steady = change / dt < 1e-9;
  }
  EXPECT_TRUE(steady);
  // Developed region: the middle of the duct, a from the inlet and from the outlet.
  const double h = 0.5;
  const double g_exact = 1.0 / duct_flow_rate(h);  // (-dP/dy) / mu for Q = U a^2 = 1
  const double v_centre_exact = g_exact * duct_velocity(0.0, 0.0, h);
  const int j_mid = 3 * n / 2;
  const double v_centre = gas.velocity_at({0.5, grid.centre(1, j_mid), 0.5}).y;
  const int j_lo = n;
  const int j_hi = 2 * n;
  double dpdy = 0.0;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      dpdy += (gas.fields().p(i, j_hi, k) - gas.fields().p(i, j_lo, k)) / ((j_hi - j_lo) * grid.h[1]);
  dpdy /= n * n;
  DuctResult res{v_centre, dpdy, v_centre_exact, -g_exact, 0.0};
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i) res.flow_rate += gas.fields().u[1](i, j_mid, k) * grid.h[0] * grid.h[2];
  std::printf("[ duct     ] %2d cells across: centre-line v = %.5f (series %.5f, error %.2e), dP/dy = %.5f (series "
              "%.5f, error %.2e), flow rate %.15f (imposed 1)\n", n, v_centre, v_centre_exact,
              std::abs(v_centre / v_centre_exact - 1.0), dpdy, -g_exact, std::abs(dpdy / -g_exact - 1.0), res.flow_rate);
  return res;
}

TEST(Gas3d, SquareDuctDevelopedFlowAgainstSeries) {
  // Central viscous fluxes and the half-cell wall distance are second order, so the error is C h^2 + O(h^3):
  // demand an observed order above 1.7 between 7 and 11 cells across, and the Richardson extrapolation of the
  // two (which removes the h^2 term) within 0.5% of the series; the flow rate is imposed by the inlet and must
  // pass every cross-section to round-off. Odd counts put a cell centre on the duct's axis.
  const DuctResult r7 = run_duct(7);
  const DuctResult r11 = run_duct(11);
  const double ratio = (11.0 / 7.0) * (11.0 / 7.0);
  for (auto [c7, c11, exact, what] : {std::tuple{r7.centre, r11.centre, r7.centre_exact, "centre-line velocity"},
                                      std::tuple{r7.gradient, r11.gradient, r7.gradient_exact, "dP/dy"}}) {
    const double order = std::log(std::abs(c7 - exact) / std::abs(c11 - exact)) / std::log(11.0 / 7.0);
    const double extrapolated = c11 + (c11 - c7) / (ratio - 1.0);
    std::printf("[ duct     ] %s: observed order %.2f, Richardson extrapolation %.5f (series %.5f, error %.2e)\n",
                what, order, extrapolated, exact, std::abs(extrapolated / exact - 1.0));
    EXPECT_GT(order, 1.7) << what;
    EXPECT_LT(std::abs(c11 / exact - 1.0), 0.035) << what;
    EXPECT_LT(std::abs(extrapolated / exact - 1.0), 0.005) << what;
  }
  EXPECT_NEAR(r7.flow_rate, 1.0, 1e-12);
  EXPECT_NEAR(r11.flow_rate, 1.0, 1e-12);
}

// beta of Eq. 13 per cell from the current gas velocity, the solids being at rest.
void update_beta(const GasSolver<3>& gas, const Field<3>& eps, Field<3>& beta) {
  CellVector<3> u;
  gas.cell_velocity(u);
  const GasConfig& c = gas.config();
  for_each(eps.box(), [&](const Index<3>& i) {
    const double slip = std::sqrt(u[0][i] * u[0][i] + u[1][i] * u[1][i] + u[2][i] * u[2][i]);
    beta[i] = beta_ergun_wen_yu({eps[i], kD, c.rho_g, c.mu_g, slip});
  });
}

TEST(Gas3d, PackedBedPressureDropFollowsErgun) {
  // As in 2D: for uniform flow the discrete momentum balance is eps dP/dy = -beta v + eps rho g exactly, so the
  // deviations from Ergun come only from the SIMPLE tolerance (1e-8) and the lagged beta, converged to 1e-10:
  // a relative tolerance of 1e-6.
  const Grid<3> grid = Grid<3>::uniform({0.08, 0.5, 0.06}, {4, 25, 3});
  const double eps_bed = 0.4;
  for (double u_sup : {0.5, 1.0, 1.8, 3.0}) {
    GasConfig cfg;
    cfg.boundary.jets.clear();
    cfg.boundary.inlet_velocity = u_sup;
    GasSolver<3> gas(grid, cfg);
    const Field<3> eps = cells(grid, eps_bed);
    Field<3> beta = cells(grid, 0.0);
    const CellVector<3> us = zero_velocity(grid);
    double dp_prev = 0.0;
    bool steady = false;
    for (int step = 1; step <= 200 && !steady; ++step) {
      update_beta(gas, eps, beta);
      const GasStepReport rep = gas.advance(step * 0.01, 0.01, eps, eps, beta, us);
      ASSERT_LT(rep.mass_residual, cfg.mass_tolerance);
      steady = std::abs(gas.pressure_drop() - dp_prev) < 1e-10 * std::abs(gas.pressure_drop());
      dp_prev = gas.pressure_drop();
    }
    ASSERT_TRUE(steady);
    const double height = (grid.n(1) - 1) * grid.h[1];  // between the bottom and top cell centres
    const double measured = gas.pressure_drop() / height - cfg.rho_g * std::abs(cfg.gravity.y);
    const double ergun = ergun_pressure_gradient(eps_bed, kD, cfg.rho_g, cfg.mu_g, u_sup);
    std::printf("[ ergun 3d ] U = %.2f m/s: dP/dy (frictional) computed %.4f Pa/m, Ergun %.4f Pa/m, rel. error %.2e\n",
                u_sup, measured, ergun, std::abs(measured / ergun - 1.0));
    EXPECT_NEAR(measured / ergun, 1.0, 1e-6);
    for (int j = 0; j <= grid.n(1); ++j) EXPECT_NEAR(gas.fields().u[1](2, j, 1), u_sup / eps_bed, 1e-9 * u_sup);
  }
}

// Voidage 0.45 with a sphere of radius 0.04 m whose centre rises at 1 m/s and whose voidage breathes.
double blob_eps(const Vec3& x, double t) {
  const double r = std::sqrt((x.x - 0.1) * (x.x - 0.1) + (x.y - 0.1 - t) * (x.y - 0.1 - t) + (x.z - 0.05) * (x.z - 0.05));
  const double inside = 0.5 * (1.0 - std::tanh((r - 0.04) / 0.01));
  return 0.45 + (0.25 + 0.2 * std::sin(60.0 * t)) * inside;
}

TEST(Gas3d, MassBalanceClosedWithBreathingBlobAndDiscJet) {
  // A disc jet switching on at 5 ms: its volume flux is exact because each bottom face takes the jet over the
  // exact area of the disc it covers, so the inflow must be rho (U_bg (A - pi r^2) + U_jet pi r^2) to round-off.
  const Grid<3> grid = Grid<3>::uniform({0.2, 0.4, 0.1}, {10, 20, 5});
  GasConfig cfg;
  cfg.boundary.inlet_velocity = 1.8;
  InletJet jet{0.1, 0.035, 30.0, 0.005, 0.05};
  jet.shape = InletShape::Disc;
  jet.z_centre = 0.05;
  cfg.boundary.jets = {jet};
  GasSolver<3> gas(grid, cfg);
  Field<3> eps_old = cells(grid, 0.0), eps_new = cells(grid, 0.0), beta = cells(grid, 0.0);
  const CellVector<3> us = zero_velocity(grid);
  for_each(grid.domain, [&](const Index<3>& c) { eps_old[c] = blob_eps(grid.centre(c), 0.0); });
  const double dt = 1e-3;
  double max_balance = 0.0, max_accumulation = 0.0, min_in = 1e300, max_in = 0.0;
  for (int step = 1; step <= 30; ++step) {
    const double t = step * dt;
    for_each(grid.domain, [&](const Index<3>& c) { eps_new[c] = blob_eps(grid.centre(c), t); });
    update_beta(gas, eps_new, beta);
    const GasStepReport rep = gas.advance(t, dt, eps_old, eps_new, beta, us);
    // Independent bookkeeping from the fields.
    const GasFields<3>& f = gas.fields();
    const double area = grid.h[0] * grid.h[2];
    double in = 0.0, out = 0.0, acc = 0.0;
    for (int k = 0; k < grid.n(2); ++k)
      for (int i = 0; i < grid.n(0); ++i) {
        in += cfg.rho_g * eps_new(i, 0, k) * f.u[1](i, 0, k) * area;
        out += cfg.rho_g * eps_new(i, grid.n(1) - 1, k) * f.u[1](i, grid.n(1), k) * area;
      }
    for_each(grid.domain, [&](const Index<3>& c) { acc += cfg.rho_g * (eps_new[c] - eps_old[c]) * grid.cell_measure() / dt; });
    const double balance = std::abs(out - in + acc) / rep.reference_mass_flow;
    EXPECT_NEAR(rep.mass_in, in, 1e-12 * rep.reference_mass_flow);
    EXPECT_NEAR(rep.mass_out, out, 1e-12 * rep.reference_mass_flow);
    EXPECT_LT(balance, cfg.mass_tolerance) << "step " << step;
    EXPECT_LT(rep.mass_balance_relative, cfg.mass_tolerance) << "step " << step;
    max_balance = std::max(max_balance, balance);
    max_accumulation = std::max(max_accumulation, std::abs(acc) / rep.reference_mass_flow);
    min_in = std::min(min_in, in);
    max_in = std::max(max_in, in);
    eps_old = eps_new;
  }
  const double disc = kPi * 0.0175 * 0.0175;
  const double in_jet = cfg.rho_g * (1.8 * (0.02 - disc) + 30.0 * disc);
  std::printf("[ mass 3d  ] 30 steps: max |out - in + accumulation| / reference = %.2e, max |accumulation| / "
              "reference = %.2e; inflow with the disc jet %.9f kg/s (exact %.9f), without %.9f kg/s\n",
              max_balance, max_accumulation, max_in, in_jet, min_in);
  EXPECT_GT(max_accumulation, 1e-2);
  EXPECT_NEAR(max_in, in_jet, 1e-12 * in_jet);
  EXPECT_NEAR(min_in, cfg.rho_g * 1.8 * 0.02, 1e-12);
}

// The 2D blob (a cylinder along z in 3D) of the 2D mass-balance test.
double blob_eps_2d(double x, double y, double t) {
  const double r = std::hypot(x - 0.15, y - 0.12 - t);
  const double inside = 0.5 * (1.0 - std::tanh((r - 0.05) / 0.01));
  return 0.45 + (0.25 + 0.2 * std::sin(60.0 * t)) * inside;
}

// A 2D case (slot jet, moving blob, drag, van Leer convection) run in 3D with slip front and back walls, nz cells
// deep: every z-layer must hold the 2D solution. The 3D system differs from the 2D one by the factor h_z in every
// coefficient and by zero couplings in z, so the answers agree to the linear solvers' tolerance (momentum 1e-13
// here, pressure direct), well below 1e-9 of the jet speed; w stays at round-off.
void expect_uniform_in_z_equals_2d(int nz) {
  const int nx = 15, ny = 30;
  GasConfig cfg;
  cfg.boundary.jets = {InletJet{0.15, 0.02, 30.0, 0.002, 0.05}};
  cfg.boundary.front_back_walls = WallKind::Slip;
  cfg.momentum_solver_tolerance = 1e-13;
  GasSolver<2> gas2(Grid<2>::uniform({0.3, 0.6}, {nx, ny}), cfg);
  const Grid<3> g3 = Grid<3>::uniform({0.3, 0.6, 0.06}, {nx, ny, nz});
  GasSolver<3> gas3(g3, cfg);
  const Grid<2>& g2 = gas2.grid();
  Field<2> e2o(g2.domain, 0), e2n(g2.domain, 0), b2(g2.domain, 0);
  const CellVector<2> us2{Field<2>(g2.domain, 0), Field<2>(g2.domain, 0)};
  Field<3> e3o = cells(g3, 0.0), e3n = cells(g3, 0.0), b3 = cells(g3, 0.0);
  const CellVector<3> us3 = zero_velocity(g3);
  const auto fill = [&](double t, Field<2>& e2, Field<3>& e3) {
    for_each(g2.domain, [&](const Index<2>& c) { e2[c] = blob_eps_2d(g2.centre(0, c[0]), g2.centre(1, c[1]), t); });
    for_each(g3.domain, [&](const Index<3>& c) { e3[c] = e2(c[0], c[1]); });
  };
  fill(0.0, e2o, e3o);
  const double dt = 1e-3;
  double du = 0.0, dp = 0.0, w = 0.0, dm = 0.0;
  for (int step = 1; step <= 15; ++step) {
    fill(step * dt, e2n, e3n);
    // beta from a fixed slip of 1 m/s so both see the same drag.
    for_each(g2.domain, [&](const Index<2>& c) { b2[c] = beta_ergun_wen_yu({e2n[c], kD, cfg.rho_g, cfg.mu_g, 1.0}); });
    for_each(g3.domain, [&](const Index<3>& c) { b3[c] = b2(c[0], c[1]); });
    const GasStepReport r2 = gas2.advance(step * dt, dt, e2o, e2n, b2, us2);
    const GasStepReport r3 = gas3.advance(step * dt, dt, e3o, e3n, b3, us3);
    dm = std::max(dm, std::abs(r3.mass_in / g3.length(2) - r2.mass_in) / r2.reference_mass_flow);
    e2o = e2n;
    e3o = e3n;
  }
  const GasFields<2>& f2 = gas2.fields();
  const GasFields<3>& f3 = gas3.fields();
  double p_scale = 0.0;
  for (int k = 0; k < nz; ++k) {
    for (int a = 0; a < 2; ++a)
      for_each(f2.u[a].box(), [&](const Index<2>& c) { du = std::max(du, std::abs(f3.u[a](c[0], c[1], k) - f2.u[a][c])); });
    for_each(f2.p.box(), [&](const Index<2>& c) {
      dp = std::max(dp, std::abs(f3.p(c[0], c[1], k) - f2.p[c]));
      p_scale = std::max(p_scale, std::abs(f2.p[c]));
    });
  }
  for_each(f3.u[2].box(), [&](const Index<3>& c) { w = std::max(w, std::abs(f3.u[2][c])); });
  std::printf("[ 2d = 3d  ] %d cell(s) deep, after 15 steps: max |u_3d - u_2d| = %.2e m/s, max |P_3d - P_2d| = %.2e Pa (of %.3g), "
              "max |w| = %.2e m/s, inflow per depth differs by %.2e of the reference\n", nz, du, dp, p_scale, w, dm);
  EXPECT_LT(du, 1e-9 * 30.0);
  EXPECT_LT(dp, 1e-9 * p_scale);
  EXPECT_LT(w, 1e-12 * 30.0);
  EXPECT_LT(dm, 1e-12);
}

TEST(Gas3d, UniformInZEqualsTheTwoDimensionalSolver) { expect_uniform_in_z_equals_2d(3); }

// One cell across the depth (the paper's bed as a slab one diameter deep, cases/pseudo2d/slab1d.toml): the z
// momentum has only wall faces and the pressure stencil only wall ghosts in z, and the 2D answer must still hold.
TEST(Gas3d, OneCellDeepSlabEqualsTheTwoDimensionalSolver) { expect_uniform_in_z_equals_2d(1); }

}  // namespace
}  // namespace fluidbed
