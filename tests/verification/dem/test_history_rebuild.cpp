// The tangential spring of a contact (Cundall-Strack history of Eq. 3) survives neighbour-list rebuilds and
// re-sorting: a run that rebuilds every step matches a run that never rebuilds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "dem/dem_solver.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.004, kRho = 2700.0, kK = 800.0, kMu = 0.5, kG = 9.81, kV = 0.5;

/// Sphere B rests on sphere A, which rests on the floor; both roll to the right at kV, and B's spin is off
/// by s0 / r from rolling on A, so the A-B tangential spring rings while sticking (its force stays below
/// mu m g) for the whole run.
DemSolver stacked_pair(double skin) {
  DemConfig c = test::one_species_config(kD, kRho, kK, 0.9, kMu, 1e-5, {0.0, -kG}, 0.2, 0.1,
                                         WallConfig{false, false, true, false});
  c.skin = skin;
  const Species& sp = c.species[0];
  const double r = sp.radius(), m = sp.mass(), s0 = 1e-3;
  const double ya = r - 2.0 * m * kG / kK;  // static overlaps: A carries both weights
  const double yb = ya + 2.0 * r - m * kG / kK;
  ParticleStore p;
  p.add(0, 0, sp, {0.05, ya}, {kV, 0.0}, -kV / r);
  p.add(1, 0, sp, {0.05, yb}, {kV, 0.0}, kV / r - s0 / r);
  return DemSolver(c, std::move(p));
}

std::size_t slot_of(const ParticleStore& p, std::int64_t id) { return p.id[0] == id ? 0 : 1; }

/// Largest difference between the two runs over positions, velocities, spins, forces and torques, relative
/// to the size of each quantity.
double max_rel_diff(const ParticleStore& a, const ParticleStore& b) {
  double worst = 0.0;
  for (std::int64_t id : {0, 1}) {
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
  DemSolver small = stacked_pair(1e-5);  // rebuilt whenever a particle moved 5 um, i.e. every step
  DemSolver large = stacked_pair(0.1);   // never rebuilt after the first step over the 15 mm travelled
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
    const NeighborList& nl = small.neighbors();
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
  DemSolver::State st = small.state();
  DemSolver::State dropped = st;
  for (Vec2& xi : dropped.neighbors.history) xi = Vec2{};
  DemSolver keep(small.config(), ParticleStore{}), lose(small.config(), ParticleStore{});
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

}  // namespace
}  // namespace fluidbed
