// A single sphere falling through still gas reaches the terminal velocity of Eq. 14 (isolated-sphere drag),
// once through the drag law alone with the gas frozen at rest (one-way) and once with the gas solved and pushed
// back by the particle (two-way CFD-DEM).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include <omp.h>

#include "coupling/cfd_dem.hpp"
#include "closures/drag.hpp"

namespace fluidbed {
namespace {

// A 0.1 mm sphere of density 2500 kg/m^3 in air: u_t of about 0.5 m/s at Re of about 3, so both the Stokes
// and the inertial parts of Eq. 14 matter, and the relaxation time u_t/g of about 0.05 s lets it reach u_t
// within a 0.4 m fall.
constexpr double kDiameter = 1e-4;
constexpr double kDensity = 2500.0;
constexpr double kHeight = 0.4;
constexpr double kWidth = 0.015;
constexpr double kFallTime = 0.5;  // about 9 relaxation times

DemConfig single_particle_dem(double dt) {
  DemConfig c;
  c.species = {Species{kDiameter, kDensity}};
  c.domain.width = kWidth;
  c.domain.height = kHeight;
  c.dt = dt;
  return c;
}

ParticleStore<2> one_particle() {
  ParticleStore<2> p;
  p.add(0, 0, Species{kDiameter, kDensity}, {0.5 * kWidth, kHeight - 0.01});
  return p;
}

double exact_terminal_velocity(const GasConfig& gas) {
  return terminal_velocity(kDiameter, kDensity, gas.rho_g, gas.mu_g, -gas.gravity.y);
}

void print_row(const char* name, double exact, double computed, double gas_v) {
  std::printf("[ terminal ] %-28s u_t exact %.6f m/s  computed %.6f m/s  rel. error %.2e  gas v at particle %.2e m/s\n",
              name, exact, computed, std::abs(computed / exact - 1.0), gas_v);
}

// Why 1%: the implicit drag update has the terminal velocity as its exact fixed point whatever dt, so what is
// left is the transient (exp(-9) of the initial slip after nine relaxation times, < 1e-3) and the counted
// voidage below 1 (drag ~ eps^-1.7 with 1 - eps < 1e-5 here). The brief asks for 1%; we measure ~1e-4 or less.
constexpr double kTolerance = 0.01;

// One particle: threads only add synchronisation (results do not depend on the thread count).
class TerminalVelocity : public ::testing::Test {
 protected:
  void SetUp() override { omp_set_num_threads(1); }
  void TearDown() override { omp_set_num_threads(saved_); }
  int saved_ = omp_get_max_threads();
};

TEST_F(TerminalVelocity, OneWayDragLawWithGasAtRest) {
  const GasConfig gas;  // air of Table 1
  const double dt = 1e-4;
  DemSolver<2> dem(single_particle_dem(dt), one_particle());
  ParticleStore<2>& p = dem.particles();
  const double r = p.radius[0];
  const double vp = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  // Gas at rest: the pressure gradient is hydrostatic, so -V_p grad P is the buoyancy V_p rho_g g.
  p.fy_ext[0] = -vp * gas.rho_g * gas.gravity.y;
  // The coupling's voidage cap for an isolated particle (CfdDemSimulation caps gathered eps at 1 - 1e-9).
  const double eps = 1.0 - 1e-9;
  const auto steps = static_cast<int>(std::lround(kFallTime / dt));
  for (int s = 0; s < steps; ++s) {
    const double slip = std::hypot(p.vx[0], p.vy[0]);
    const double beta = beta_ergun_wen_yu(DragInput{eps, kDiameter, gas.rho_g, gas.mu_g, slip});
    p.drag_k[0] = vp * beta / (1.0 - eps);  // Eq. 12's beta shared per particle, as in the coupling
    dem.step();
  }
  const double exact = exact_terminal_velocity(gas);
  print_row("one-way (gas frozen at rest)", exact, -p.vy[0], 0.0);
  EXPECT_NEAR(-p.vy[0] / exact, 1.0, kTolerance);
  EXPECT_NEAR(p.vx[0], 0.0, 1e-12);
  EXPECT_GT(p.y[0], 0.05);  // still falling freely, far from the floor
}

// Gas at rest in a closed box with a pressure outlet on top. The gas solver cannot converge this case today:
// its mass residual is normalised by max(inlet flow, rho_g * largest face speed * width, rho_g * 1e-12 m/s *
// width), and with no flow the floor (1e-12 m/s) times mass_tolerance (1e-8) lies far below the round-off of
// the velocities (~1e-16 m/s), so SIMPLE stops at max_simple_iterations with a relative residual ~1e-4.
// Disabled until the floor of GasSolver::Impl::reference_mass_flow is a resolvable velocity scale (see the
// verification-coupling report); enable to check the fix.
TEST_F(TerminalVelocity, StillGasInClosedBoxConverges) {
  GasConfig gas;
  gas.boundary.inlet_velocity = 0.0;
  gas.boundary.jets.clear();
  const Grid<2> grid = Grid<2>::uniform({kWidth, kHeight}, {3, 80});
  GasSolver<2> solver(grid, gas);
  const Field<2> eps(cell_field(grid, 1.0)), zero(cell_field(grid, 0.0));
  for (int k = 1; k <= 3; ++k) {
    const GasStepReport r = solver.advance(k * 5e-4, 5e-4, eps, eps, zero, {zero, zero});
    EXPECT_LT(r.mass_residual, gas.mass_tolerance);
  }
  double v_max = 0.0;
  for (double v : solver.fields().u[1].interior()) v_max = std::max(v_max, std::abs(v));
  EXPECT_LT(v_max, 1e-12);
}

TEST_F(TerminalVelocity, TwoWayCoupledInStillGas) {
  GasConfig gas;
  // Nearly closed bottom: a 1 mm/s inflow (0.2% of u_t); the closed box itself is the test above. The particle
  // is compared through its slip to the local gas, u_g - v_p, which the inflow does not change.
  gas.boundary.inlet_velocity = 1e-3;
  gas.boundary.jets.clear();
  gas.boundary.top = TopBoundary::PressureOutlet;
  // Three columns of cubic 5 mm cells, the particle in the middle one. The bed depth is set to one cell (50
  // particle diameters) rather than one diameter, so the particle's weight is spread over 1.25e-7 m^3 of gas:
  // the force density on the gas (m g / V_cell ~ 0.1 N/m^3) drives a gas velocity far below u_t, and
  // 1 - eps ~ 4e-6. We check that the particle's disturbance of the gas at its own position is negligible
  // (|u_g - inflow| < 1e-3 u_t), so the slip is the terminal velocity of an isolated sphere.
  const int nx = 3, ny = 80;
  const Grid<2> grid = Grid<2>::uniform({kWidth, kHeight}, {nx, ny});
  CouplingConfig cc;
  cc.depth = grid.h[0];
  cc.dem_substeps = 5;
  const double dt = 1e-4;
  GasSolver<2> solver(grid, gas);
  // Start from the hydrostatic pressure of gas at rest, so SIMPLE need not build it in the first step.
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) solver.fields().p(i, j) = gas.rho_g * gas.gravity.y * (grid.centre(1, j) - kHeight);
  CfdDemSimulation<2> sim(DemSolver<2>(single_particle_dem(dt), one_particle()), std::move(solver), cc);
  sim.initialize();
  const auto steps = static_cast<int>(std::lround(kFallTime / sim.macro_dt()));
  double max_mass = 0.0;
  for (int s = 0; s < steps; ++s) {
    sim.advance();
    max_mass = std::max(max_mass, sim.last_gas_report().mass_residual);
  }
  const ParticleStore<2>& p = sim.dem().particles();
  const double exact = exact_terminal_velocity(gas);
  const double v_gas = sim.gas().velocity_at(p.pos(0)).y;
  const double v_far = gas.boundary.inlet_velocity;  // interstitial = superficial at eps = 1
  print_row("two-way, slip to local gas", exact, v_gas - p.vy[0], v_gas);
  std::printf("[ terminal ] two-way: particle velocity %.6f m/s, 1 - min voidage %.2e, gas disturbance at the "
              "particle %.2e m/s, largest gas mass residual %.1e\n",
              p.vy[0], 1.0 - sim.min_voidage(), v_gas - v_far, max_mass);
  EXPECT_NEAR((v_gas - p.vy[0]) / exact, 1.0, kTolerance);
  EXPECT_LT(std::abs(v_gas - v_far), 1e-3 * exact);
  EXPECT_GT(p.y[0], 0.05);
}

}  // namespace
}  // namespace fluidbed
