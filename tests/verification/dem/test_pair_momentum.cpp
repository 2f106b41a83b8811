// An isolated frictional pair (no gravity, no walls) conserves its linear momentum and its angular momentum,
// orbital plus spin, to round-off, in 2D and 3D, head-on and glancing, with spin. The friction torque acts
// with the lever arm to the contact point x_i + (r_i - delta / 2) n, the same point seen from both partners,
// so the torques cancel the moment of the contact forces exactly; Eq. 10 keeps this step by step, since
// x_{n+1} x v_{n+1} = x_n x v_{n+1} and the forces are evaluated at x_n. With the full radii as lever arms the
// pair would gain d(L) = delta (n x f_t) dt per step: with the paper's soft spring (k = 800 N/m, overlaps of
// 5% of d here) about delta / d times the spin impulse, some 1e-5 of the scale, far above the tolerance.
// Tolerance: each step adds a few roundings (1e-16 relative) of the largest terms, over a few hundred steps,
// some 1e-14; 1e-12 of the scale m |v| (|x| + d) + I |omega| bounds this with a margin of 100.
#include <gtest/gtest.h>

#include <cmath>

#include "dem/dem_solver.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.004, kRho = 2700.0, kK = 800.0, kE = 0.9, kMu = 0.3, kTol = 1e-12;

template <int Dim>
struct Totals {
  Vec<Dim> p{};
  Spin<Dim> l{};  // about the origin
};

template <int Dim>
Totals<Dim> totals(const ParticleStore<Dim>& q) {
  Totals<Dim> t;
  for (std::size_t i = 0; i < q.size(); ++i) {
    t.p += q.mass[i] * q.vel(i);
    t.l += q.mass[i] * cross(q.pos(i), q.vel(i)) + (1.0 / q.inv_inertia[i]) * q.spin(i);
  }
  return t;
}

double size_of(double v) { return std::abs(v); }
double size_of(Vec2 v) { return norm(v); }
double size_of(Vec3 v) { return norm(v); }

struct PairResult {
  double dp, dl, spin_change, max_overlap_frac;
};

/// Sphere 0 at c, sphere 1 at c + (d + gap) u, approaching along u with a tangential offset velocity, both
/// spinning; runs until the contact has ended.
template <int Dim>
PairResult run_pair(Vec<Dim> u, Vec<Dim> t, double approach, double slip, Spin<Dim> w0, Spin<Dim> w1) {
  const Species sp{kD, kRho};
  const double m_eff = reduced_mass(sp.mass(), sp.mass());
  const double dt = contact_duration(m_eff, kK, damping_from_restitution(m_eff, kK, kE)) / 50.0;
  DemConfig c = test::one_species_config_3d(kD, kRho, kK, kE, kMu, dt, {0.0, 0.0, 0.0}, {0.2, 0.2, 0.2},
                                            WallConfig{false, false, false, false, false, false, false});
  c.domain.dimension = Dim;
  c.skin = 1e-3;
  Vec<Dim> centre{};
  for (int a = 0; a < Dim; ++a) centre[a] = 0.1 + 0.01 * a;
  ParticleStore<Dim> p;
  p.add(0, 0, sp, centre, (0.5 * approach) * u + (0.5 * slip) * t, w0);
  p.add(1, 0, sp, centre + (kD + 2.0 * approach * dt) * u, (-0.5 * approach) * u - (0.5 * slip) * t, w1);
  DemSolver<Dim> s(c, std::move(p));
  const ParticleStore<Dim>& q = s.particles();
  const Totals<Dim> t0 = totals(q);
  const Spin<Dim> spin0 = (1.0 / q.inv_inertia[0]) * q.spin(0);
  const double r_scale = size_of(q.pos(0)) + kD;
  const double p_scale = sp.mass() * (approach + std::abs(slip));
  const double l_scale = p_scale * r_scale + (size_of(w0) + size_of(w1)) / q.inv_inertia[0];
  PairResult out{};
  bool touched = false;
  for (int n = 0; n < 100000; ++n) {
    s.step();
    const bool in_contact = s.max_overlap() > 0.0;
    out.max_overlap_frac = std::max(out.max_overlap_frac, s.max_overlap() / kD);
    touched = touched || in_contact;
    const Totals<Dim> tn = totals(q);
    out.dp = std::max(out.dp, size_of(tn.p - t0.p) / p_scale);
    out.dl = std::max(out.dl, size_of(tn.l - t0.l) / l_scale);
    if (touched && !in_contact) break;
  }
  EXPECT_TRUE(touched);
  std::size_t i0 = q.id[0] == 0 ? 0 : 1;
  out.spin_change = size_of((1.0 / q.inv_inertia[i0]) * q.spin(i0) - spin0) / l_scale;
  return out;
}

TEST(DemPairMomentum, IsolatedFrictionalPairConservesLinearAndAngularMomentumIn2DAnd3D) {
  const test::ScopedThreads one_thread(1);
  test::Table t("Isolated pair, k = 800 N/m, e = 0.9, mu = 0.3, dt = t_contact / 50: largest change over the "
                "collision, relative to the scale of each",
                {"dim", "impact", "|dP|", "|dL|", "spin impulse", "max ov / d"}, 0);
  auto check = [&](double dim, double kind, const PairResult& r) {
    t.row({dim, kind, r.dp, r.dl, r.spin_change, r.max_overlap_frac});
    EXPECT_LE(r.dp, kTol) << dim << " " << kind;
    EXPECT_LE(r.dl, kTol) << dim << " " << kind;
    // Friction must have acted for the test to mean anything: the spin impulse is far above the tolerance.
    EXPECT_GT(r.spin_change, 1e6 * kTol) << dim << " " << kind;
  };
  const double c = std::cos(0.7), s = std::sin(0.7);
  const Vec2 u2{c, s}, t2{-s, c};
  // kind 0: head-on (no tangential velocity; friction from the spins), kind 1: glancing (slip 0.8 of approach).
  check(2, 0, run_pair<2>(u2, t2, 1.0, 0.0, 300.0, -100.0));
  check(2, 1, run_pair<2>(u2, t2, 1.0, 0.8, 150.0, 400.0));
  const Vec3 u3 = (1.0 / std::sqrt(14.0)) * Vec3{1.0, 2.0, 3.0};
  const Vec3 t3 = (1.0 / std::sqrt(5.0)) * Vec3{2.0, -1.0, 0.0};  // normal to u3
  const Vec3 b3 = cross(u3, t3);
  check(3, 0, run_pair<3>(u3, t3, 1.0, 0.0, Vec3{300.0, -50.0, 120.0}, Vec3{-100.0, 200.0, 40.0}));
  check(3, 1, run_pair<3>(u3, (1.0 / std::sqrt(2.0)) * (t3 + b3), 1.0, 0.8, Vec3{10.0, 250.0, -80.0},
                          Vec3{0.0, 0.0, 400.0}));
}

}  // namespace
}  // namespace fluidbed
