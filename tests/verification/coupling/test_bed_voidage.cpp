// Voidage of the settled bed: a random settled 2D monolayer of spheres counted over a depth of one diameter.
#include <gtest/gtest.h>

#include <cstdio>

#include "settled_bed.hpp"

namespace fluidbed {
namespace {

using namespace coupling_test;

TEST(SettledBedVoidage, MonolayerInteriorNearPaperMinimumFluidisationVoidage) {
  const SettledBed& bed = settled_bed();
  // Discs of diameter d covering an area fraction phi_2D, seen as spheres in a slab of depth d, fill
  // (pi d^3 / 6) / (pi d^2 / 4 * d) = 2/3 of it: eps = 1 - (2/3) phi_2D. Random settled disc packings have
  // phi_2D = 0.80-0.84 (eps 0.44-0.47); the densest (hexagonal, 0.907) gives 0.395 and a loose frictional
  // packing (0.78) 0.48, hence the bounds. The paper's eps_mf is about 0.43.
  const double paper_eps_mf = 0.43;
  const double phi_2d = 1.5 * (1.0 - bed.eps_interior);
  std::printf("[ voidage  ] interior voidage %.4f (paper eps_mf %.2f, difference %+.4f), disc area fraction %.4f\n",
              bed.eps_interior, paper_eps_mf, bed.eps_interior - paper_eps_mf, phi_2d);
  EXPECT_GT(bed.eps_interior, 0.38);
  EXPECT_LT(bed.eps_interior, 0.48);
  // The whole bed as a check of the interior average: particle volume over the bed's slab volume.
  const double eps_bulk = 1.0 - total_particle_volume(bed.particles) / (kWidth * bed.bed_height * Species{}.diameter);
  std::printf("[ voidage  ] whole-bed voidage %.4f (bed height %.4f m from the tops of 10 columns)\n", eps_bulk,
              bed.bed_height);
  EXPECT_GT(eps_bulk, 0.38);
  EXPECT_LT(eps_bulk, 0.52);  // also counts the rough surface and the looser layers at the walls
}

}  // namespace
}  // namespace fluidbed
