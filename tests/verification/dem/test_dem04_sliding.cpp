// MFIX DEM04-like: a sphere resting on the floor is launched sliding without spin. Coulomb friction (paper
// Eqs. 6-7) slows it and spins it up until it rolls: sliding lasts 2 v0 / (7 mu g), then v = 5/7 v0 = omega r.
#include <gtest/gtest.h>

#include <cmath>

#include "dem/dem_solver.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.001, kRho = 1e4, kG = 9.81, kV0 = 0.1;
// Stiff floor: static overlap m g / k = 5e-10 m, and after sticking the tangential spring (which holds mu m g
// at the moment of sticking) rings with a velocity amplitude mu g sqrt(3.5 m / k_t) = 0.18% of 5/7 v0 for
// mu = 1, damped within ~1e-4 s by the dashpot (e = 0.9).
constexpr double kK = 1e5;
// During sliding the friction force is exactly mu m g, so the scheme integrates the linear velocity ramps
// exactly; the remaining errors are the resolution of the end of sliding (one step, dt / t_slide < 2e-4)
// and the ringing of the tangential spring (< 0.2%). 1% bounds both with a factor of five.
constexpr double kTol = 0.01;

TEST(DemDem04, SlidingSphereRollsAfterTwoSeventhsOfItsSpeed) {
  const test::ScopedThreads one_thread(1);
  test::Table t("DEM04: d = 1 mm, 1e4 kg/m3, v0 = 0.1 m/s on the floor, k = 1e5 N/m, dt = t_contact / 50",
                {"mu", "t_slide ex.", "t_slide", "err", "v_roll ex.", "v_roll", "err", "omega r/v-1"});
  const Species sp{kD, kRho};
  const double m = sp.mass(), r = sp.radius();
  for (double mu : {0.2, 0.4, 0.6, 0.8, 1.0}) {
    const double e = 0.9;
    const double dt = contact_duration(m, kK, damping_from_restitution(m, kK, e)) / 50.0;
    DemConfig c = test::one_species_config(kD, kRho, kK, e, mu, dt, {0.0, -kG}, 0.05, 0.05,
                                           WallConfig{false, false, true, false});
    c.skin = 1e-4;
    ParticleStore<2> p;
    p.add(0, 0, sp, {0.01, r - m * kG / kK}, {kV0, 0.0});  // at its static overlap: no bounce
    DemSolver<2> s(c, std::move(p));
    const ParticleStore<2>& q = s.particles();

    const double t_slide = 2.0 * kV0 / (7.0 * mu * kG);
    const double v_roll = 5.0 / 7.0 * kV0;
    double slip_prev = kV0, t_prev = 0.0, t_slide_sim = -1.0;
    while (s.time() < 1.3 * t_slide + 4000 * dt) {
      s.step();
      const double slip = q.vx[0] + q.omega[0] * r;  // contact-point velocity, n = (0, -1)
      if (t_slide_sim < 0.0 && slip <= 0.0) {
        t_slide_sim = t_prev + slip_prev / (slip_prev - slip) * (s.time() - t_prev);
      }
      slip_prev = slip;
      t_prev = s.time();
    }
    const double v = q.vx[0];
    const double roll = -q.omega[0] * r / v - 1.0;
    t.row({mu, t_slide, t_slide_sim, test::rel_err(t_slide_sim, t_slide), v_roll, v, test::rel_err(v, v_roll), roll});
    EXPECT_LE(test::rel_err(t_slide_sim, t_slide), kTol) << "mu " << mu;
    EXPECT_LE(test::rel_err(v, v_roll), kTol) << "mu " << mu;
    EXPECT_LE(std::abs(roll), kTol) << "mu " << mu;
  }
}

}  // namespace
}  // namespace fluidbed
