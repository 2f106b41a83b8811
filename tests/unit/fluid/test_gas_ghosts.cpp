// Ghost layers of the gas unknowns filled by the physical boundary conditions: a no-slip wall's ghost and its
// mirror average to the wall's speed, a slip wall's ghost repeats its mirror, a pressure outlet's pair averages
// to P_out (to one rounding of 2 P_out - P), the normal velocity beyond a boundary face repeats it; a sub-domain's
// internal side is left to the halo exchange, which is called once per field. Exact up to that rounding, so the
// tolerance is a few ulps of the values (|u|, |P| <= 10).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "parallel/comm.hpp"
#include "fluid/gas_boundary.hpp"
#include "fluid/gas_solver.hpp"

namespace fluidbed {
namespace {

constexpr double kTol = 1e-14;

// A serial communicator that counts the halo exchanges it is asked for.
class CountingComm final : public SerialComm {
 public:
  void exchange_halo(Field<2>&) const override { ++exchanges; }
  void exchange_halo(Field<3>&) const override { ++exchanges; }
  mutable int exchanges = 0;
};

template <int Dim>
void fill_pattern(Field<Dim>& f) {
  for_each(f.box(), [&](const Index<Dim>& c) {
    double v = 0.0;
    for (int a = 0; a < Dim; ++a) v += (a + 1.3) * std::sin(0.7 * c[a] + a);
    f[c] = v;
  });
}

TEST(GasGhosts, NoSlipLidSlipWallAndOutletIn2D) {
  const Grid<2> g = Grid<2>::uniform({1.0, 2.0}, {4, 6}, 2);
  GasBoundaryConfig bc;
  bc.top = TopBoundary::Wall;
  bc.top_wall = WallKind::NoSlip;
  bc.lid_velocity = 1.5;
  bc.side_walls = WallKind::Slip;
  bc.bottom_wall = WallKind::NoSlip;
  FaceFields<2> u(g.domain, g.ghost);
  for (int a = 0; a < 2; ++a) fill_pattern(u[a]);
  CountingComm comm;
  fill_velocity_ghosts(g, bc, comm, u);
  EXPECT_EQ(comm.exchanges, 2);
  double worst = 0.0;
  for (int i = 0; i <= 4; ++i)
    for (int k = 0; k < 2; ++k) {
      // u on vertical faces: lid above (2 u_lid - u), still no-slip distributor below (-u).
      worst = std::max(worst, std::abs(0.5 * (u[0](i, 6 + k) + u[0](i, 5 - k)) - 1.5));
      worst = std::max(worst, std::abs(u[0](i, -1 - k) + u[0](i, k)));
    }
  for (int j = 0; j <= 6; ++j)
    for (int k = 0; k < 2; ++k) {
      // v on horizontal faces beside slip side walls: mirrored.
      worst = std::max(worst, std::abs(u[1](-1 - k, j) - u[1](k, j)));
      worst = std::max(worst, std::abs(u[1](4 + k, j) - u[1](3 - k, j)));
    }
  // Normal components beyond their boundary faces: zero gradient.
  for (int j = 0; j < 6; ++j) worst = std::max(worst, std::abs(u[0](-2, j) - u[0](0, j)) + std::abs(u[0](6, j) - u[0](4, j)));
  for (int i = 0; i < 4; ++i) worst = std::max(worst, std::abs(u[1](i, -1) - u[1](i, 0)) + std::abs(u[1](i, 8) - u[1](i, 6)));
  std::printf("2D velocity ghosts: exact 0, worst error %.3e\n", worst);
  EXPECT_LE(worst, kTol);

  Field<2> p(g.domain, g.ghost);
  fill_pattern(p);
  bc.top = TopBoundary::PressureOutlet;
  bc.top_pressure = 3.25;
  fill_pressure_ghosts(g, bc, comm, p);
  double p_worst = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 2; ++k) {
      p_worst = std::max(p_worst, std::abs(0.5 * (p(i, 6 + k) + p(i, 5 - k)) - 3.25));
      p_worst = std::max(p_worst, std::abs(p(i, -1 - k) - p(i, 0)));
    }
  for (int j = 0; j < 6; ++j) p_worst = std::max(p_worst, std::abs(p(-1, j) - p(0, j)) + std::abs(p(4, j) - p(3, j)));
  std::printf("2D pressure ghosts: exact 0, worst error %.3e\n", p_worst);
  EXPECT_LE(p_worst, kTol);
}

TEST(GasGhosts, FrontBackWallsIn3D) {
  const Grid<3> g = Grid<3>::uniform({1.0, 1.0, 1.0}, {3, 4, 5});
  GasBoundaryConfig bc;
  bc.front_back_walls = WallKind::NoSlip;
  bc.side_walls = WallKind::Slip;
  FaceFields<3> u(g.domain, g.ghost);
  for (int a = 0; a < 3; ++a) fill_pattern(u[a]);
  fill_velocity_ghosts(g, bc, serial_comm(), u);
  double worst = 0.0;
  for (int a : {0, 1})
    for_each(u[a].box().inside(2, false), [&](const Index<3>& c) {
      Index<3> ghost = c;
      ghost[2] = -1;
      worst = std::max(worst, std::abs(u[a][ghost] + u[a][c]));
    });
  // Outlet (the default top): tangential zero gradient.
  for_each(u[2].box().inside(1, true), [&](const Index<3>& c) {
    worst = std::max(worst, std::abs(u[2][shifted<3>(c, 1, 1)] - u[2][c]));
  });
  std::printf("3D velocity ghosts: exact 0, worst error %.3e\n", worst);
  EXPECT_LE(worst, kTol);
}

TEST(GasGhosts, InternalSideOfASubDomainIsLeftToTheHalo) {
  Grid<2> g = Grid<2>::uniform({1.0, 1.0}, {8, 4});
  g.owned.hi[0] = 4;  // the left half: its high x side meets a neighbour rank
  GasBoundaryConfig bc;
  Field<2> p(g.owned, g.ghost, 7.0);
  fill_pattern(p);
  for (int j = 0; j < 4; ++j) p(4, j) = 99.0;  // the ghost column a neighbour would send
  CountingComm comm;
  fill_pressure_ghosts(g, bc, comm, p);
  EXPECT_EQ(comm.exchanges, 1);
  for (int j = 0; j < 4; ++j) {
    EXPECT_EQ(p(4, j), 99.0);
    EXPECT_EQ(p(-1, j), p(0, j));
  }
}

// The solver refreshes the ghosts after every update: after a step of a lid-driven cavity the ghosts above the
// lid mirror the top row about the lid speed.
TEST(GasGhosts, SolverLeavesGhostsConsistentAfterAStep) {
  const Grid<2> g = Grid<2>::uniform({1.0, 1.0}, {8, 8});
  GasConfig cfg;
  cfg.rho_g = 1.0;
  cfg.mu_g = 0.01;
  cfg.viscous = ViscousStress::Laplacian;
  cfg.gravity = {0.0, 0.0, 0.0};
  cfg.boundary.inlet_velocity = 0.0;
  cfg.boundary.top = TopBoundary::Wall;
  cfg.boundary.lid_velocity = 1.0;
  cfg.boundary.jets.clear();
  cfg.max_simple_iterations = 1000;
  cfg.mass_tolerance = 1e-6;
  GasSolver<2> gas(g, cfg);
  Field<2> eps(g.domain, 0, 1.0);
  Field<2> beta(g.domain, 0, 0.0);
  CellVector<2> us{Field<2>(g.domain, 0), Field<2>(g.domain, 0)};
  gas.advance(1.0, 1.0, eps, eps, beta, us);
  const Field<2>& u = gas.fields().u[0];
  double worst = 0.0;
  double speed = 0.0;
  for (int i = 0; i <= 8; ++i) {
    worst = std::max(worst, std::abs(0.5 * (u(i, 8) + u(i, 7)) - 1.0));
    speed = std::max(speed, std::abs(u(i, 7)));
  }
  std::printf("lid ghosts after a step: top-row speed %.4f, exact mean 1, worst error %.3e\n", speed, worst);
  EXPECT_GT(speed, 0.0);
  EXPECT_LE(worst, kTol);
}

}  // namespace
}  // namespace fluidbed
