// Normal impacts without gravity: the restitution coefficient of the linear spring-dashpot (paper Eq. 8, e
// defined at zero overlap) against the prescribed e, on a wall and between two particles (momentum exact).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "dem/dem_solver.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

using test::Table;

constexpr double kPaperD = 0.004, kPaperRho = 2700.0, kPaperK = 800.0;  // paper Table 1

struct ImpactResult {
  double e_measured = 0.0;
  int contact_steps = 0;
};

/// A sphere hits the floor at speed v; `phase` in [0, 1) sets where between two steps the first touch falls.
ImpactResult wall_impact(double e, double dt, double v, double phase) {
  const DemConfig c = test::one_species_config(kPaperD, kPaperRho, kPaperK, e, 0.3, dt, {0.0, 0.0}, 0.1, 0.1,
                                               WallConfig{false, false, true, false});
  const double r = 0.5 * kPaperD;
  ParticleStore<2> p;
  p.add(0, 0, c.species[0], {0.05, r + (2.0 + phase) * v * dt}, {0.0, -v});
  DemSolver<2> s(c, std::move(p));
  ImpactResult res;
  bool touched = false;
  for (int n = 0; n < 100000; ++n) {
    const bool in_contact = s.particles().y[0] < r;
    if (in_contact) { touched = true; ++res.contact_steps; }
    if (touched && !in_contact) break;  // force evaluated at a separated position: flight is ballistic from here
    s.step();
  }
  res.e_measured = s.particles().vy[0] / v;
  return res;
}

/// Two equal spheres moving head-on along x (plus a common y velocity), far from any wall.
struct PairResult {
  double e_measured = 0.0;
  int contact_steps = 0;
  double max_momentum_drift = 0.0;  ///< max over steps of |P(t) - P(0)| / (|p1| + |p2|)
  double momentum_bound = 0.0;      ///< round-off bound for that drift
};

PairResult pair_impact(double e, double dt, double v1, double v2, double phase) {
  const DemConfig c = test::one_species_config(kPaperD, kPaperRho, kPaperK, e, 0.3, dt, {0.0, 0.0}, 1.0, 1.0,
                                               WallConfig{false, false, false, false});
  const double r = 0.5 * kPaperD;
  const double gap = (2.0 + phase) * (v1 - v2) * dt;
  ParticleStore<2> p;
  p.add(0, 0, c.species[0], {0.5 - r - 0.5 * gap, 0.5}, {v1, 0.3});
  p.add(1, 0, c.species[0], {0.5 + r + 0.5 * gap, 0.5}, {v2, 0.3});
  DemSolver<2> s(c, std::move(p));
  const ParticleStore<2>& q = s.particles();
  auto momentum = [&]() { return Vec2{q.mass[0] * q.vx[0] + q.mass[1] * q.vx[1], q.mass[0] * q.vy[0] + q.mass[1] * q.vy[1]}; };
  const Vec2 p0 = momentum();
  const double scale = q.mass[0] * (std::abs(v1) + std::abs(v2) + 0.6);
  PairResult res;
  bool touched = false;
  for (int n = 0; n < 100000; ++n) {
    const double dist = std::hypot(q.x[1] - q.x[0], q.y[1] - q.y[0]);
    const bool in_contact = dist < 2.0 * r;
    if (in_contact) { touched = true; ++res.contact_steps; }
    if (touched && !in_contact) break;
    s.step();
    res.max_momentum_drift = std::max(res.max_momentum_drift, norm(momentum() - p0) / scale);
  }
  // Both partners see bit-for-bit opposite forces, so only the rounding of v += dv (at most one unit in the
  // last place of |v| per particle and component per step, i.e. 2^-52 relative) moves the total momentum.
  res.momentum_bound = 2.0 * std::numeric_limits<double>::epsilon() * std::max(res.contact_steps, 1);
  const std::size_t a = q.id[0] == 0 ? 0 : 1, b = 1 - a;  // storage order changes at list rebuilds
  res.e_measured = (q.vx[b] - q.vx[a]) / (v1 - v2);
  return res;
}

double wall_contact_duration(double e) {
  const Species s{kPaperD, kPaperRho};
  return contact_duration(s.mass(), kPaperK, damping_from_restitution(s.mass(), kPaperK, e));
}

double pair_contact_duration(double e) {
  const Species s{kPaperD, kPaperRho};
  const double m_eff = reduced_mass(s.mass(), s.mass());
  return contact_duration(m_eff, kPaperK, damping_from_restitution(m_eff, kPaperK, e));
}

// Error model of Eq. 10 (first order) at N steps per contact, with the dashpot of the first and last contact
// steps weighted by the part of the step spent in contact (normal_dashpot_velocity, src/dem/contact_law.hpp).
// Two leading terms remain: (ii) the explicit dashpot decays by (1 - 2 gamma dt) per step instead of
// exp(-2 gamma dt): ln(1/e)^2 / N at most; (iii) the first and last contact steps fall at a random phase of
// the overlap, which the spring feels: (pi / N)^2 in energy. Without the end-step weighting a third term,
// 2 ln(1/e) / N (the last dashpot pull acting for a whole step), dominated and broke 1% at N = 50 for e < 0.8.
double restitution_error_bound(double e, int n) {
  const double l = std::log(1.0 / e), h = std::numbers::pi / n;
  return l * l / n + h * h;
}
// The acceptance criterion of issue 2: 1% at N = 50 and above, for every e.
constexpr double kAcceptTol = 0.01;



TEST(DemRestitution, WallImpactConvergesToEAtFirstOrder) {
  const test::ScopedThreads one_thread(1);
  Table t("Normal wall impact, no gravity, dt = t_contact / N (worst of 8 contact phases)",
          {"N", "e exact", "e computed", "rel error", "bound", "steps in c."});
  for (int n : {50, 100, 200}) {
    for (double e : {0.5, 0.7, 0.9, 1.0}) {
      const double dt = wall_contact_duration(e) / n;
      double worst = 0.0, worst_e = 0.0;
      int steps = 0;
      for (int ph = 0; ph < 8; ++ph) {
        const ImpactResult r = wall_impact(e, dt, 1.0, ph / 8.0);
        const double err = test::rel_err(r.e_measured, e);
        if (err >= worst) { worst = err; worst_e = r.e_measured; steps = r.contact_steps; }
        EXPECT_LE(err, restitution_error_bound(e, n)) << "e = " << e << " N " << n << " phase " << ph / 8.0;
        EXPECT_LE(err, kAcceptTol) << "e = " << e << " N " << n << " phase " << ph / 8.0;
      }
      t.row({static_cast<double>(n), e, worst_e, worst, restitution_error_bound(e, n), static_cast<double>(steps)});
    }
  }
}

TEST(DemRestitution, HeadOnPairConvergesToEAndConservesMomentum) {
  const test::ScopedThreads one_thread(1);
  Table t("Head-on collision of two equal spheres, dt = t_contact / N (worst of 8 contact phases)",
          {"N", "e exact", "e computed", "rel error", "bound", "dP/|p| max", "dP bound"});
  for (int n : {50, 100, 200}) {
    for (double e : {0.5, 0.7, 0.9, 1.0}) {
      const double dt = pair_contact_duration(e) / n;
      double worst = 0.0, worst_e = 0.0, drift = 0.0, bound = 0.0;
      for (int ph = 0; ph < 8; ++ph) {
        const PairResult r = pair_impact(e, dt, 0.8, -0.5, ph / 8.0);
        const double err = test::rel_err(r.e_measured, e);
        if (err >= worst) { worst = err; worst_e = r.e_measured; }
        drift = std::max(drift, r.max_momentum_drift);
        bound = std::max(bound, r.momentum_bound);
        EXPECT_LE(err, restitution_error_bound(e, n)) << "e = " << e << " N " << n << " phase " << ph / 8.0;
        EXPECT_LE(err, kAcceptTol) << "e = " << e << " N " << n << " phase " << ph / 8.0;
        EXPECT_LE(r.max_momentum_drift, r.momentum_bound) << "e = " << e << " phase " << ph / 8.0;
      }
      t.row({static_cast<double>(n), e, worst_e, worst, restitution_error_bound(e, n), drift, bound});
    }
  }
}

TEST(DemRestitution, ErrorAtThePapersTimeStep) {
  const test::ScopedThreads one_thread(1);
  // The paper's dt = 2e-4 s resolves a contact of its particles with only a few steps; the error is reported
  // (docs/verification-dem.md), and only what physics demands is asserted: a rebound, and no large gain.
  // The paper's case file steps the particles at 1e-4 s (docs/model.md), so that step is reported too.
  const double e = 0.9;
  Table t("Paper's particles (d = 4 mm, 2700 kg/m3, k = 800 N/m, e = 0.9), 16 contact phases",
          {"dt", "pair", "t_c / dt", "e min", "e max", "max rel err"});
  for (double dt : {2e-4, 1e-4})
  for (bool pair : {false, true}) {
    double e_min = 1e9, e_max = -1e9;
    for (int ph = 0; ph < 16; ++ph) {
      const double em = pair ? pair_impact(e, dt, 0.5, -0.5, ph / 16.0).e_measured
                             : wall_impact(e, dt, 1.0, ph / 16.0).e_measured;
      e_min = std::min(e_min, em);
      e_max = std::max(e_max, em);
      EXPECT_GT(em, 0.0);
      EXPECT_LE(em, 1.05);
    }
    const double tc = pair ? pair_contact_duration(e) : wall_contact_duration(e);
    t.row({dt, pair ? 1.0 : 0.0, tc / dt, e_min, e_max, std::max(std::abs(e_min - e), std::abs(e_max - e)) / e});
  }
}

}  // namespace
}  // namespace fluidbed
