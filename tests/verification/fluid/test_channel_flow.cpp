// Plane Poiseuille flow: uniform inflow through the bottom, pressure outlet at the top, no-slip side walls.
// Checks the viscous wall treatment, the inlet and the outlet against the developed analytic solution
// v(x) = 6 U x (W - x) / W^2, dP/dy = -12 mu U / W^2 (no gravity).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fluid/gas_solver.hpp"

namespace fluidbed {
namespace {

struct ChannelError {
  double velocity = 0.0;  // max |v - v_exact| / U over the cells of one developed row
  double gradient = 0.0;  // |dP/dy / dP/dy_exact - 1|
};

ChannelError run_channel(int nx) {
  // W = 1, H = 6, U = 1, rho = 1, mu = 0.1: Re = 10, entry length about 0.05 Re W + 0.6 W = 1.1 W.
  const double mu = 0.1;
  const int ny = 6 * nx;
  const Grid<2> grid = Grid<2>::uniform({1.0, 6.0}, {nx, ny});
  GasConfig cfg;
  cfg.rho_g = 1.0;
  cfg.mu_g = mu;
  cfg.gravity = {0.0, 0.0};
  cfg.viscous = ViscousStress::Laplacian;
  cfg.boundary.jets.clear();
  cfg.boundary.inlet_velocity = 1.0;
  cfg.boundary.side_walls = WallKind::NoSlip;
  GasSolver<2> gas(grid, cfg);
  const Field<2> eps(cell_field(grid, 1.0));
  const Field<2> zero(cell_field(grid, 0.0));
  const double dt = 0.5;
  bool steady = false;
  for (int step = 1; step <= 400 && !steady; ++step) {
    const std::vector<double> before = gas.fields().u[1].data();
    gas.advance(step * dt, dt, eps, eps, zero, {zero, zero});
    double change = 0.0;
    for (std::size_t k = 0; k < before.size(); ++k)
      change = std::max(change, std::abs(before[k] - gas.fields().u[1].data()[k]));
    steady = change / dt < 1e-9;
  }
  EXPECT_TRUE(steady);
  // Developed region: rows between y = 3 and y = 4, away from the entry and from the outlet.
  ChannelError err;
  const int j_row = static_cast<int>(3.5 / grid.h[1]);
  for (int i = 0; i < nx; ++i) {
    const double x = grid.centre(0, i);
    err.velocity = std::max(err.velocity, std::abs(gas.fields().u[1](i, j_row) - 6.0 * x * (1.0 - x)));
  }
  const int j_lo = static_cast<int>(3.0 / grid.h[1]);
  const int j_hi = static_cast<int>(4.0 / grid.h[1]);
  double dpdy = 0.0;
  for (int i = 0; i < nx; ++i) dpdy += (gas.fields().p(i, j_hi) - gas.fields().p(i, j_lo)) / ((j_hi - j_lo) * grid.h[1]);
  dpdy /= nx;
  err.gradient = std::abs(dpdy / (-12.0 * mu) - 1.0);
  std::printf("[ channel  ] %2d cells across: max |v - v_exact| = %.2e U, dP/dy relative error %.2e\n", nx, err.velocity,
              err.gradient);
  return err;
}

TEST(ChannelFlow, DevelopedPoiseuilleProfile) {
  // Central viscous fluxes and the half-cell wall distance are second order, so the error should drop by about
  // 4 per halving of the cell; demand a factor of 3 and a 1% profile error at 16 cells.
  const ChannelError e8 = run_channel(8);
  const ChannelError e16 = run_channel(16);
  EXPECT_LT(e16.velocity, e8.velocity / 3.0);
  EXPECT_LT(e16.velocity, 0.01);
  EXPECT_LT(e16.gradient, e8.gradient / 3.0);
  EXPECT_LT(e16.gradient, 0.01);
}

}  // namespace
}  // namespace fluidbed
