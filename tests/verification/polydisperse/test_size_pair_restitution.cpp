// Eq. 8 on each pair's own reduced mass: a head-on impact of two particles of one species but different sizes
// (2 and 5 mm, masses 1 : 15.6) rebounds with the restitution asked for. The linear spring-dashpot's restitution
// is exact for eta of Eq. 8 on the pair's m_eff; the explicit step leaves an O(ln(1/e)^2 / N) error at N steps per
// contact (docs/verification-dem.md, test 2): N = 400 here, so |e_measured - e| < 1e-3. Damping taken from the
// species' nominal size instead (m_eff of two 3.5 mm particles) would give e = 0.54 for this pair.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "dem/dem_solver.hpp"

namespace fluidbed {
namespace {

TEST(SizePairRestitution, HeadOnImpactOfUnequalSizesRebounds) {
  DemConfig c;
  Species s{0.0035, 2700.0};
  s.size.law = SizeLaw::List;
  s.size.diameters = {0.002, 0.005};
  s.size.fractions = {0.5, 0.5};
  s.size.d_min = 0.002;
  s.size.d_max = 0.005;
  c.species = {s};
  const double e = 0.7;
  c.pair = {InteractionParams{e, 0.0}};
  c.wall = {InteractionParams{e, 0.0}};
  c.domain.width = c.domain.height = 0.1;
  c.domain.gravity = {0.0, 0.0, 0.0};
  const Species small = s.of_diameter(0.002), large = s.of_diameter(0.005);
  const double m_eff = reduced_mass(small.mass(), large.mass());
  const double t_c = contact_duration(m_eff, c.stiffness, damping_from_restitution(m_eff, c.stiffness, e));
  c.dt = t_c / 400.0;
  c.skin = 0.001;
  const double v0 = 0.5;
  ParticleStore<2> p;
  p.add(0, 0, small, {0.045, 0.05}, {v0, 0.0});
  p.add(1, 0, large, {0.045 + 0.0035 + 1e-4, 0.05}, {0.0, 0.0});
  DemSolver<2> dem(c, p);
  ASSERT_TRUE(dem.has_own_sizes());
  for (int k = 0; k < 20000; ++k) {
    dem.step();
    const auto& q = dem.particles();
    const double gap = std::abs(q.x[1] - q.x[0]) - q.radius[0] - q.radius[1];
    if (gap > 5e-4) break;  // separated and clear
  }
  const auto& q = dem.particles();
  const std::size_t a = q.id[0] == 0 ? 0 : 1, b = 1 - a;
  const double e_measured = (q.vx[b] - q.vx[a]) / v0;
  // The same pair damped with the species' nominal m_eff (two particles of 3.5 mm): its restitution, from the
  // damping ratio zeta = eta / (2 sqrt(m_eff k)), e = exp(-pi zeta / sqrt(1 - zeta^2)).
  const double eta_nominal = damping_from_restitution(0.5 * s.mass(), c.stiffness, e);
  const double zeta = eta_nominal / (2.0 * std::sqrt(m_eff * c.stiffness));
  const double e_nominal = std::exp(-std::numbers::pi * zeta / std::sqrt(1.0 - zeta * zeta));
  std::printf("[ restitution ] exact %.4f, measured %.5f, error %.2e; with the nominal size's damping %.4f\n", e,
              e_measured, e_measured - e, e_nominal);
  EXPECT_NEAR(e_measured, e, 1e-3);
  EXPECT_GT(std::abs(e_nominal - e), 1e-2);  // the test tells the two apart
  // Momentum is conserved by the pair forces.
  EXPECT_NEAR(q.mass[a] * q.vx[a] + q.mass[b] * q.vx[b], small.mass() * v0, 1e-12 * small.mass() * v0);
}

}  // namespace
}  // namespace fluidbed
