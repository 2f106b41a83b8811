// Pressure drop of a DEM bed under an increasing gas velocity: it rises along the packed-bed (Ergun) branch
// and levels off at the bed weight per unit area once the bed fluidises.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "settled_bed.hpp"

namespace fluidbed {
namespace {

using namespace coupling_test;


struct Level {
  double u = 0.0;          // superficial velocity, m/s
  double dp = 0.0;         // mean distributor-to-outlet pressure drop, Pa
  double fluid = 0.0;      // mean vertical fluid force on the particles, N
  double walls = 0.0;      // mean vertical force of the walls and distributor on the particles, N
  double dmom_dt = 0.0;    // change of the particles' vertical momentum over the window / window, N
};

TEST(MinimumFluidisation, PressureDropLevelsOffAtBedWeight) {
  ScopedOneThread one;
  const SettledBed& bed = settled_bed();
  const Species sp;
  GasConfig gas = bed_gas();
  const double g = -gas.gravity.y;
  const double u_ergun = ergun_minimum_fluidisation_velocity(bed.eps_interior, sp.diameter, sp.density, gas.rho_g,
                                                             gas.mu_g, g);
  // Four packed levels: the gas is quasi-steady and the bed static, so 0.06 s (300 steps) is steady. Then
  // fluidised levels held 2 s each, averaged over the last 1.8 s (the first 0.2 s is the bed's expansion): the
  // bed's momentum swings by about M x 0.1 m/s from slug to slug, so a window T leaves a term of order
  // 0.1 / (g T) of W in the mean (1.7% at T = 0.6 s, 0.6% at 1.8 s). The plateau is the mean of the levels
  // 1.1-1.3 U_Ergun; 1.6 U_Ergun, where this 25-particle-wide column slugs hard, is checked on its own.
  const std::vector<double> fraction{0.3, 0.6, 0.8, 0.95, 1.1, 1.2, 1.3, 1.6};
  const double hold_f = 2.0;  // s
  const auto in_plateau = [](double f) { return f > 1.0 && f < 1.5; };
  std::vector<double> hold, window;
  for (double f : fraction) {
    hold.push_back(f < 1.0 ? 0.06 : hold_f);
    window.push_back(f < 1.0 ? 0.03 : hold_f - 0.2);
  }
  std::vector<double> t_start;
  double t = 0.0;
  for (std::size_t k = 0; k < fraction.size(); ++k) {
    // The first level also covers initialize(), which solves the gas at t = 0 (still gas cannot converge).
    gas.boundary.jets.push_back(full_width_inflow(fraction[k] * u_ergun, k == 0 ? -1.0 : t, t + hold[k]));
    t_start.push_back(t);
    t += hold[k];
  }
  // Frictionless side walls, so that they cannot carry the bed's weight (a narrow monodisperse bed otherwise
  // arches between them). A lid at the top of the gas column: at 1.6 U_Ergun a slug bursting at the surface now and
  // then throws a particle that high (which slug does is chaotic, a matter of round-off); the lid's push, if any,
  // is part of the walls' force in the closure below.
  CfdDemSimulation<2> sim = bed_simulation(gas, 0.0, true);
  sim.initialize();
  const double area = kWidth * sp.diameter;
  const ParticleStore<2>& p = sim.dem().particles();
  const double weight = total_particle_weight(p, g);
  const double gas_weight = gas.rho_g * g * (area * kHeight - total_particle_volume(p));
  // The particles feel drag plus -V_p grad P, so the gas holds up their full weight (buoyancy is part of the
  // pressure force) plus its own: dP = (W + rho_g g V_gas) / A, i.e. the buoyant weight per area above the
  // hydrostatic pressure of the gas column.
  const double dp_weight = (weight + gas_weight) / area;
  const auto momentum = [&p] {
    double m = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) m += p.mass[i] * p.vy[i];
    return m;
  };
  std::vector<Level> levels;
  for (std::size_t k = 0; k < fraction.size(); ++k) {
    const double t_end = t_start[k] + hold[k];
    Level lv;
    lv.u = fraction[k] * u_ergun;
    int n = 0;
    double mom0 = 0.0, t0 = 0.0;
    while (sim.time() < t_end - 0.5 * sim.macro_dt()) {
      sim.advance();
      if (sim.time() > t_end - window[k]) {
        if (n == 0) {
          mom0 = momentum();
          t0 = sim.time();
        }
        lv.dp += distributor_pressure(sim.gas()) - gas.boundary.top_pressure;
        lv.fluid += sim.total_fluid_force().y;
        double walls = 0.0;  // pair forces cancel in the sum: what is left is the walls' and distributor's
        for (double f : p.fy) walls += f;
        lv.walls += walls;
        ++n;
      }
    }
    lv.dp /= n;
    lv.fluid /= n;
    lv.walls /= n;
    lv.dmom_dt = (momentum() - mom0) / (sim.time() - t0);
    levels.push_back(lv);
  }

  std::printf("[ U_mf     ] W/A + gas column = %.2f Pa; Ergun U_mf %.4f m/s at the bed's voidage %.4f\n", dp_weight,
              u_ergun, bed.eps_interior);
  std::printf("[ U_mf     ]  U [m/s]  U/U_Ergun   dP [Pa]  dP/(W/A)  fluid/W  walls/W  dMom/dt/W  closure\n");
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const Level& lv = levels[k];
    // closure: (dP A - gas weight) / (W - F_walls + dMom/dt), 1 when the gas carries what the particles need.
    std::printf("[ U_mf     ] %8.4f  %9.2f  %8.2f  %8.4f  %7.4f  %7.4f  %9.4f  %7.4f\n", lv.u, fraction[k], lv.dp,
                lv.dp / dp_weight, lv.fluid / weight, lv.walls / weight, lv.dmom_dt / weight,
                (lv.dp * area - gas_weight) / (weight - lv.walls + lv.dmom_dt));
  }

  // Packed branch: fit dP = a U + b U^2 (the Ergun form) through the packed levels, and find where it reaches
  // the fluidised plateau.
  double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0, plateau = 0;
  int n_fl = 0;
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const double u = levels[k].u, y = levels[k].dp - gas_weight / area;
    if (fraction[k] < 1.0) {
      s11 += u * u;
      s12 += u * u * u;
      s22 += u * u * u * u;
      r1 += u * y;
      r2 += u * u * y;
    } else if (in_plateau(fraction[k])) {
      plateau += levels[k].dp;
      ++n_fl;
    }
  }
  plateau /= n_fl;
  const double det = s11 * s22 - s12 * s12;
  const double a = (r1 * s22 - r2 * s12) / det, b = (s11 * r2 - s12 * r1) / det;
  const double y_pl = plateau - gas_weight / area;
  const double u_mf_sim = 2.0 * y_pl / (a + std::sqrt(a * a + 4.0 * b * y_pl));
  std::printf("[ U_mf     ] U_mf: Ergun %.4f m/s  simulated (packed-branch fit meets plateau) %.4f m/s  ratio %.4f\n",
              u_ergun, u_mf_sim, u_mf_sim / u_ergun);

  // Before fluidisation the gas carries a fraction of the bed that grows with U.
  for (std::size_t k = 1; k < levels.size(); ++k) {
    if (fraction[k] < 1.0) {
      EXPECT_GT(levels[k].dp, levels[k - 1].dp);
    }
  }
  EXPECT_LT(levels[3].dp, 0.9 * dp_weight);
  // Plateau (acceptance 3 of the gas issue): the pressure drop levels off at the bed's
  // weight per area within 3%. What the gas does not carry is measured and printed: the distributor's support
  // (particles resting on, and raining onto, the solid distributor between slugs: 1-2% of W) and the bed's
  // momentum change over the window (under 1% of W at 1.8 s). The same balance net of the distributor's
  // support is also asserted, to the momentum term's 1%.
  double plateau_walls = 0.0;
  for (std::size_t k = 0; k < levels.size(); ++k) {
    if (in_plateau(fraction[k])) plateau_walls += levels[k].walls;
  }
  plateau_walls /= n_fl;
  const double dp_carried = (weight - plateau_walls + gas_weight) / area;
  std::printf("[ U_mf     ] plateau (1.1-1.3 U_Ergun): W/A + gas column %.2f Pa  computed %.2f Pa  rel. error %.2e; "
              "net of the distributor's support %.2f Pa, rel. error %.2e\n", dp_weight, plateau,
              plateau / dp_weight - 1.0, dp_carried, plateau / dp_carried - 1.0);
  EXPECT_NEAR(plateau / dp_weight, 1.0, 0.03);
  EXPECT_NEAR(plateau / dp_carried, 1.0, 0.01);
  // Hard slugging at 1.6 U_Ergun: the distributor carries more (about 2% of W); the pressure drop stays within
  // 5% of the weight and the balance below still closes.
  EXPECT_NEAR(levels.back().dp / dp_weight, 1.0, 0.05);
  EXPECT_LT(plateau_walls, 0.05 * weight);  // the bed is fluidised: the distributor carries little of it
  // Momentum closure in the fluidised levels: the pressure drop carries what neither the walls nor the
  // particles' acceleration take, dP A - gas weight = W - F_walls + dMom/dt; same 2% as the packed bed of
  // the momentum-exchange test (interpolation in the cell rows the bed surface and bubbles cross).
  for (std::size_t k = 0; k < levels.size(); ++k) {
    if (fraction[k] < 1.0) continue;
    const Level& lv = levels[k];
    EXPECT_NEAR((lv.dp * area - gas_weight) / (weight - lv.walls + lv.dmom_dt), 1.0, 0.02) << "level " << k;
  }
  // Within 20% of Ergun: the simulated bed is a 2D monolayer whose voidage is not uniform (looser layers at the
  // walls and the distributor, hexagonal patches inside) and Ergun's 1/eps^3 weighs the loose paths most; the
  // gas short-cuts through the wall layers, so the bed fluidises at a somewhat different U than Ergun at the
  // mean interior voidage.
  EXPECT_NEAR(u_mf_sim / u_ergun, 1.0, 0.2);
}

}  // namespace
}  // namespace fluidbed
