// Beetstra et al.'s polydisperse correction through the CFD-DEM coupling: two particles of 4 mm and 2 mm, at rest
// in one cell of still gas (the paper's counting voidage, so each sees its own cell). The coupling deposits the
// Sauter mean <d> = sum d^3 / sum d^2 = 3.6 mm; in creeping flow each particle's drag coefficient must then be
// K_i = 3 pi mu d_i eps y_i F(phi, 0), y_i = d_i / <d> (docs/model.md). Tolerance 1e-6: the gas of a closed still
// box moves only by round-off (its Re, printed, is < 1e-9, and F's inertial part grows as Re^0.657).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "coupling/cfd_dem.hpp"
#include "closures/drag.hpp"

namespace fluidbed {
namespace {

TEST(DragLawsCfdDem, BeetstraSeesTheCellsSauterMean) {
  const Species big{0.004, 2700.0}, small{0.002, 2700.0};
  DemConfig dem;
  dem.species = {big, small};
  dem.pair.assign(4, InteractionParams{});
  dem.wall.assign(2, InteractionParams{});
  dem.domain.width = 0.02;
  dem.domain.height = 0.02;
  dem.dt = 1e-4;
  ParticleStore<2> p;
  p.add(0, 0, big, {0.004, 0.004});
  p.add(1, 1, small, {0.0085, 0.0025});
  GasConfig gas;
  gas.boundary.inlet_velocity = 0.0;
  gas.boundary.jets.clear();
  CouplingConfig cc;
  cc.voidage = VoidageMethod::Centre;
  cc.drag_law = DragLaw::Beetstra;
  CfdDemSimulation<2> sim(DemSolver<2>(dem, p), GasSolver<2>(Grid<2>::uniform({0.02, 0.02}, {2, 2}), gas), cc);
  sim.initialize();
  const ParticleStore<2>& q = sim.dem().particles();
  const double d_mean = (std::pow(0.004, 3) + std::pow(0.002, 3)) / (std::pow(0.004, 2) + std::pow(0.002, 2));
  // The cell's voidage as counted, with the monolayer depth of species 0.
  const double v_solid = std::numbers::pi / 6.0 * (std::pow(0.004, 3) + std::pow(0.002, 3));
  const double eps = 1.0 - v_solid / (0.01 * 0.01 * sim.depth());
  const double phi = 1.0 - eps;
  const double f = 10.0 * phi / (eps * eps) + eps * eps * (1.0 + 1.5 * std::sqrt(phi));  // Beetstra Eq. 13, Re = 0
  for (std::size_t i = 0; i < q.size(); ++i) {
    const double d = 2.0 * q.radius[i];
    const double exact = 3.0 * std::numbers::pi * gas.mu_g * d * eps * (d / d_mean) * f;
    const double slip = std::hypot(q.ugx[i] - q.vx[i], q.ugy[i] - q.vy[i]);
    std::printf("[ poly     ] d %.3f mm  <d> %.3f mm  eps %.5f  K exact %.10e kg/s  computed %.10e  error %.2e  "
                "Re %.1e\n", 1e3 * d, 1e3 * d_mean, eps, exact, q.drag_k[i], std::abs(q.drag_k[i] / exact - 1.0),
                eps * gas.rho_g * slip * d / gas.mu_g);
    EXPECT_NEAR(q.drag_k[i] / exact, 1.0, 1e-6);
  }
  EXPECT_NEAR(q.drag_k[0] / q.drag_k[1], 4.0, 4e-6);  // (d_1 / d_2)^2: y carries one more power of d
}

}  // namespace
}  // namespace fluidbed
