// The start-up ramp of the background inflow (inlet.ramp_from, inlet.ramp_time): linear in time, then constant,
// with the jets still replacing it over their width.
#include <gtest/gtest.h>

#include "core/grid.hpp"
#include "fluid/gas_boundary.hpp"

namespace fluidbed {
namespace {

GasBoundaryConfig ramped() {
  GasBoundaryConfig bc;
  bc.inlet_velocity = 3.6;
  bc.ramp_from = 1.8;
  bc.ramp_time = 0.5;
  bc.jets.clear();
  return bc;
}

TEST(InletRamp, LinearFromStartVelocityThenConstant) {
  const GasBoundaryConfig bc = ramped();
  // u(t) = u0 + (u1 - u0) t / T for t < T, u1 after: exact in binary at these points up to one rounding.
  for (const double t : {0.0, 0.1, 0.25, 0.4, 0.49999}) {
    EXPECT_NEAR(background_inlet_velocity(bc, t), 1.8 + 1.8 * t / 0.5, 1e-15) << "t = " << t;
  }
  EXPECT_EQ(background_inlet_velocity(bc, 0.5), 3.6);
  EXPECT_EQ(background_inlet_velocity(bc, 2.0), 3.6);
  GasBoundaryConfig none = bc;
  none.ramp_time = 0.0;
  EXPECT_EQ(background_inlet_velocity(none, 0.0), 3.6);
}

TEST(InletRamp, FacesCarryTheRampAndJetsKeepTheirFlux) {
  GasBoundaryConfig bc = ramped();
  bc.jets.push_back(InletJet{0.05, 0.02, 30.0, 0.0, 1.0});
  const Grid<2> g = Grid<2>::uniform({0.1, 0.1}, {10, 10});
  std::vector<double> u;
  inlet_superficial_profile(bc, g, 0.25, u);
  double flux = 0.0;
  for (double x : u) flux += x * g.h[0];
  // Background 2.7 m/s over 0.08 m, the jet 30 m/s over 0.02 m.
  EXPECT_NEAR(flux, 2.7 * 0.08 + 30.0 * 0.02, 1e-14);
  EXPECT_NEAR(u[0], 2.7, 1e-15);
  EXPECT_NEAR(u[4], 30.0, 1e-14);
}

}  // namespace
}  // namespace fluidbed

namespace fluidbed {
namespace {

// A seeded distributor non-uniformity (inlet.noise): fixed factors within 1 -+ a, the total inflow unchanged,
// the jets untouched, and none at all with a = 0 (bit for bit the uniform profile).
TEST(InletNoise, FixedFactorsKeepTheTotalInflow) {
  GasBoundaryConfig bc;
  bc.inlet_velocity = 3.6;
  bc.jets.clear();
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {30, 50});
  std::vector<double> uniform, noisy, later;
  inlet_superficial_profile(bc, g, 0.1, uniform);
  for (int i = 0; i < g.n(0); ++i) {  // exactly the per-face value of the uniform distributor
    EXPECT_EQ(uniform[static_cast<std::size_t>(i)], inlet_superficial_velocity(bc, g.origin[0] + i * g.h[0], g.origin[0] + i * g.h[0] + g.h[0], 0.1));
  }
  bc.inlet_noise = 0.1;
  bc.noise_seed = 1998;
  inlet_superficial_profile(bc, g, 0.1, noisy);
  inlet_superficial_profile(bc, g, 1.7, later);
  double flux = 0.0, lo = 1e300, hi = 0.0;
  for (std::size_t i = 0; i < noisy.size(); ++i) {
    flux += noisy[i] * g.h[0];
    lo = std::min(lo, noisy[i]);
    hi = std::max(hi, noisy[i]);
    EXPECT_EQ(noisy[i], later[i]) << "the distributor does not change in time";
  }
  EXPECT_NEAR(flux, 3.6 * 0.6, 1e-13);
  // Within 1 -+ 0.1 of the mean (the renormalisation moves the bounds by at most the mean's deviation from 1).
  EXPECT_GT(lo, 3.6 * 0.88);
  EXPECT_LT(hi, 3.6 * 1.12);
  EXPECT_GT(hi - lo, 3.6 * 0.1) << "30 draws should span most of the range";
  bc.noise_seed = 1999;
  std::vector<double> other;
  inlet_superficial_profile(bc, g, 0.1, other);
  EXPECT_NE(other, noisy);
  // A jet keeps its velocity; only the background is perturbed.
  bc.jets.push_back(InletJet{0.31, 0.02, 30.0, 0.0, 1.0});
  inlet_superficial_profile(bc, g, 0.1, noisy);
  EXPECT_NEAR(noisy[15], 30.0, 1e-14);
}

}  // namespace
}  // namespace fluidbed
