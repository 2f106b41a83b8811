// Particle outflow through a declared side and insertion at a given rate: the mass balance closes, exactly in
// counts (N(t) = N(0) + inserted - removed, integers) and to round-off in kg (three running sums of the same
// masses in different orders: a relative 1e-13 bounds N eps with N < 1000); the feed delivers floor(rate t)
// particles when its region has room; a restart from the state continues bit for bit (the feed's random stream
// is a counter, carried in the state).
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "dem/dem_solver.hpp"
#include "../dem/dem_closed_form.hpp"

namespace fluidbed {
namespace {

enum class Out { Bottom, Right };

DemConfig feed_config(Out side) {
  DemConfig c = test::one_species_config(0.004, 2700.0, 800.0, 0.9, 0.3, 1e-4, {0.0, -9.81}, 0.05, 0.2,
                                         WallConfig{true, true, true, true});
  c.skin = 4e-4;
  if (side == Out::Bottom) {
    c.walls.bottom = false;
    c.walls.side_outflow[2] = true;
  } else {
    c.walls.right = false;
    c.walls.side_outflow[1] = true;
    c.domain.gravity = {4.0, -9.81, 0.0};  // the bed slides out through the open right side
  }
  InsertionConfig& in = c.insertion;
  in.rate = 500.0;
  in.region_lo = {0.003, 0.15, 0.0};
  in.region_hi = {0.047, 0.19, 0.0};
  in.velocity = {0.0, -1.0, 0.0};
  in.seed = 42;
  return c;
}

double bed_mass(const ParticleStore<2>& p) {
  double m = 0.0;
  for (double x : p.mass) m += x;
  return m;
}

void run_balance(Out side, const char* name) {
  const test::ScopedThreads two(2);
  DemSolver<2> s(feed_config(side), ParticleStore<2>{});
  test::Table t(fmt::format("Feed of 500 particles/s, outflow through the {} side", name),
                {"t", "inserted", "removed", "in bed", "mass error", "floor(rate t)"});
  std::uint64_t worst_count = 0;
  double worst_mass = 0.0;
  bool short_feed = false;
  for (int n = 1; n <= 2500; ++n) {
    s.step();
    const auto due = static_cast<std::uint64_t>(std::floor(500.0 * s.time()));
    short_feed = short_feed || s.inserted_count() != due;
    const std::uint64_t bed = s.particles().size();
    const std::uint64_t balance = s.inserted_count() - s.removed_count();
    worst_count = std::max(worst_count, bed > balance ? bed - balance : balance - bed);
    const double err = std::abs(bed_mass(s.particles()) - (s.inserted_mass() - s.removed_mass()));
    worst_mass = std::max(worst_mass, err / std::max(s.inserted_mass(), 1e-300));
    if (n % 500 == 0) {
      t.row({s.time(), double(s.inserted_count()), double(s.removed_count()), double(bed), err, double(due)});
    }
  }
  fmt::print("largest count imbalance {}, largest relative mass imbalance {:.3g}\n", worst_count, worst_mass);
  EXPECT_FALSE(short_feed) << "the sparse feed region always has room: the feed must be on schedule";
  EXPECT_EQ(worst_count, 0u);
  EXPECT_LE(worst_mass, 1e-13);
  EXPECT_GT(s.removed_count(), 20u) << "particles should have left through the " << name;
  EXPECT_NEAR(s.inserted_mass(), double(s.inserted_count()) * s.config().species[0].mass(),
              1e-13 * s.inserted_mass());
  // Every particle that remains is inside the domain: the outflow side removed the others.
  for (std::size_t i = 0; i < s.particles().size(); ++i) {
    EXPECT_LE(s.particles().x[i], 0.05);
    EXPECT_GE(s.particles().y[i], 0.0);
  }
}

TEST(ParticleOutflow, MassBalanceClosesThroughTheBottom) { run_balance(Out::Bottom, "bottom"); }
TEST(ParticleOutflow, MassBalanceClosesThroughTheRightSide) { run_balance(Out::Right, "right"); }

TEST(ParticleInsertion, NewParticlesDoNotOverlap) {
  const test::ScopedThreads one(1);
  DemConfig c = feed_config(Out::Bottom);
  c.insertion.rate = 20000.0;  // two per step into a small box: the rejection test is exercised
  c.insertion.region_lo = {0.003, 0.17, 0.0};
  c.insertion.region_hi = {0.047, 0.19, 0.0};
  c.insertion.velocity = {0.0, -2.0, 0.0};
  DemSolver<2> s(c, ParticleStore<2>{});
  double worst = 0.0;
  for (int n = 0; n < 400; ++n) {
    const std::size_t before = s.particles().size();
    const DemStepInfo info = s.step();
    const ParticleStore<2>& p = s.particles();
    // The new ones are the last: none overlaps any particle at its placement.
    for (std::size_t i = before - info.removed; i < p.size(); ++i) {
      for (std::size_t j = 0; j < p.size(); ++j) {
        if (j == i) continue;
        const double ov = p.radius[i] + p.radius[j] - norm(p.pos(j) - p.pos(i));
        worst = std::max(worst, ov);
      }
    }
  }
  const auto due = static_cast<std::uint64_t>(std::floor(20000.0 * s.time()));
  fmt::print("{} particles inserted of {} due (the rest wait for room); largest overlap of a new particle at its "
             "placement {:.3g} m\n", s.inserted_count(), due, worst);
  EXPECT_GT(s.inserted_count(), 100u);
  EXPECT_LT(s.inserted_count(), due) << "the small region should have run out of room";
  EXPECT_LE(worst, 0.0);
}

TEST(ParticleInsertion, RestartContinuesBitForBit) {
  const test::ScopedThreads two(2);
  const DemConfig c = feed_config(Out::Bottom);
  DemSolver<2> whole(c, ParticleStore<2>{});
  for (int n = 0; n < 1000; ++n) whole.step();
  DemSolver<2> resumed(c, ParticleStore<2>{});
  resumed.restore(whole.state());
  for (int n = 0; n < 1000; ++n) {
    whole.step();
    resumed.step();
  }
  const auto a = whole.state(), b = resumed.state();
  EXPECT_EQ(a.particles.id, b.particles.id);
  EXPECT_EQ(a.particles.x, b.particles.x);
  EXPECT_EQ(a.particles.y, b.particles.y);
  EXPECT_EQ(a.particles.vx, b.particles.vx);
  EXPECT_EQ(a.particles.omega, b.particles.omega);
  EXPECT_EQ(a.feed.inserted, b.feed.inserted);
  EXPECT_EQ(a.feed.draws, b.feed.draws);
  EXPECT_EQ(a.removed_count, b.removed_count);
  fmt::print("after 0.2 s: {} inserted, {} removed, {} in the bed, identical after a restart at 0.1 s\n",
             a.feed.inserted, a.removed_count, a.particles.size());
}

}  // namespace
}  // namespace fluidbed
