// The paper's bed (Table 1, TFM column) with each of the three rheologies runs to 1.0 s with the solids mass
// conserved. The smallest voidage is printed beside the static compaction floor of docs/model-tfm.md: in the
// bubbling bed the wake compacts further than that floor (a known shortfall, see the docs), so it is reported
// here, not asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ctime>

#include "tfm/tfm_solver.hpp"

namespace fluidbed::tfm {
namespace {

// Static floor: P_s reaches twice the buoyant weight per area of all solids.
double voidage_floor(const TfmConfig& c) {
  const double load = (1.0 - c.eps_initial) * c.packed_height * (c.rho_s - c.rho_g) * std::abs(c.gravity.y);
  if (c.rheology == SolidsRheology::KineticTheory) {
    // Eqs. 21-22: (1 - eps) 1e24 (eps* - eps)^10 = 2 load, with 1 - eps taken at eps* (within 2% of the root).
    return c.eps_star - std::pow(2.0 * load / ((1.0 - c.eps_star) * 1e24), 0.1);
  }
  return modulus_voidage_for_pressure(c.modulus, 2.0 * load, c.eps_star);
}

void run_paper_case(SolidsRheology rheology) {
  TfmConfig c;
  c.rheology = rheology;
  TfmSolver solver(c);
  const double m0 = solver.solids_mass();
  double eps_min = 1.0;
  const std::clock_t c0 = std::clock();
  while (solver.time() < 1.0 - 1e-12) {
    solver.step(1.0);
    eps_min = std::min(eps_min, solver.min_voidage());
  }
  const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  std::printf("rheology %d: %ld steps, CPU %.1f s per simulated second, eps_min %.4f (static floor %.4f), "
              "mass drift %.1e\n",
              static_cast<int>(rheology), solver.state().steps, cpu, eps_min, voidage_floor(c),
              solver.solids_mass() / m0 - 1.0);
  EXPECT_NEAR(solver.time(), 1.0, 1e-12);
  // Conservative fluxes: only rounding (about steps * cells * 1e-16) can change the solids mass.
  EXPECT_NEAR(solver.solids_mass() / m0, 1.0, 1e-10);
  // U = 1.8 m/s is below the Ergun U_mf of the initial bed, so the bed must settle below eps*.
  EXPECT_LT(eps_min, c.eps_star);
}

TEST(TfmPaperCase, KineticTheoryRunsToOneSecond) { run_paper_case(SolidsRheology::KineticTheory); }
TEST(TfmPaperCase, ConstantViscosityRunsToOneSecond) { run_paper_case(SolidsRheology::ConstantViscosity); }
TEST(TfmPaperCase, InviscidRunsToOneSecond) { run_paper_case(SolidsRheology::Inviscid); }

}  // namespace
}  // namespace fluidbed::tfm
