// The tangential spring of a contact (Cundall-Strack history of Eq. 3) survives neighbour-list rebuilds and
// re-sorting: a run that rebuilds every step matches a run that never rebuilds.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstring>

#include "dem/dem_solver.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.004, kRho = 2700.0, kK = 800.0, kMu = 0.5, kG = 9.81, kV = 0.5;

/// Sphere B rests on sphere A, which rests on the floor; both roll to the right at kV, and B's spin is off
/// by s0 / r from rolling on A, so the A-B tangential spring rings while sticking (its force stays below
/// mu m g) for the whole run.
DemSolver<2> stacked_pair(double skin) {
  DemConfig c = test::one_species_config(kD, kRho, kK, 0.9, kMu, 1e-5, {0.0, -kG}, 0.2, 0.1,
                                         WallConfig{false, false, true, false});
  c.skin = skin;
  const Species& sp = c.species[0];
  const double r = sp.radius(), m = sp.mass(), s0 = 1e-3;
  const double ya = r - 2.0 * m * kG / kK;  // static overlaps: A carries both weights
  const double yb = ya + 2.0 * r - m * kG / kK;
  ParticleStore<2> p;
  p.add(0, 0, sp, {0.05, ya}, {kV, 0.0}, -kV / r);
  p.add(1, 0, sp, {0.05, yb}, {kV, 0.0}, kV / r - s0 / r);
  return DemSolver<2>(c, std::move(p));
}

std::size_t slot_of(const ParticleStore<2>& p, std::int64_t id) {
  return static_cast<std::size_t>(std::find(p.id.begin(), p.id.end(), id) - p.id.begin());
}

/// Largest difference between the two runs over positions, velocities, spins, forces and torques, relative
/// to the size of each quantity.
double max_rel_diff(const ParticleStore<2>& a, const ParticleStore<2>& b) {
  double worst = 0.0;
  for (std::int64_t id = 0; id < static_cast<std::int64_t>(a.size()); ++id) {
    const std::size_t i = slot_of(a, id), j = slot_of(b, id);
    const std::pair<double, double> q[] = {{a.x[i], b.x[j]},   {a.y[i], b.y[j]},         {a.vx[i], b.vx[j]},
                                           {a.vy[i], b.vy[j]}, {a.omega[i], b.omega[j]}, {a.fx[i], b.fx[j]},
                                           {a.fy[i], b.fy[j]}, {a.torque[i], b.torque[j]}};
    for (auto [u, v] : q) {
      const double scale = std::max(std::abs(u), std::abs(v));
      if (scale > 0.0) worst = std::max(worst, std::abs(u - v) / scale);
    }
  }
  return worst;
}

TEST(DemHistory, TangentialSpringSurvivesNeighbourListRebuilds) {
  const test::ScopedThreads one_thread(1);
  DemSolver<2> small = stacked_pair(1e-5);  // rebuilt whenever a particle moved 5 um, i.e. every step
  DemSolver<2> large = stacked_pair(0.1);   // never rebuilt after the first step over the 15 mm travelled
  const int steps = 3000;
  double worst = 0.0;
  int identical = 0, sticking = 0;
  for (int n = 0; n < steps; ++n) {
    small.step();
    large.step();
    const double diff = max_rel_diff(small.particles(), large.particles());
    worst = std::max(worst, diff);
    if (diff == 0.0) ++identical;

    // Mirror entries: both partners hold the same spring with opposite signs, bit for bit.
    const NeighborList<2>& nl = small.neighbors();
    ASSERT_EQ(nl.entries(), 2u);
    EXPECT_EQ(nl.history[0].x, -nl.history[1].x) << "step " << n;
    EXPECT_EQ(nl.history[0].y, -nl.history[1].y) << "step " << n;
    const double m = small.particles().mass[0];
    if (norm(nl.history[0]) > 0.0 && kK * norm(nl.history[0]) < kMu * m * kG) ++sticking;
  }
  test::Table t("Contact history across rebuilds: stacked rolling pair, 3000 steps",
                {"rebuilds S", "rebuilds L", "max rel diff", "identical st.", "sticking st."});
  t.row({static_cast<double>(small.rebuild_count()), static_cast<double>(large.rebuild_count()), worst,
         static_cast<double>(identical), static_cast<double>(sticking)});
  EXPECT_GE(small.rebuild_count(), static_cast<std::uint64_t>(steps / 2));
  EXPECT_EQ(large.rebuild_count(), 1u);
  // The spring must matter for the test to mean anything: it is loaded and below the Coulomb limit.
  EXPECT_GE(sticking, steps * 9 / 10);
  // One partner per particle, so both runs add the same terms in the same order: only round-off could
  // differ, and it does not arise; 1e-12 is the acceptance criterion.
  EXPECT_LE(worst, 1e-12);

  // Sensitivity: the same state with the springs dropped gives a clearly different tangential force.
  DemSolver<2>::State st = small.state();
  DemSolver<2>::State dropped = st;
  for (Vec2& xi : dropped.neighbors.history) xi = Vec2{};
  DemSolver<2> keep(small.config(), ParticleStore<2>{}), lose(small.config(), ParticleStore<2>{});
  keep.restore(std::move(st));
  lose.restore(std::move(dropped));
  keep.compute_forces();
  lose.compute_forces();
  const std::size_t b = slot_of(keep.particles(), 1);
  const double ft_keep = keep.particles().fx[b], ft_lose = lose.particles().fx[slot_of(lose.particles(), 1)];
  fmt::print("tangential force on the top sphere: with history {:.6g} N, history dropped {:.6g} N\n", ft_keep,
             ft_lose);
  EXPECT_GT(std::abs(ft_keep - ft_lose), 1e-3 * std::abs(ft_keep));
}

/// Two spheres collide obliquely (tangential slip a tenth of the approach speed, below mu: the spring sticks)
/// while flying together at 20 m/s along y, past a column of spheres at rest that pins the cell grid in space
/// (the grid starts at the lower-left particle; enough particles that the grid is not capped). Sphere B sits
/// up and to the left of A, one cell column to its left, so their order in the row-major cell sort flips
/// each time a row boundary passes between them: their storage slots swap while the spring is loaded.
DemSolver<2> flying_pair(double skin) {
  DemConfig c = test::one_species_config(kD, kRho, kK, 0.9, 0.3, 1e-6, {0.0, 0.0}, 1.0, 1.0,
                                         WallConfig{false, false, false, false});
  c.skin = skin;
  const Species& sp = c.species[0];
  const double r = sp.radius(), approach = 0.5, slip = 0.05;
  const Vec2 u{-std::sqrt(0.5), std::sqrt(0.5)}, t{-u.y, u.x}, common{0.0, 20.0};
  const Vec2 a{0.5, 0.3};
  ParticleStore<2> p;
  p.add(0, 0, sp, a, common + (0.5 * approach) * u + (0.5 * slip) * t);
  p.add(1, 0, sp, a + (2.0 * r + 3.0 * approach * c.dt) * u, common - (0.5 * approach) * u - (0.5 * slip) * t);
  for (int k = 0; k < 9; ++k) p.add(2 + k, 0, sp, {0.4815, 0.29 + 0.005 * k});
  return DemSolver<2>(c, std::move(p));
}

TEST(DemHistory, TangentialSpringSurvivesReorderingOfTheStore) {
  const test::ScopedThreads one_thread(1);
  DemSolver<2> small = flying_pair(1e-6);
  DemSolver<2> large = flying_pair(0.1);
  double worst = 0.0;
  int loaded = 0, swaps_loaded = 0;
  std::size_t slot_a = slot_of(small.particles(), 0);
  for (int n = 0; n < 1000; ++n) {
    small.step();
    large.step();
    worst = std::max(worst, max_rel_diff(small.particles(), large.particles()));
    const NeighborList<2>& nl = small.neighbors();
    bool spring = false;
    for (std::size_t k = 0; k < nl.entries(); ++k) spring = spring || norm2(nl.history[k]) > 0.0;
    if (spring) ++loaded;
    const std::size_t now = slot_of(small.particles(), 0);
    if (spring && now != slot_a) ++swaps_loaded;
    slot_a = now;
  }
  test::Table t("Contact history across re-sorting: oblique collision of a pair flying at 20 m/s, 1000 steps",
                {"rebuilds S", "rebuilds L", "loaded st.", "slot swaps", "max rel diff"});
  t.row({static_cast<double>(small.rebuild_count()), static_cast<double>(large.rebuild_count()),
         static_cast<double>(loaded), static_cast<double>(swaps_loaded), worst});
  EXPECT_EQ(large.rebuild_count(), 1u);
  EXPECT_GE(loaded, 500);        // the contact lasts about 750 steps
  EXPECT_GE(swaps_loaded, 1);    // the re-sorting path was exercised with a loaded spring
  EXPECT_LE(worst, 1e-12);       // acceptance criterion; one partner per particle, so in fact bit for bit
}

}  // namespace
}  // namespace fluidbed
