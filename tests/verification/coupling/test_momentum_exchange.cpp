// Momentum exchange in a steady packed bed below minimum fluidisation: what the particles feel equals what
// the gas pressure drop says, and what the gas feels equals what the particles feel.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "settled_bed.hpp"

namespace fluidbed {
namespace {

using namespace coupling_test;

TEST(MomentumExchange, FluidForceMatchesPressureDropAndGasReaction) {
  ScopedOneThread one;
  const SettledBed& bed = settled_bed();
  const Species sp;
  GasConfig gas = bed_gas();
  const double g = -gas.gravity.y;
  const double u_mf = ergun_minimum_fluidisation_velocity(bed.eps_interior, sp.diameter, sp.density, gas.rho_g,
                                                          gas.mu_g, g);
  // Half of U_mf from before t = 0, so that initialize() already solves the flowing gas.
  gas.boundary.jets.push_back(full_width_inflow(0.5 * u_mf, -1.0, 1.0));
  CfdDemSimulation<2> sim = bed_simulation(gas);
  sim.initialize();
  // 0.05 s: the packed bed settles onto the gas force within a few steps (it moves by less than its overlaps).
  while (sim.time() < 0.05) sim.advance();

  const ParticleStore<2>& p = sim.dem().particles();
  const double area = kWidth * sp.diameter;
  const double v_s = total_particle_volume(p);
  // Gas momentum over the whole domain: the pressure drop carries the gas's own weight and the force the gas
  // exerts on the particles (drag plus -V_p grad P): dP A = F_fluid + rho_g g V_gas.
  const double dp = distributor_pressure(sim.gas()) - gas.boundary.top_pressure;
  const double f_expected = dp * area - gas.rho_g * g * (area * kHeight - v_s);
  const Vec2 f_fluid = sim.total_fluid_force();
  double drag = 0.0, drag_x = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    drag += p.drag_k[i] * (p.ugy[i] - p.vy[i]);
    drag_x += p.drag_k[i] * (p.ugx[i] - p.vx[i]);
  }
  const Vec2 reaction = sim.total_gas_reaction();
  const double weight = total_particle_weight(p, g);
  const double err_dp = std::abs(f_fluid.y / f_expected - 1.0);
  const double err_reaction = std::abs(reaction.y / drag - 1.0);
  std::printf("[ momentum ] U = %.3f m/s (0.5 U_mf): dP = %.2f Pa, fluid force %.5f N (%.3f of the weight)\n",
              0.5 * u_mf, dp, f_fluid.y, f_fluid.y / weight);
  std::printf("[ momentum ] fluid force: exact (dP A - gas weight) %.5f N  computed %.5f N  rel. error %.2e\n",
              f_expected, f_fluid.y, err_dp);
  std::printf("[ momentum ] gas reaction: exact (particle drag sum) %.5f N  computed %.5f N  rel. error %.2e; "
              "x: drag %.2e N, reaction %.2e N\n", drag, reaction.y, err_reaction, drag_x, reaction.x);
  // Below U_mf the gas carries only part of the bed.
  EXPECT_GT(f_fluid.y, 0.1 * weight);
  EXPECT_LT(f_fluid.y, 0.5 * weight);
  // Tolerance 2%: the two sides differ only where the discrete pressure gradient is not linear: in the cell
  // row holding the bed surface (the gradient drops from the bed's value to the gas's across one cell, and
  // the particles there see it bilinearly interpolated) and in the bottom row (extrapolated to the
  // distributor). The surface row holds dy / H_bed ~ 7% of the bed; at most about a quarter of that row's
  // force is misassigned by a linear interpolation of a one-cell step, so |error| < 2%.
  EXPECT_LT(err_dp, 0.02);
  // Tolerance 2%: the gas sees the drag coefficients deposited with the bilinear kernel and the cell-centred
  // gas velocity gathered with the same kernel, the particles the face velocities interpolated to their
  // centres. Both interpolations are exact for a linear velocity, so they differ only in the surface row,
  // where the interstitial velocity jumps from U / eps to U across one cell: the same 2% bound as above.
  EXPECT_LT(err_reaction, 0.02);
  // Nothing drives the gas sideways: the horizontal forces are round-off or asymmetry of the random bed.
  EXPECT_LT(std::abs(reaction.x), 0.02 * std::abs(reaction.y));
}

}  // namespace
}  // namespace fluidbed
