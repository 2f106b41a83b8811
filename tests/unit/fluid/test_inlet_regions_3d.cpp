// Jets as regions of a 3D bed's bottom face (slot, rectangle, disc).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "fluid/gas_boundary.hpp"
#include "fluid/gas_solver.hpp"

namespace fluidbed {
namespace {

// Sum of jet_overlap_area over an n x n tiling of [0, 0.1]^2: the region's area inside the square.
double tiled_area(const InletJet& jet, int n) {
  const double h = 0.1 / n;
  double sum = 0.0;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i) sum += jet_overlap_area(jet, i * h, (i + 1) * h, k * h, (k + 1) * h);
  return sum;
}

TEST(InletRegions, OverlapAreasTileToTheRegionsArea) {
  // The overlaps are exact (closed forms), so any tiling sums to the area to round-off (a few ulps per face).
  InletJet disc{0.043, 0.05, 30.0, 0.0, 1.0};
  disc.shape = InletShape::Disc;
  disc.z_centre = 0.051;
  InletJet rect{0.04, 0.03, 30.0, 0.0, 1.0};
  rect.shape = InletShape::Rectangle;
  rect.z_centre = 0.06;
  rect.depth = 0.025;
  InletJet slot{0.05, 0.02, 30.0, 0.0, 1.0};
  const double disc_area = std::numbers::pi * 0.025 * 0.025;
  for (int n : {1, 7, 10, 33}) {
    EXPECT_NEAR(tiled_area(disc, n), disc_area, 1e-15) << n;
    EXPECT_NEAR(tiled_area(rect, n), 0.03 * 0.025, 1e-15) << n;
    EXPECT_NEAR(tiled_area(slot, n), 0.02 * 0.1, 1e-15) << n;
  }
  // A face wholly inside the disc, one wholly outside, one cut by it.
  EXPECT_NEAR(jet_overlap_area(disc, 0.04, 0.045, 0.05, 0.055), 0.005 * 0.005, 1e-18);
  EXPECT_EQ(jet_overlap_area(disc, 0.09, 0.1, 0.09, 0.1), 0.0);
  // The quarter disc about the centre: the face [xc, xc + r] x [zc, zc + r].
  EXPECT_NEAR(jet_overlap_area(disc, 0.043, 0.068, 0.051, 0.076), disc_area / 4.0, 1e-16);
}

TEST(InletRegions, ThreeDimensionalProfileCarriesTheJetsVolumeFlux) {
  GasBoundaryConfig bc;
  bc.inlet_velocity = 1.8;
  InletJet disc{0.1, 0.035, 30.0, 0.0, 1.0};
  disc.shape = InletShape::Disc;
  disc.z_centre = 0.05;
  bc.jets = {disc};
  bc.inlet_noise = 0.2;
  const Grid<3> g = Grid<3>::uniform({0.2, 0.4, 0.1}, {10, 20, 5});
  std::vector<double> u;
  inlet_superficial_profile(bc, g, 0.5, u);
  ASSERT_EQ(u.size(), 50u);
  double flux = 0.0;
  for (double x : u) flux += x * g.h[0] * g.h[2];
  const double jet = std::numbers::pi * 0.0175 * 0.0175;
  // The distributor factors scale only the background part of the cut faces; what they add there is taken back
  // over the uncovered parts (keep_background_flow), so the flux is exact with noise as without, to rounding.
  bc.inlet_noise = 0.0;
  inlet_superficial_profile(bc, g, 0.5, u);
  double exact_flux = 0.0;
  for (double x : u) exact_flux += x * g.h[0] * g.h[2];
  EXPECT_NEAR(exact_flux, 1.8 * (0.02 - jet) + 30.0 * jet, 1e-15);
  EXPECT_NEAR(flux, exact_flux, 1e-15);
}

TEST(InletRegions, TwoDimensionalSolverRefusesThreeDimensionalShapes) {
  GasConfig cfg;
  cfg.boundary.jets[0].shape = InletShape::Disc;
  EXPECT_THROW(GasSolver<2>(Grid<2>::uniform({0.1, 0.2}, {4, 8}), cfg), Error);
  cfg.boundary.jets[0].shape = InletShape::Rectangle;
  cfg.boundary.jets[0].depth = 0.0;
  EXPECT_THROW(GasSolver<3>(Grid<3>::uniform({0.6, 0.2, 0.1}, {6, 4, 2}), cfg), Error);
}

}  // namespace
}  // namespace fluidbed
