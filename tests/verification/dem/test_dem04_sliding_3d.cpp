// MFIX DEM04 in 3D: a sphere resting on a wall is launched sliding without spin, in a direction of the wall's
// plane that is not along an axis. Coulomb friction (paper Eqs. 6-7) slows it and spins it up about the axis
// n x v until it rolls: sliding lasts 2 v0 / (7 mu g), then |v| = 5/7 v0 = |omega| r, with v along the launch
// direction and omega normal to both v and the wall. Run on the floor and on two side walls (left, back), with
// gravity pressing the sphere onto the wall in each case.
// Tolerance, as in 2D (test_dem04_sliding.cpp): during sliding the friction force is exactly mu m g, so the ramps
// are integrated exactly; the end of sliding is resolved to one step (dt / t_slide < 2e-4) and the tangential
// spring rings after sticking with an amplitude of 0.18% of 5/7 v0 at mu = 1. 1% bounds both with a factor of
// five. The launch direction is kept to round-off (a spring along the slip never turns it): a few roundings
// (1e-16) per step over up to 1e4 steps, below 1e-10 even when they add up.
#include <gtest/gtest.h>

#include <cmath>

#include "dem/dem_solver.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.001, kRho = 1e4, kG = 9.81, kV0 = 0.1, kK = 1e5, kTol = 0.01;

struct Case {
  const char* name;
  int wall;     // 2 axis + side
  Vec3 launch;  // unit, in the wall's plane
};

TEST(DemDem04In3D, SlidingSphereRollsOnTheFloorAndOnSideWallsWithTheSpinVector) {
  const test::ScopedThreads one_thread(1);
  test::Table t("DEM04 in 3D: d = 1 mm, 1e4 kg/m3, v0 = 0.1 m/s along a diagonal of the wall, k = 1e5 N/m",
                {"mu", "t_slide err", "v_roll err", "|w| r/v - 1", "slip/v", "v off dir", "w . n/|w|", "w . v/|w||v|"},
                8);
  const double c30 = std::cos(0.5236), s30 = std::sin(0.5236);
  const Case cases[] = {{"floor", 2, {c30, 0.0, s30}}, {"left", 0, {0.0, s30, c30}}, {"back", 4, {c30, -s30, 0.0}}};
  const Species sp{kD, kRho};
  const double m = sp.mass(), r = sp.radius();
  for (const Case& cs : cases) {
    const int axis = cs.wall / 2;
    for (double mu : {0.2, 0.6, 1.0}) {
      const double e = 0.9;
      const double dt = contact_duration(m, kK, damping_from_restitution(m, kK, e)) / 50.0;
      Vec3 g{};
      g[axis] = -kG;  // onto the low-side wall of that axis
      DemConfig c = test::one_species_config_3d(kD, kRho, kK, e, mu, dt, g, {0.05, 0.05, 0.05}, test::closed_box());
      c.skin = 1e-4;
      Vec3 x{0.01, 0.01, 0.01};
      x[axis] = r - m * kG / kK;  // at its static overlap: no bounce
      ParticleStore<3> p;
      p.add(0, 0, sp, x, kV0 * cs.launch);
      DemSolver<3> s(c, std::move(p));
      const ParticleStore<3>& q = s.particles();
      Vec3 n{};  // from the centre to the contact point
      n[axis] = -1.0;

      const double t_slide = 2.0 * kV0 / (7.0 * mu * kG);
      const double v_roll = 5.0 / 7.0 * kV0;
      auto slip = [&]() {  // contact-point velocity along the launch direction
        const double lever = r - std::max(0.0, r - q.coord(axis)[0]);
        return dot(q.vel(0) + cross(q.spin(0), lever * n), cs.launch);
      };
      double slip_prev = kV0, t_prev = 0.0, t_slide_sim = -1.0;
      while (s.time() < 1.3 * t_slide + 4000 * dt) {
        s.step();
        const double sl = slip();
        if (t_slide_sim < 0.0 && sl <= 0.0) t_slide_sim = t_prev + slip_prev / (slip_prev - sl) * (s.time() - t_prev);
        slip_prev = sl;
        t_prev = s.time();
      }
      const Vec3 v = q.vel(0), w = q.spin(0);
      Vec3 v_t = v;
      v_t[axis] = 0.0;  // the normal velocity rings at the static overlap
      const double speed = norm(v_t);
      const double roll = norm(w) * r / speed - 1.0;
      const double off_dir = norm(v_t - dot(v_t, cs.launch) * cs.launch) / speed;
      const double w_n = std::abs(dot(w, n)) / norm(w);
      const double w_v = std::abs(dot(w, v_t)) / (norm(w) * speed);
      const double slip_rel = std::abs(slip()) / speed;
      t.labelled_row(cs.name, {mu, test::rel_err(t_slide_sim, t_slide), test::rel_err(speed, v_roll), roll, slip_rel,
                               off_dir, w_n, w_v});
      EXPECT_LE(test::rel_err(t_slide_sim, t_slide), kTol) << cs.name << " mu " << mu;
      EXPECT_LE(test::rel_err(speed, v_roll), kTol) << cs.name << " mu " << mu;
      EXPECT_LE(std::abs(roll), kTol) << cs.name << " mu " << mu;
      EXPECT_LE(slip_rel, kTol) << cs.name << " mu " << mu;
      EXPECT_LE(off_dir, 1e-10) << cs.name << " mu " << mu;
      EXPECT_LE(w_n, 1e-12) << cs.name << " mu " << mu;
      EXPECT_LE(w_v, 1e-12) << cs.name << " mu " << mu;
    }
  }
}

}  // namespace
}  // namespace fluidbed
