// MFIX DEM01-like: a heavy sphere falls on the floor under gravity, bounces on the linear spring-dashpot of
// paper Eqs. 2 and 8, and flies up again. Each stage is compared with its closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dem/dem_solver.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.2, kRho = 2600.0, kY0 = 0.5, kG = 9.81;
// Eq. 10 is first order: at N steps per contact the overlap history carries a phase error of about
// omega dt / 2 = pi / (2N) of its amplitude, and the discrete first touch shifts the contact by at most one
// step (pi / N); N = 1000 puts both below 0.5%, so the 1% required by the acceptance criterion (taken
// relative to the natural scale of each stage) is at least twice the expected error.
constexpr int kStepsPerContact = 1000;
constexpr double kTol = 0.01;

struct Dem01Errors {
  double t_end_exact, t_end_err, v_r_exact, e_v_i, v_r_sim, v_r_err, apex_exact, apex_err;
  double fall_err, contact_err, flight_err;
};

Dem01Errors run_dem01(double k, double e) {
  const Species sp{kD, kRho};
  const double m = sp.mass(), r = sp.radius();
  const double eta = damping_from_restitution(m, k, e);
  const double dt = contact_duration(m, k, eta) / kStepsPerContact;
  DemConfig c = test::one_species_config(kD, kRho, k, e, 0.3, dt, {0.0, -kG}, 1.0, 1.0,
                                         WallConfig{false, false, true, false});
  c.skin = 0.01;

  // Closed form: free fall, damped oscillator under gravity from zero overlap, ballistic flight.
  const double h = kY0 - r;
  const double t_i = std::sqrt(2.0 * h / kG), v_i = kG * t_i;
  const test::DampedOscillator osc{m, k, eta, kG, 0.0, v_i};
  const double t_c = test::contact_end_time(osc);
  const double v_r = -osc.rate(t_c);
  const double apex = r + v_r * v_r / (2.0 * kG);
  double d_max = 0.0;
  for (int q = 0; q <= 2000; ++q) d_max = std::max(d_max, osc.overlap(t_c * q / 2000.0));
  auto y_exact = [&](double t) {
    if (t < t_i) return kY0 - 0.5 * kG * t * t;
    if (t < t_i + t_c) return r - osc.overlap(t - t_i);
    const double tau = t - t_i - t_c;
    return r + v_r * tau - 0.5 * kG * tau * tau;
  };

  ParticleStore<2> p;
  p.add(0, 0, sp, {0.5, kY0});
  DemSolver<2> s(c, std::move(p));
  const ParticleStore<2>& q = s.particles();
  Dem01Errors out{};
  out.t_end_exact = t_c;
  out.v_r_exact = v_r;
  out.e_v_i = e * v_i;
  out.apex_exact = apex;
  int stage = 0;  // 0 falling, 1 in contact, 2 rebounding
  double y_prev = q.y[0], t_prev = 0.0, t_end_sim = 0.0, y_top = 0.0;
  const double t_stop = t_i + t_c + v_r / kG + 0.05;
  while (s.time() < t_stop) {
    const double t = s.time(), y = q.y[0];
    if (stage == 0 && y < r) stage = 1;
    if (stage == 1 && y >= r) {
      stage = 2;
      t_end_sim = t_prev + (r - y_prev) / (y - y_prev) * (t - t_prev);
      // Velocity of the ballistic flight extrapolated back to the end of contact.
      out.v_r_sim = q.vy[0] + kG * (t - t_end_sim);
    }
    const double err = std::abs(y - y_exact(t));
    if (stage == 0) out.fall_err = std::max(out.fall_err, err / h);
    if (stage == 1) out.contact_err = std::max(out.contact_err, err / d_max);
    if (stage == 2) {
      out.flight_err = std::max(out.flight_err, err / (apex - r));
      y_top = std::max(y_top, y);
    }
    y_prev = y;
    t_prev = t;
    s.step();
  }
  out.t_end_err = test::rel_err(t_end_sim - t_i, t_c);
  out.v_r_err = test::rel_err(out.v_r_sim, v_r);
  out.apex_err = test::rel_err(y_top - r, apex - r);
  return out;
}

TEST(DemDem01, BouncingSphereFollowsTheClosedFormInAllThreeStages) {
  const test::ScopedThreads one_thread(1);
  test::Table t("DEM01: d = 0.2 m, 2600 kg/m3, dropped from y = 0.5 m, g = 9.81, dt = t_contact / 1000",
                {"k N/m", "e", "t_c exact", "t_c err", "v_r exact", "e*v_impact", "v_r computed", "v_r err",
                 "apex err", "fall err", "contact err", "flight err"});
  for (double k : {1e4, 3e4, 1e5}) {
    for (double e : {0.6, 0.8, 0.9, 1.0}) {
      // k = 1e4 N/m with e = 1 would compress the sphere by more than its radius (its centre below the floor).
      if (k < 2e4 && e > 0.95) continue;
      const Dem01Errors r = run_dem01(k, e);
      t.row({k, e, r.t_end_exact, r.t_end_err, r.v_r_exact, r.e_v_i, r.v_r_sim, r.v_r_err, r.apex_err, r.fall_err,
             r.contact_err, r.flight_err});
      EXPECT_LE(r.fall_err, kTol) << "k " << k << " e " << e;
      EXPECT_LE(r.contact_err, kTol) << "k " << k << " e " << e;
      EXPECT_LE(r.t_end_err, kTol) << "k " << k << " e " << e;
      EXPECT_LE(r.v_r_err, kTol) << "k " << k << " e " << e;
      EXPECT_LE(r.apex_err, kTol) << "k " << k << " e " << e;
      EXPECT_LE(r.flight_err, kTol) << "k " << k << " e " << e;
    }
  }
}

}  // namespace
}  // namespace fluidbed
