// A single sphere falling through still gas in 3D reaches the terminal velocity of Eq. 14 (isolated-sphere
// drag): once through the drag law alone with the gas frozen at rest (one-way), once with the 3D gas solved and
// pushed back by the particle (two-way CFD-DEM, CfdDemSimulation<3>).
//
// Tolerance 1%, as in 2D (test_terminal_velocity.cpp): the implicit drag update has u_t as its exact fixed point
// whatever dt, so what is left is the transient (exp(-9) of the initial slip after nine relaxation times, < 1e-3)
// and the counted voidage below 1 (drag ~ eps^-1.7, 1 - eps ~ 4e-6 in a 5 mm cube). Two-way, the particle's force
// on the gas (m g / V_cell ~ 0.1 N/m^3) disturbs the gas at its position by < 1e-3 u_t, which is also asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include <omp.h>

#include "coupling/cfd_dem.hpp"
#include "closures/drag.hpp"

namespace fluidbed {
namespace {

// A 0.1 mm sphere of density 2500 kg/m^3 in air: u_t of about 0.5 m/s at Re of about 3 (both the Stokes and the
// inertial parts of Eq. 14 matter); relaxation time u_t / g of about 0.05 s, so u_t is reached within 0.4 m.
constexpr double kDiameter = 1e-4;
constexpr double kDensity = 2500.0;
constexpr double kHeight = 0.4;
constexpr double kWidth = 0.015;  // x and z
constexpr double kFallTime = 0.5;  // about 9 relaxation times
constexpr double kTolerance = 0.01;

DemConfig single_particle_dem(double dt) {
  DemConfig c;
  c.species = {Species{kDiameter, kDensity}};
  c.domain.dimension = 3;
  c.domain.width = kWidth;
  c.domain.height = kHeight;
  c.domain.depth = kWidth;
  c.dt = dt;
  return c;
}

// Off the cell centres in x and z, so that the trilinear kernels and the face interpolation are exercised.
ParticleStore<3> one_particle() {
  ParticleStore<3> p;
  p.add(0, 0, Species{kDiameter, kDensity}, {0.52 * kWidth, kHeight - 0.01, 0.47 * kWidth});
  return p;
}

double exact_terminal_velocity(const GasConfig& gas) {
  return terminal_velocity(kDiameter, kDensity, gas.rho_g, gas.mu_g, -gas.gravity.y);
}

void print_row(const char* name, double exact, double computed, double gas_v) {
  std::printf("[ terminal3d] %-28s u_t exact %.6f m/s  computed %.6f m/s  rel. error %.2e  gas v at particle %.2e m/s\n",
              name, exact, computed, std::abs(computed / exact - 1.0), gas_v);
}

class TerminalVelocity3d : public ::testing::Test {
 protected:
  void SetUp() override { omp_set_num_threads(1); }
  void TearDown() override { omp_set_num_threads(saved_); }
  int saved_ = omp_get_max_threads();
};

TEST_F(TerminalVelocity3d, OneWayDragLawWithGasAtRest) {
  const GasConfig gas;  // air of Table 1
  const double dt = 1e-4;
  DemSolver<3> dem(single_particle_dem(dt), one_particle());
  ParticleStore<3>& p = dem.particles();
  const double r = p.radius[0];
  const double vp = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  // Gas at rest: -V_p grad P is the buoyancy V_p rho_g g.
  p.fy_ext[0] = -vp * gas.rho_g * gas.gravity.y;
  const double eps = 1.0 - 1e-9;  // the coupling's cap for an isolated particle
  const auto steps = static_cast<int>(std::lround(kFallTime / dt));
  for (int s = 0; s < steps; ++s) {
    const double slip = std::sqrt(p.vx[0] * p.vx[0] + p.vy[0] * p.vy[0] + p.vz[0] * p.vz[0]);
    const double beta = beta_ergun_wen_yu(DragInput{eps, kDiameter, gas.rho_g, gas.mu_g, slip});
    p.drag_k[0] = vp * beta / (1.0 - eps);
    dem.step();
  }
  const double exact = exact_terminal_velocity(gas);
  print_row("one-way (gas frozen at rest)", exact, -p.vy[0], 0.0);
  EXPECT_NEAR(-p.vy[0] / exact, 1.0, kTolerance);
  EXPECT_NEAR(p.vx[0], 0.0, 1e-12);
  EXPECT_NEAR(p.vz[0], 0.0, 1e-12);
  EXPECT_GT(p.y[0], 0.05);  // still falling freely, far from the floor
}

TEST_F(TerminalVelocity3d, TwoWayCoupledInStillGas) {
  GasConfig gas;
  // Nearly closed bottom: a 1 mm/s inflow (0.2% of u_t), because SIMPLE's residual floor cannot resolve a gas
  // exactly at rest (see the 2D test); the particle is compared through its slip to the local gas.
  gas.boundary.inlet_velocity = 1e-3;
  gas.boundary.jets.clear();
  gas.boundary.top = TopBoundary::PressureOutlet;
  // 3 x 80 x 3 cubic 5 mm cells: the cell volume 1.25e-7 m^3 (from the grid) is the 2D test's one-cell depth.
  const int nx = 3, ny = 80, nz = 3;
  const Grid<3> grid = Grid<3>::uniform({kWidth, kHeight, kWidth}, {nx, ny, nz});
  CouplingConfig cc;
  cc.dem_substeps = 5;
  const double dt = 1e-4;
  GasSolver<3> solver(grid, gas);
  // Hydrostatic pressure of gas at rest, so SIMPLE need not build it in the first step.
  for_each(grid.owned, [&](const Index<3>& c) {
    solver.fields().p[c] = gas.rho_g * gas.gravity.y * (grid.centre(1, c[1]) - kHeight);
  });
  CfdDemSimulation<3> sim(DemSolver<3>(single_particle_dem(dt), one_particle()), std::move(solver), cc);
  sim.initialize();
  const auto steps = static_cast<int>(std::lround(kFallTime / sim.macro_dt()));
  double max_mass = 0.0;
  for (int s = 0; s < steps; ++s) {
    sim.advance();
    max_mass = std::max(max_mass, sim.last_gas_report().mass_residual);
  }
  const ParticleStore<3>& p = sim.dem().particles();
  const double exact = exact_terminal_velocity(gas);
  const Vec3 ug = sim.gas().velocity_at(p.pos(0));
  const double v_far = gas.boundary.inlet_velocity;  // interstitial = superficial at eps = 1
  print_row("two-way, slip to local gas", exact, ug.y - p.vy[0], ug.y);
  std::printf("[ terminal3d] two-way: particle velocity (%.2e, %.6f, %.2e) m/s, 1 - min voidage %.2e (exact %.2e), "
              "gas disturbance at the particle %.2e m/s, largest gas mass residual %.1e\n",
              p.vx[0], p.vy[0], p.vz[0], 1.0 - sim.min_voidage(), Species{kDiameter, kDensity}.volume() / grid.cell_measure(),
              ug.y - v_far, max_mass);
  EXPECT_NEAR((ug.y - p.vy[0]) / exact, 1.0, kTolerance);
  EXPECT_LT(std::abs(ug.y - v_far), 1e-3 * exact);
  // The deposited solids fraction is V_p over the 3D cell volume (not an area times a depth): at most the
  // particle's whole volume in one cell.
  const double solids_max = Species{kDiameter, kDensity}.volume() / grid.cell_measure();
  EXPECT_LE(1.0 - sim.min_voidage(), solids_max * (1 + 1e-12));
  EXPECT_GT(1.0 - sim.min_voidage(), 0.1 * solids_max);
  // Nothing pushes it sideways.
  EXPECT_LT(std::abs(p.vx[0]), 1e-3 * exact);
  EXPECT_LT(std::abs(p.vz[0]), 1e-3 * exact);
  EXPECT_GT(p.y[0], 0.05);
}

}  // namespace
}  // namespace fluidbed
