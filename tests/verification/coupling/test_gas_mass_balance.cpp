// Gas mass balance of the coupled solver with a moving bed and a jet switching on and off: every gas step
// must close (mass out - mass in + accumulation of rho_g eps V) to the solver tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "settled_bed.hpp"

namespace fluidbed {
namespace {

using namespace coupling_test;

TEST(CoupledGasMassBalance, ClosedEveryStepWithJetSwitching) {
  ScopedOneThread one;
  GasConfig gas = bed_gas();
  const double u_background = 1.0;  // m/s, below U_mf: the bed moves only where the jet blows
  const double jet_u = 15.0, jet_w = 0.02, jet_on = 0.01, jet_off = 0.03;
  gas.boundary.inlet_velocity = u_background;
  gas.boundary.jets.push_back(InletJet{0.5 * kWidth, jet_w, jet_u, jet_on, jet_off});
  CfdDemSimulation<2> sim = bed_simulation(gas);
  sim.initialize();
  double max_balance = 0.0, max_residual = 0.0, max_accumulation = 0.0, max_speed = 0.0;
  int steps = 0, steps_with_jet = 0;
  double max_deps = 0.0;  // largest change of a cell's voidage in one step: the bed moves through the cells
  std::vector<double> eps_before = sim.voidage().data();
  while (sim.time() < 0.05) {
    sim.advance();
    for (std::size_t c = 0; c < eps_before.size(); ++c) {
      max_deps = std::max(max_deps, std::abs(sim.voidage().data()[c] - eps_before[c]));
    }
    eps_before = sim.voidage().data();
    ++steps;
    const GasStepReport& r = sim.last_gas_report();
    // Jets switch at mid-step: the inflow of this step, per metre of depth.
    const double t_mid = sim.time() - 0.5 * sim.macro_dt();
    const bool jet = t_mid >= jet_on && t_mid < jet_off;
    steps_with_jet += jet ? 1 : 0;
    const double inflow = gas.rho_g * (u_background * kWidth + (jet ? (jet_u - u_background) * jet_w : 0.0));
    EXPECT_NEAR(r.mass_in, inflow, 1e-12 * inflow) << "step " << steps;
    // The balance is the signed sum of the cell imbalances the SIMPLE loop drives below mass_tolerance (in
    // the same normalisation), so it cannot exceed it.
    EXPECT_LT(r.mass_balance_relative, gas.mass_tolerance) << "step " << steps;
    max_balance = std::max(max_balance, r.mass_balance_relative);
    max_residual = std::max(max_residual, r.mass_residual);
    // Summed over the domain the accumulation is zero to round-off (the particles' volume is conserved); the
    // cells exchange gas as the voidage changes, and each cell's balance is what the residual measures.
    max_accumulation = std::max(max_accumulation, std::abs(r.accumulation) / r.reference_mass_flow);
  }
  const ParticleStore<2>& p = sim.dem().particles();
  for (std::size_t i = 0; i < p.size(); ++i) max_speed = std::max(max_speed, std::hypot(p.vx[i], p.vy[i]));
  std::printf("[ mass     ] %d gas steps (%d with the jet): max |balance| / reference %.2e (tolerance %.0e), max "
              "residual %.2e, max |total accumulation| / reference %.2e, largest voidage change in a step %.2e, fastest "
              "particle %.2f m/s\n", steps, steps_with_jet, max_balance, gas.mass_tolerance, max_residual,
              max_accumulation, max_deps, max_speed);
  // The test must see a moving bed and both jet states, or it checks nothing.
  EXPECT_GT(steps_with_jet, 10);
  EXPECT_LT(steps_with_jet, steps - 10);
  EXPECT_GT(max_deps, 1e-3);
  EXPECT_GT(max_speed, 0.1);
}

}  // namespace
}  // namespace fluidbed
