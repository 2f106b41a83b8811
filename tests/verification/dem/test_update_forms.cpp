// The update of Eq. 10 has two forms: the coupled one, which adds the fluid force and takes the drag implicitly,
// and the DEM-only one, which reads no fluid arrays (docs/performance.md section 31). With the fluid arrays at
// zero the coupled form adds exact zeros and relaxes by exactly 1, so the two must give the same bits: a settling,
// frictional bed (contacts starting, sliding and ending; walls) stepped both ways, compared bit for bit.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

#include "dem/dem_solver.hpp"
#include "dem/packing.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

template <int Dim>
void expect_same_bits(const ParticleStore<Dim>& a, const ParticleStore<Dim>& b) {
  ASSERT_EQ(a.size(), b.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (int c = 0; c < Dim; ++c) {
      differ += std::bit_cast<std::uint64_t>(a.coord(c)[i]) != std::bit_cast<std::uint64_t>(b.coord(c)[i]);
      differ += std::bit_cast<std::uint64_t>(a.velocity(c)[i]) != std::bit_cast<std::uint64_t>(b.velocity(c)[i]);
    }
    for (int c = 0; c < kSpinComponents<Dim>; ++c) {
      differ += std::bit_cast<std::uint64_t>(a.spin_component(c)[i]) !=
                std::bit_cast<std::uint64_t>(b.spin_component(c)[i]);
    }
  }
  EXPECT_EQ(differ, 0u) << "values that differ in some bit between the two update forms";
}

TEST(DemUpdateForms, DemOnlyUpdateGivesTheCoupledFormsBitsWithTheFluidAtZero) {
  const test::ScopedThreads two_threads(2);
  const Vec3 box{0.04, 0.08, 0.02};
  const Species sp{0.004, 2700.0};
  const double k = 800.0;
  const double dt = contact_duration(reduced_mass(sp.mass(), sp.mass()), k, 0.0) / 20.0;  // undamped: the shorter
  const DemConfig c = test::one_species_config_3d(sp.diameter, sp.density, k, 0.9, 0.3, dt, {0.0, -9.81, 0.0},
                                                  box, test::closed_box());
  const ParticleStore<3> p = place_random<3>(c, test::box_packing(box, 300, 3));
  DemSolver<3> dem_only(c, p);
  dem_only.couple_to_fluid(false);
  DemSolver<3> coupled(c, p);  // the default form
  std::uint64_t contact_steps = 0;
  for (int n = 0; n < 1500; ++n) {
    dem_only.step();
    coupled.step();
    if (dem_only.max_overlap() > 0.0) ++contact_steps;
  }
  EXPECT_GT(contact_steps, 1000u);  // the bed has landed and is in contact, not in free fall
  EXPECT_GT(dem_only.rebuild_count(), 2u);
  expect_same_bits(dem_only.particles(), coupled.particles());
}

}  // namespace
}  // namespace fluidbed
