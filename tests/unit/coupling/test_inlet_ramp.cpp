// The start-up ramp of the background inflow (inlet.ramp_from, inlet.ramp_time): linear in time, then constant,
// with the jets still replacing it over their width.
#include <gtest/gtest.h>

#include "core/grid2.hpp"
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
  const Grid2 g = Grid2::uniform(0.1, 0.1, 10, 10);
  std::vector<double> u;
  inlet_superficial_profile(bc, g, 0.25, u);
  double flux = 0.0;
  for (double x : u) flux += x * g.dx;
  // Background 2.7 m/s over 0.08 m, the jet 30 m/s over 0.02 m.
  EXPECT_NEAR(flux, 2.7 * 0.08 + 30.0 * 0.02, 1e-14);
  EXPECT_NEAR(u[0], 2.7, 1e-15);
  EXPECT_NEAR(u[4], 30.0, 1e-14);
}

}  // namespace
}  // namespace fluidbed
