// MFIX DEM01 in 3D: a heavy sphere falls under gravity onto a wall of a closed cubic box, bounces on the linear
// spring-dashpot of paper Eqs. 2 and 8, and flies back; each stage against its closed form, as the 2D test
// (test_dem01_bouncing.cpp) does. Gravity points in turn into each of the six walls, so every wall of the 3D
// solver (both sides of all three axes) is exercised; the closed form is that of the 2D test.
// Tolerance: as in 2D, Eq. 10 is first order and at N = 1000 steps per contact the phase error of the overlap
// history (pi / 2N) and the shift of the first touch (at most one step, pi / N) are below 0.5%; 1% is the
// acceptance criterion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dem/dem_solver.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.2, kRho = 2600.0, kDrop = 0.5, kG = 9.81, kBox = 1.0;
constexpr int kStepsPerContact = 1000;
constexpr double kTol = 0.01;

struct Errors {
  double fall, contact, t_end, v_r, apex, flight, transverse;
};

/// Gravity into wall `w` (2 axis + side); the sphere starts at the centre of the box, kDrop from that wall.
Errors run_dem01_3d(int w, double k, double e) {
  const int axis = w / 2;
  const bool high = w % 2 == 1;
  const Species sp{kD, kRho};
  const double m = sp.mass(), r = sp.radius();
  const double eta = damping_from_restitution(m, k, e);
  const double dt = contact_duration(m, k, eta) / kStepsPerContact;
  Vec3 g{};
  g[axis] = high ? kG : -kG;
  DemConfig c = test::one_species_config_3d(kD, kRho, k, e, 0.3, dt, g, {kBox, kBox, kBox}, test::closed_box());
  c.skin = 0.01;

  const double h = kDrop - r;
  const double t_i = std::sqrt(2.0 * h / kG), v_i = kG * t_i;
  const test::DampedOscillator osc{m, k, eta, kG, 0.0, v_i};
  const double t_c = test::contact_end_time(osc);
  const double v_r = -osc.rate(t_c);
  const double apex = r + v_r * v_r / (2.0 * kG);
  double d_max = 0.0;
  for (int q = 0; q <= 2000; ++q) d_max = std::max(d_max, osc.overlap(t_c * q / 2000.0));
  auto s_exact = [&](double t) {  // distance of the centre from the wall
    if (t < t_i) return kDrop - 0.5 * kG * t * t;
    if (t < t_i + t_c) return r - osc.overlap(t - t_i);
    const double tau = t - t_i - t_c;
    return r + v_r * tau - 0.5 * kG * tau * tau;
  };

  ParticleStore<3> p;
  p.add(0, 0, sp, {0.5 * kBox, 0.5 * kBox, 0.5 * kBox});
  DemSolver<3> s(c, std::move(p));
  const ParticleStore<3>& q = s.particles();
  auto dist = [&]() { return high ? kBox - q.coord(axis)[0] : q.coord(axis)[0]; };
  auto speed_off_wall = [&]() { return high ? -q.velocity(axis)[0] : q.velocity(axis)[0]; };
  Errors out{};
  int stage = 0;
  double s_prev = dist(), t_prev = 0.0, t_end_sim = 0.0, s_top = 0.0, v_r_sim = 0.0;
  const double t_stop = t_i + t_c + v_r / kG + 0.05;
  while (s.time() < t_stop) {
    const double t = s.time(), x = dist();
    if (stage == 0 && x < r) stage = 1;
    if (stage == 1 && x >= r) {
      stage = 2;
      t_end_sim = t_prev + (r - s_prev) / (x - s_prev) * (t - t_prev);
      v_r_sim = speed_off_wall() + kG * (t - t_end_sim);
    }
    const double err = std::abs(x - s_exact(t));
    if (stage == 0) out.fall = std::max(out.fall, err / h);
    if (stage == 1) out.contact = std::max(out.contact, err / d_max);
    if (stage == 2) {
      out.flight = std::max(out.flight, err / (apex - r));
      s_top = std::max(s_top, x);
    }
    // Head-on: the other coordinates and the spin stay exactly as they started.
    for (int a = 0; a < 3; ++a) {
      if (a != axis) out.transverse = std::max(out.transverse, std::abs(q.coord(a)[0] - 0.5 * kBox));
    }
    out.transverse = std::max(out.transverse, norm(q.spin(0)));
    s_prev = x;
    t_prev = t;
    s.step();
  }
  out.t_end = test::rel_err(t_end_sim - t_i, t_c);
  out.v_r = test::rel_err(v_r_sim, v_r);
  out.apex = test::rel_err(s_top - r, apex - r);
  return out;
}

TEST(DemDem01In3D, BouncingSphereFollowsTheClosedFormOnEveryWallOfABox) {
  const test::ScopedThreads one_thread(1);
  static constexpr const char* kWall[6] = {"left", "right", "bottom", "top", "back", "front"};
  test::Table t("DEM01 in 3D: d = 0.2 m, 2600 kg/m3, dropped 0.5 m towards each wall of a 1 m box, g = 9.81, "
                "dt = t_contact / 1000",
                {"k N/m", "e", "fall err", "contact err", "t_c err", "v_r err", "apex err", "flight err",
                 "transverse"},
                8);
  for (int w = 0; w < 6; ++w) {
    for (auto [k, e] : {std::pair{3e4, 0.6}, std::pair{1e5, 0.9}, std::pair{1e5, 1.0}}) {
      const Errors r = run_dem01_3d(w, k, e);
      t.labelled_row(kWall[w], {k, e, r.fall, r.contact, r.t_end, r.v_r, r.apex, r.flight, r.transverse});
      EXPECT_LE(r.fall, kTol) << kWall[w] << " k " << k << " e " << e;
      EXPECT_LE(r.contact, kTol) << kWall[w] << " k " << k << " e " << e;
      EXPECT_LE(r.t_end, kTol) << kWall[w] << " k " << k << " e " << e;
      EXPECT_LE(r.v_r, kTol) << kWall[w] << " k " << k << " e " << e;
      EXPECT_LE(r.apex, kTol) << kWall[w] << " k " << k << " e " << e;
      EXPECT_LE(r.flight, kTol) << kWall[w] << " k " << k << " e " << e;
      EXPECT_EQ(r.transverse, 0.0) << kWall[w];
    }
  }
}

}  // namespace
}  // namespace fluidbed
