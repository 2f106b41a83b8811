// An outflow top removes the particles that cross it and counts them and their mass; the particles that stay
// go on exactly as if the others had never been there (their order, neighbour entries and springs survive).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "dem/dem_solver.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

// Two species (4 mm glass, 2 mm of a lighter solid) so that the mass lost is not just a count times one mass.
DemConfig outflow_config() {
  DemConfig c = test::one_species_config(0.004, 2700.0, 800.0, 0.9, 0.3, 2e-5, {0.0, -9.81}, 0.1, 0.1, WallConfig{});
  c.species = {Species{0.004, 2700.0}, Species{0.002, 1000.0}};
  c.pair.assign(4, InteractionParams{0.9, 0.3});
  c.wall.assign(2, InteractionParams{0.9, 0.3});
  c.walls.top_outflow = true;
  // A skin the heap never crosses: a re-sort (every 16th rebuild) orders the store by the cells of the moment,
  // and the escapers' speed would set when the rebuilds fall, so the two runs would end in different storage
  // orders and sum the same forces in another order (with a 1 mm skin: 180 rebuilds against 69). With this skin
  // neither run re-sorts after its start (2 and 1 rebuilds, the extra one after the removal carrying the heap's
  // springs by id), so the heap keeps one storage order and can be compared bit for bit.
  c.skin = 0.1;
  return c;
}

// Stayers: a heap in the left half, falling onto the floor and into contact (loaded springs). Escapers: thrown up
// at 3 m/s in the right half, far from the heap, so they reach y = 0.05 + 3^2 / (2 g) = 0.51 m > 0.1 m.
void add_stayers(ParticleStore<2>& p, const DemConfig& c) {
  std::int64_t id = 0;
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 8; ++i, ++id) {
      const int s = (i + j) % 2;
      p.add(2 * id, s, c.species[static_cast<std::size_t>(s)], {0.003 + 0.0052 * i + 0.0003 * j, 0.003 + 0.0045 * j});
    }
  }
}
double add_escapers(ParticleStore<2>& p, const DemConfig& c, std::size_t& count) {
  double mass = 0.0;
  std::int64_t id = 0;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 5; ++i, ++id) {
      const int s = (i * 3 + j) % 2;
      const Species& sp = c.species[static_cast<std::size_t>(s)];
      p.add(2 * id + 1, s, sp, {0.062 + 0.0065 * i, 0.04 + 0.0065 * j}, {0.0, 3.0});
      mass += sp.mass();
      ++count;
    }
  }
  return mass;
}

TEST(OutflowTop, RemovesAndCountsLeavingParticles) {
  const test::ScopedThreads one(1);
  const DemConfig c = outflow_config();
  ParticleStore<2> both, stay;
  add_stayers(both, c);
  add_stayers(stay, c);
  std::size_t n_escape = 0;
  const double m_escape = add_escapers(both, c, n_escape);
  double m_total = 0.0;
  for (double m : both.mass) m_total += m;

  DemSolver<2> with(c, both), without(c, stay);
  std::size_t removed_in_steps = 0;
  for (int n = 0; n < 5000; ++n) {  // 0.1 s
    removed_in_steps += with.step().removed;
    without.step();
  }
  double m_left = 0.0;
  for (double m : with.particles().mass) m_left += m;
  fmt::print("removed {} of {} escapers, mass lost {:.6e} kg (thrown up: {:.6e} kg); {} particles stay; "
             "list rebuilds {} with the escapers, {} without\n",
             with.removed_count(), n_escape, with.removed_mass(), m_escape, with.particles().size(),
             with.rebuild_count(), without.rebuild_count());
  EXPECT_EQ(with.removed_count(), n_escape);
  EXPECT_EQ(removed_in_steps, n_escape);
  // Mass lost equals the mass of the particles removed, and with the remaining mass makes up the total (the sums
  // differ only by the order of additions: a few ulps).
  EXPECT_NEAR(with.removed_mass(), m_escape, 1e-14 * m_escape);
  EXPECT_NEAR(with.removed_mass() + m_left, m_total, 1e-14 * m_total);

  // The heap did not notice: same particles, same order, same state bit for bit, springs included.
  const DemSolver<2>::State a = with.state(), b = without.state();
  ASSERT_EQ(a.particles.id, b.particles.id);
  EXPECT_EQ(a.particles.x, b.particles.x);
  EXPECT_EQ(a.particles.y, b.particles.y);
  EXPECT_EQ(a.particles.vx, b.particles.vx);
  EXPECT_EQ(a.particles.omega, b.particles.omega);
  std::size_t loaded = 0;
  for (const Vec2& xi : b.neighbors.history) loaded += norm2(xi) > 0.0 ? 1 : 0;
  EXPECT_GT(loaded, 0u) << "the heap should carry loaded tangential springs";
  EXPECT_EQ(a.neighbors.partner, b.neighbors.partner);
  ASSERT_EQ(a.neighbors.history.size(), b.neighbors.history.size());
  for (std::size_t k = 0; k < a.neighbors.history.size(); ++k) {
    EXPECT_EQ(a.neighbors.history[k].x, b.neighbors.history[k].x);
    EXPECT_EQ(a.neighbors.history[k].y, b.neighbors.history[k].y);
  }
}

TEST(OutflowTop, OpenTopFailsNamingTheChoices) {
  const test::ScopedThreads one(1);
  DemConfig c = outflow_config();
  c.walls.top_outflow = false;
  ParticleStore<2> p;
  std::size_t n = 0;
  add_escapers(p, c, n);
  DemSolver<2> s(c, p);
  try {
    for (int k = 0; k < 5000; ++k) s.step();
    FAIL() << "a particle crossed the open top without an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("domain.particle_top = \"outflow\""), std::string::npos) << what;
    EXPECT_NE(what.find("domain.particle_top = \"wall\""), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace fluidbed
