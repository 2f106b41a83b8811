// Inlet profiles, validation, interpolation and smoke tests of the staggered gas solver.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "core/error.hpp"
#include "fluid/gas_boundary.hpp"
#include "fluid/gas_solver.hpp"

namespace fluidbed {
namespace {

TEST(GasInlet, JetOverlapConservesVolumeFlux) {
  GasBoundaryConfig bc;  // paper: 1.8 m/s background, one 0.02 m jet of 30 m/s at x = 0.3 for 0 <= t < 0.4
  const Grid<2> grid = Grid<2>::uniform({0.6, 1.0}, {30, 50});
  std::vector<double> u;
  inlet_superficial_profile(bc, grid, 0.1, u);
  // The jet [0.29, 0.31] covers half of the faces [0.28, 0.30] and [0.30, 0.32]: each gets (30 + 1.8) / 2.
  EXPECT_NEAR(u[14], 15.9, 1e-12);
  EXPECT_NEAR(u[15], 15.9, 1e-12);
  EXPECT_DOUBLE_EQ(u[0], 1.8);
  EXPECT_DOUBLE_EQ(u[29], 1.8);
  // Total volume flux: 1.8 * 0.58 + 30 * 0.02 = 1.644 m^2/s.
  const double q = std::accumulate(u.begin(), u.end(), 0.0) * grid.h[0];
  EXPECT_NEAR(q, 1.8 * 0.58 + 30.0 * 0.02, 1e-12);
  // Switched off at t_end, and not yet on before t_start.
  inlet_superficial_profile(bc, grid, 0.4, u);
  EXPECT_DOUBLE_EQ(u[14], 1.8);
  bc.jets[0].t_start = 0.2;
  EXPECT_DOUBLE_EQ(inlet_superficial_velocity(bc, 0.28, 0.30, 0.1), 1.8);
  // A jet aligned with one face fills it completely.
  bc.jets[0].x_centre = 0.31;
  EXPECT_DOUBLE_EQ(inlet_superficial_velocity(bc, 0.30, 0.32, 0.3), 30.0);
}

TEST(GasConfigValidation, RejectsBadValues) {
  GasConfig c;
  EXPECT_NO_THROW(validate(c));
  c.rho_g = -1.0;
  EXPECT_THROW(validate(c), Error);
  c = GasConfig{};
  c.relax_velocity = 1.5;
  EXPECT_THROW(validate(c), Error);
  c = GasConfig{};
  c.boundary.jets[0].width = 0.0;
  EXPECT_THROW(validate(c), Error);
  c = GasConfig{};
  c.mu_g = 0.0;
  c.viscous = ViscousStress::Laplacian;
  EXPECT_THROW(validate(c), Error);
}

TEST(GasInterpolation, LinearFieldsAreExact) {
  // A grid off the origin, P and both velocity components linear: every interpolation to a point and every
  // cell-centred value (central differences inside, one-sided at the sides) reproduces them to rounding.
  Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {6, 5});
  g.origin = {-0.3, 0.5};
  GasConfig cfg;
  GasSolver<2> gas(g, cfg);
  const auto lin = [](double x, double y) { return 2.0 + 3.0 * x - 1.5 * y; };
  GasFields<2>& f = gas.fields();
  for_each(f.u[0].box(), [&](const Index<2>& c) { f.u[0][c] = lin(g.face(0, c[0]), g.centre(1, c[1])); });
  for_each(f.u[1].box(), [&](const Index<2>& c) { f.u[1][c] = 2.0 * lin(g.centre(0, c[0]), g.face(1, c[1])); });
  for_each(f.p.box(), [&](const Index<2>& c) { f.p[c] = lin(g.centre(0, c[0]), g.centre(1, c[1])); });
  // Points inside the node boxes of every field (the outermost half cells are clamped by design).
  for (Vec2 x : {Vec2{-0.2, 0.65}, Vec2{0.0, 1.0}, Vec2{0.17, 1.23}, Vec2{0.24, 1.39}}) {
    const Vec2 u = gas.velocity_at(x);
    EXPECT_NEAR(u.x, lin(x.x, x.y), 1e-12);
    EXPECT_NEAR(u.y, 2.0 * lin(x.x, x.y), 1e-12);
    const Vec2 gp = gas.pressure_gradient_at(x);
    EXPECT_NEAR(gp.x, 3.0, 1e-12);
    EXPECT_NEAR(gp.y, -1.5, 1e-12);
  }
  CellVector<2> ug, grad;
  gas.cell_velocity(ug);
  gas.cell_pressure_gradient(grad);
  for_each(g.owned, [&](const Index<2>& c) {
    const double x = g.centre(0, c[0]), y = g.centre(1, c[1]);
    EXPECT_NEAR(ug[0][c], lin(x, y), 1e-12);
    EXPECT_NEAR(ug[1][c], 2.0 * lin(x, y), 1e-12);
    EXPECT_NEAR(grad[0][c], 3.0, 1e-12);
    EXPECT_NEAR(grad[1][c], -1.5, 1e-12);
  });
}

TEST(GasSolverSmoke, UniformFlowThroughEmptyColumnIsExact) {
  // No particles, inviscid: plug flow at the inlet speed; pressure hydrostatic rho g (y_top - y).
  GasConfig cfg;
  cfg.boundary.jets.clear();
  cfg.boundary.inlet_velocity = 1.0;
  const Grid<2> g = Grid<2>::uniform({0.1, 0.2}, {4, 8});
  GasSolver<2> gas(g, cfg);
  const Field<2> eps = cell_field(g, 1.0), zero = cell_field(g, 0.0);
  GasStepReport rep;
  for (int n = 1; n <= 3; ++n) rep = gas.advance(n * 1e-3, 1e-3, eps, eps, zero, {zero, zero});
  EXPECT_LT(rep.mass_residual, cfg.mass_tolerance);
  for (double v : gas.fields().u[1].interior()) EXPECT_NEAR(v, 1.0, 1e-9);
  for (double u : gas.fields().u[0].interior()) EXPECT_NEAR(u, 0.0, 1e-9);
  // Hydrostatic head over the 7 cell pitches between bottom and top rows (the outlet face holds P = 0).
  EXPECT_NEAR(gas.pressure_drop(), cfg.rho_g * 9.81 * 7 * g.h[1], 1e-8);
  EXPECT_NEAR(gas.fields().p(0, 7), cfg.rho_g * 9.81 * 0.5 * g.h[1], 1e-8);
  const Vec2 vel = gas.velocity_at({0.05, 0.1});
  EXPECT_NEAR(vel.y, 1.0, 1e-9);
  EXPECT_NEAR(gas.pressure_gradient_at({0.05, 0.1}).y, -cfg.rho_g * 9.81, 1e-7);
}

TEST(GasSolverSmoke, RejectsOutOfRangeInputs) {
  GasConfig cfg;
  const Grid<2> g = Grid<2>::uniform({0.1, 0.2}, {4, 8});
  GasSolver<2> gas(g, cfg);
  const Field<2> eps = cell_field(g, 0.5), zero = cell_field(g, 0.0);
  const Field<2> small(IndexBox<2>{{0, 0}, {3, 8}}, 0, 0.5);
  Field<2> bad = cell_field(g, 0.5);
  bad(2, 3) = 0.0;
  EXPECT_THROW(gas.advance(1e-3, 1e-3, eps, bad, zero, {zero, zero}), Error);
  Field<2> beta = cell_field(g, 0.0);
  beta(1, 1) = -1.0;
  EXPECT_THROW(gas.advance(1e-3, 1e-3, eps, eps, beta, {zero, zero}), Error);
  EXPECT_THROW(gas.advance(1e-3, 1e-3, eps, small, zero, {zero, zero}), Error);
  EXPECT_THROW(gas.advance(1e-3, 0.0, eps, eps, zero, {zero, zero}), Error);
  // SIMPLE limited to one iteration cannot converge the start of a jet: a simulation error with a diagnosis.
  cfg.max_simple_iterations = 1;
  GasSolver<2> capped(g, cfg);
  try {
    capped.advance(1e-3, 1e-3, eps, eps, zero, {zero, zero});
    ADD_FAILURE() << "expected a simulation error";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 3);
    EXPECT_NE(std::string(e.what()).find("did not converge"), std::string::npos);
  }
}

TEST(GasSimpleCriteria, LooseInnerSolvesEndAtTheTightAnswer) {
  // A jet into a packed bottom half (drag beta = 1e5 there): inner solves that only reduce their residual by
  // 0.3 per SIMPLE iteration against a reference solved to 1e-12 inside and 1e-11 outside. Both criteria at 1e-8
  // bound the residual of the iterate; the error is that times the momentum operator's condition (a_P over its
  // smallest eigenvalue, below 1e2 on this grid), so 1e-6 of the reference speed with margin.
  GasConfig cfg;
  cfg.boundary.inlet_velocity = 0.5;
  cfg.boundary.jets[0].x_centre = 0.035;
  cfg.boundary.jets[0].velocity = 5.0;
  const Grid<2> g = Grid<2>::uniform({0.1, 0.2}, {6, 12});
  Field<2> eps = cell_field(g, 1.0), beta = cell_field(g, 0.0);
  const Field<2> zero = cell_field(g, 0.0);
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      eps(i, j) = 0.45;
      beta(i, j) = 1e5;
    }
  GasConfig tight = cfg;
  tight.momentum_solver_tolerance = 1e-12;
  tight.pressure_solver_tolerance = 1e-12;
  tight.mass_tolerance = 1e-11;
  tight.momentum_tolerance = 1e-11;
  GasConfig loose = cfg;
  loose.momentum_solver_tolerance = 0.3;
  loose.pressure_solver_tolerance = 0.3;
  GasSolver<2> ref(g, tight), gas(g, loose);
  GasStepReport r_ref, r_gas;
  for (int n = 1; n <= 3; ++n) {
    r_ref = ref.advance(n * 1e-3, 1e-3, eps, eps, beta, {zero, zero});
    r_gas = gas.advance(n * 1e-3, 1e-3, eps, eps, beta, {zero, zero});
  }
  EXPECT_LT(r_gas.mass_residual, loose.mass_tolerance);
  EXPECT_LT(r_gas.momentum_residual, loose.momentum_tolerance);
  const double u_ref = 5.0 / 0.45;
  double err = 0.0;
  for (int a = 0; a < 2; ++a) {
    const auto& x = gas.fields().u[a].data();
    const auto& y = ref.fields().u[a].data();
    for (std::size_t k = 0; k < x.size(); ++k) err = std::max(err, std::abs(x[k] - y[k]) / u_ref);
  }
  std::printf("tight: %d SIMPLE iterations, loose: %d; max |u - u_ref| / U = %.3e (tolerance 1e-6)\n",
              r_ref.simple_iterations, r_gas.simple_iterations, err);
  EXPECT_LT(err, 1e-6);
}

}  // namespace
}  // namespace fluidbed
