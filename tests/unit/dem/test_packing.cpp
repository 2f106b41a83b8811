// Random non-overlapping placement (paper section 2.1.1) and the particle store's re-ordering.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "core/error.hpp"
#include "dem/packing.hpp"

namespace fluidbed {
namespace {

DemConfig two_species() {
  DemConfig c;
  c.species = {Species{0.004, 2700.0}, Species{0.0025, 2500.0}};
  c.pair.assign(4, InteractionParams{});
  c.wall.assign(2, InteractionParams{});
  return c;
}

PackingConfig region(std::int64_t count) {
  PackingConfig pc;
  pc.count = count;
  pc.x_min = -0.01;
  pc.x_max = 0.09;
  pc.y_min = 0.02;
  pc.y_max = 0.12;
  pc.min_gap = 0.0005;
  pc.seed = 17;
  pc.species_fraction = {0.3, 0.7};
  return pc;
}

double min_surface_gap(const ParticleStore<2>& p) {
  double g = 1e300;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      g = std::min(g, std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]) - p.radius[i] - p.radius[j]);
    }
  }
  return g;
}

TEST(DemPacking, PlacesWithoutOverlapInsideTheRegion) {
  const DemConfig c = two_species();
  const PackingConfig pc = region(400);  // every one of the 20 x 20 = 400 sites
  const ParticleStore<2> p = place_random<2>(c, pc);
  ASSERT_EQ(p.size(), 400u);
  EXPECT_GE(min_surface_gap(p), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_GE(p.x[i] - p.radius[i], pc.x_min) << i;
    EXPECT_LE(p.x[i] + p.radius[i], pc.x_max) << i;
    EXPECT_GE(p.y[i] - p.radius[i], pc.y_min) << i;
    EXPECT_LE(p.y[i] + p.radius[i], pc.y_max) << i;
    EXPECT_EQ(p.id[i], static_cast<std::int64_t>(i));
    EXPECT_EQ(p.vx[i], 0.0);
    EXPECT_EQ(p.mass[i], c.species[static_cast<std::size_t>(p.species[i])].mass());
  }
  // Species by fraction, in id order: 30% of 400 are species 0.
  EXPECT_EQ(std::count(p.species.begin(), p.species.end(), 0), 120);
  EXPECT_EQ(std::count(p.species.begin(), p.species.end(), 1), 280);
}

TEST(DemPacking, ReproducibleForASeedAndDifferentForAnother) {
  const DemConfig c = two_species();
  PackingConfig pc = region(300);
  const ParticleStore<2> a = place_random<2>(c, pc);
  const ParticleStore<2> b = place_random<2>(c, pc);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.species, b.species);
  pc.seed = 18;
  const ParticleStore<2> d = place_random<2>(c, pc);
  EXPECT_NE(a.x, d.x);
}

TEST(DemPacking, FillsEverySiteAndRejectsOneMore) {
  const DemConfig c = two_species();
  // 0.1 m / (0.004 + 0.0005) m = 22.2: 22 x 22 sites.
  const ParticleStore<2> full = place_random<2>(c, region(400));
  EXPECT_EQ(full.size(), 400u);
  EXPECT_GE(min_surface_gap(full), 0.0);
  try {
    place_random<2>(c, region(401));
    FAIL() << "401 particles should not fit in 400 sites";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_NE(std::string(e.what()).find("401"), std::string::npos) << e.what();
  }
}

// Neighbours in adjacent lattice sites keep at least the documented gap.
TEST(DemPacking, KeepsTheDocumentedMinimumGap) {
  DemConfig c;  // one species: every site is d + 2 min_gap wide
  PackingConfig pc = region(400);
  pc.species_fraction.clear();
  const ParticleStore<2> p = place_random<2>(c, pc);
  EXPECT_GE(min_surface_gap(p), pc.min_gap * (1.0 - 1e-12));
}

TEST(DemParticleStore, PermuteMovesEveryAttributeTogether) {
  ParticleStore<2> p;
  const Species s0{0.004, 2700.0}, s1{0.002, 1000.0};
  for (int i = 0; i < 6; ++i) {
    p.add(100 + i, i % 2, (i % 2) ? s1 : s0, {0.1 * i, 0.2 * i}, {1.0 + i, 2.0 + i}, 3.0 + i, 7 - i);
    p.fx[i] = 10.0 + i;
    p.fy[i] = 20.0 + i;
    p.torque[i] = 30.0 + i;
    p.fx_ext[i] = 40.0 + i;
    p.fy_ext[i] = 50.0 + i;
    p.drag_k[i] = 60.0 + i;
    p.ugx[i] = 70.0 + i;
    p.ugy[i] = 80.0 + i;
  }
  const ParticleStore<2> old = p;
  const std::vector<std::size_t> order{3, 0, 5, 1, 4, 2};
  p.permute(order);
  ASSERT_EQ(p.size(), 6u);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t o = order[k];
    EXPECT_EQ(p.id[k], old.id[o]);
    EXPECT_EQ(p.species[k], old.species[o]);
    EXPECT_EQ(p.layer[k], old.layer[o]);
    for (auto [a, b] : {std::pair{&p.x, &old.x}, std::pair{&p.y, &old.y}, std::pair{&p.vx, &old.vx},
                        std::pair{&p.vy, &old.vy}, std::pair{&p.omega, &old.omega}, std::pair{&p.radius, &old.radius},
                        std::pair{&p.mass, &old.mass}, std::pair{&p.inv_mass, &old.inv_mass},
                        std::pair{&p.inv_inertia, &old.inv_inertia}, std::pair{&p.fx, &old.fx},
                        std::pair{&p.fy, &old.fy}, std::pair{&p.torque, &old.torque},
                        std::pair{&p.fx_ext, &old.fx_ext}, std::pair{&p.fy_ext, &old.fy_ext},
                        std::pair{&p.drag_k, &old.drag_k}, std::pair{&p.ugx, &old.ugx}, std::pair{&p.ugy, &old.ugy}}) {
      EXPECT_EQ((*a)[k], (*b)[o]) << k;
    }
  }
  // The inverse permutation restores the original.
  std::vector<std::size_t> inverse(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) inverse[order[k]] = k;
  p.permute(inverse);
  EXPECT_EQ(p.id, old.id);
  EXPECT_EQ(p.x, old.x);
  EXPECT_EQ(p.inv_inertia, old.inv_inertia);
  EXPECT_EQ(p.fy_ext, old.fy_ext);
  p.clear();
  EXPECT_EQ(p.size(), 0u);
  EXPECT_TRUE(p.x.empty() && p.fx_ext.empty() && p.layer.empty() && p.ugy.empty());
}

TEST(DemParticleStore, SphereMassAndInertia) {
  const Species s{0.004, 2700.0};
  const double m = 2700.0 * std::numbers::pi * 0.004 * 0.004 * 0.004 / 6.0;  // sphere volume times density
  EXPECT_NEAR(s.mass(), m, 1e-15 * m);  // round-off of a different operation order
  EXPECT_NEAR(s.inertia(), 0.4 * m * 0.002 * 0.002, 1e-15 * 0.4 * m * 0.002 * 0.002);
}

}  // namespace
}  // namespace fluidbed
