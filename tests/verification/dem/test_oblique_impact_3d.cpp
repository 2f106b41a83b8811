// Oblique impacts of a sphere on a wall in 3D, without gravity, against impulse (Walton / Maw-Barber-Fawcett)
// theory for the paper's contact law (Eqs. 2-8), as the 2D test (test_oblique_impact.cpp) does, but with the
// plane of incidence (the normal and the tangential velocity) turned away from the axes: on the floor with the
// tangential velocity at 35 degrees between x and z, and on the right wall at 120 degrees between y and z. In
// gross sliding the tangential impulse is mu times the integral of |normal force| over the contact, and the spin
// takes 2.5 times that change at the contact point; otherwise the change is bounded by Coulomb and by a
// tangential restitution of at most one. Nothing leaves the plane of incidence (to round-off).
// Tolerance and stiffness as in 2D: at 200 steps per contact the normal impulse is within about 0.1% of the
// closed form; k = 8e7 N/m keeps the overlap below 5.3e-4 r so that the rigid-body lever arm r holds; 1%.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dem/dem_solver.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.004, kRho = 2700.0, kK = 8e7, kE = 0.9, kV = 1.0;
constexpr int kStepsPerContact = 200;
constexpr double kTol = 0.01;

struct Plane {
  const char* name;
  int wall;  // 2 axis + side
  Vec3 t;    // unit tangential direction of the incoming velocity
};

struct Outcome {
  double dvt, spin_t, out_of_plane;
};

Outcome impact(const Plane& pl, double mu, double theta, double dt) {
  const int axis = pl.wall / 2;
  const bool high = pl.wall % 2 == 1;
  const DemConfig c = test::one_species_config_3d(kD, kRho, kK, kE, mu, dt, {0.0, 0.0, 0.0}, {0.1, 0.1, 0.1},
                                                  test::closed_box());
  const double r = 0.5 * kD;
  Vec3 n{};  // outward: from the centre to the contact point
  n[axis] = high ? 1.0 : -1.0;
  const double vn = kV * std::cos(theta), vt = kV * std::sin(theta);
  Vec3 x{0.05, 0.05, 0.05};
  x[axis] = high ? 0.1 - r - 2.5 * vn * dt : r + 2.5 * vn * dt;
  ParticleStore<3> p;
  p.add(0, 0, c.species[0], x, vt * pl.t + vn * n);
  DemSolver<3> s(c, std::move(p));
  const ParticleStore<3>& q = s.particles();
  bool touched = false;
  for (int k = 0; k < 1000000; ++k) {
    const double gap = high ? 0.1 - q.coord(axis)[0] : q.coord(axis)[0];
    const bool in_contact = gap < r;
    touched = touched || in_contact;
    if (touched && !in_contact) break;
    s.step();
  }
  const Vec3 v = q.vel(0);
  const Vec3 spin_v = cross(q.spin(0), r * n);  // velocity of the contact point from the spin
  const Vec3 b = cross(n, pl.t);                // normal to the plane of incidence
  return {dot(v, pl.t) - vt, dot(spin_v, pl.t),
          std::max(std::abs(dot(v, b)), std::max(std::abs(dot(spin_v, b)), std::abs(dot(q.spin(0), n))))};
}

TEST(DemObliqueImpactIn3D, SlidingImpactsMatchImpulseTheoryInPlanesAwayFromTheAxes) {
  const test::ScopedThreads one_thread(1);
  const Species sp{kD, kRho};
  const double m = sp.mass();
  const double eta = damping_from_restitution(m, kK, kE);
  const double dt = contact_duration(m, kK, eta) / kStepsPerContact;
  const double a35 = 35.0 * std::numbers::pi / 180.0, a120 = 120.0 * std::numbers::pi / 180.0;
  const Plane planes[] = {{"floor", 2, {std::cos(a35), 0.0, std::sin(a35)}},
                          {"right", 1, {0.0, std::cos(a120), std::sin(a120)}}};
  for (const Plane& pl : planes) {
    for (double mu : {0.1, 0.3}) {
      test::Table t(fmt::format("Oblique impact on the {} wall, e = {}, mu = {}, |v| = 1 m/s, dt = t_contact / {}",
                                pl.name, kE, mu, kStepsPerContact),
                    {"theta deg", "regime", "dvt theory", "dvt comp.", "err", "w x rn theory", "w x rn comp.", "err",
                     "out of plane"});
      for (int deg = 5; deg <= 85; deg += 10) {
        const double theta = deg * std::numbers::pi / 180.0;
        const double vn = kV * std::cos(theta), vt = kV * std::sin(theta);
        const double J = test::abs_normal_impulse(test::DampedOscillator{m, kK, eta, 0.0, 0.0, vn});
        const double slip_loss = 3.5 * mu * J / m;
        const bool sliding = slip_loss <= vt;
        const double dvt_theory = -mu * J / m, spin_theory = -2.5 * mu * J / m;
        const Outcome o = impact(pl, mu, theta, dt);
        t.row({static_cast<double>(deg), sliding ? 1.0 : 0.0, dvt_theory, o.dvt, test::rel_err(o.dvt, dvt_theory),
               spin_theory, o.spin_t, test::rel_err(o.spin_t, spin_theory), o.out_of_plane / vt});
        EXPECT_LE(o.out_of_plane, 1e-12 * vt) << pl.name << " " << deg;
        const double delta_max = vn * std::sqrt(m / kK);
        EXPECT_LE(std::abs(o.spin_t - 2.5 * o.dvt), 2.5 * delta_max / (0.5 * kD) * mu * J / m + 1e-12 * vt) << deg;
        EXPECT_LE(std::abs(o.dvt), mu * J / m * (1.0 + kTol)) << pl.name << " " << deg;
        EXPECT_LE(std::abs(vt + o.dvt + o.spin_t), vt * (1.0 + kTol)) << pl.name << " " << deg;
        if (slip_loss < vt * (1.0 - 2.0 * kTol)) {
          EXPECT_LE(test::rel_err(o.dvt, dvt_theory), kTol) << pl.name << " sliding " << deg;
          EXPECT_LE(test::rel_err(o.spin_t, spin_theory), kTol) << pl.name << " sliding " << deg;
        } else if (2.0 * vt / 3.5 < mu * J / m * (1.0 - 2.0 * kTol)) {
          EXPECT_LT(std::abs(o.dvt), mu * J / m * (1.0 - kTol)) << pl.name << " sticking " << deg;
        }
      }
    }
  }
}

}  // namespace
}  // namespace fluidbed
