// The coupled gas solution does not depend on the pressure backend beyond the solver tolerances: the settled bed
// of settled_bed.hpp with a jet, solved with Eigen's Cholesky and with hypre's PFMG-CG (gas.pressure_solver), for
// 20 gas steps. Both inner solves go to a relative residual of 1e-12, and SIMPLE stops at the normalised mass
// residual 1e-8, so the two SIMPLE answers may differ by what that residual leaves: a relative pressure
// difference of order 1e-8 per step, here allowed 1e-6 after 20 steps (the DEM sees the small force difference
// only over 40 sub-steps, far too few for the contact chaos to amplify it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "numerics/structured_solver_hypre.hpp"
#include "settled_bed.hpp"

namespace fluidbed {
namespace {

using namespace coupling_test;

TEST(PressureBackends, HypreGivesEigensCoupledBed) {
  if (!hypre_available()) GTEST_SKIP() << "built without hypre";
  ScopedOneThread one;
  GasConfig gas = bed_gas();
  gas.boundary.inlet_velocity = 1.0;
  gas.boundary.jets.push_back(InletJet{0.5 * kWidth, 0.02, 15.0, 0.0, 1.0});
  GasConfig gas_h = gas;
  gas_h.pressure_solver = PressureBackend::HyprePfmg;
  CfdDemSimulation<2> a = bed_simulation(gas), b = bed_simulation(gas_h);
  a.initialize();
  b.initialize();
  double max_dp = 0.0, max_p = 0.0, max_du = 0.0, max_u = 0.0;
  for (int step = 0; step < 20; ++step) {
    a.advance();
    b.advance();
    const auto& pa = a.gas().fields().p.data();
    const auto& pb = b.gas().fields().p.data();
    for (std::size_t k = 0; k < pa.size(); ++k) {
      max_dp = std::max(max_dp, std::abs(pa[k] - pb[k]));
      max_p = std::max(max_p, std::abs(pa[k]));
    }
    for (int ax = 0; ax < 2; ++ax) {
      const auto& ua = a.gas().fields().u[ax].data();
      const auto& ub = b.gas().fields().u[ax].data();
      for (std::size_t k = 0; k < ua.size(); ++k) {
        max_du = std::max(max_du, std::abs(ua[k] - ub[k]));
        max_u = std::max(max_u, std::abs(ua[k]));
      }
    }
  }
  const double drop_a = a.gas().pressure_drop(), drop_b = b.gas().pressure_drop();
  std::printf("[ backends ] 20 gas steps: pressure drop eigen %.10g Pa, hypre %.10g Pa; max |dp| / max |p| %.3g, "
              "max |du| / max |u| %.3g (allowed 1e-6)\n", drop_a, drop_b, max_dp / max_p, max_du / max_u);
  EXPECT_LT(max_dp / max_p, 1e-6);
  EXPECT_LT(max_du / max_u, 1e-6);
  EXPECT_GT(max_p, 0.0);
}

}  // namespace
}  // namespace fluidbed
