// Pure contact-law functions of paper Eqs. 2-8 against hand values and their invariants.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "dem/contact_law.hpp"

namespace fluidbed {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(DemContactLaw, DampingFromRestitutionHandValues) {
  // Eq. 8 with ln(1/e) = pi: eta = 2 sqrt(mk) pi / sqrt(2 pi^2) = sqrt(2 m k); m = 2, k = 8 gives 4 sqrt(2).
  EXPECT_NEAR(damping_from_restitution(2.0, 8.0, std::exp(-kPi)), 4.0 * std::sqrt(2.0), 1e-14);
  EXPECT_EQ(damping_from_restitution(2.0, 8.0, 1.0), 0.0);
  // The paper's particle on a wall (Table 1: d = 4 mm, 2700 kg/m^3, k = 800 N/m, e = 0.9), by hand:
  // m = 2700 pi 0.004^3 / 6 = 9.0478e-5 kg, ln(1/0.9) = 0.1053605, eta = 2 sqrt(m k) 0.1053605 / 3.1433
  // = 0.0180356 kg/s.
  const double m = 2700.0 * kPi * 0.004 * 0.004 * 0.004 / 6.0;
  const double l = std::log(1.0 / 0.9);
  EXPECT_NEAR(damping_from_restitution(m, 800.0, 0.9), 2.0 * std::sqrt(m * 800.0) * l / std::sqrt(kPi * kPi + l * l),
              1e-16);
  EXPECT_NEAR(damping_from_restitution(m, 800.0, 0.9), 0.0180356, 1e-7);
}

TEST(DemContactLaw, DampingAndDurationReproduceTheRestitution) {
  // The damped oscillator's speed ratio over one contact is exp(-gamma t_c), gamma = eta / 2m: Eq. 8 inverts it.
  for (double e : {0.1, 0.5, 0.7, 0.9, 0.99}) {
    const double m = 3.0e-4, k = 1234.0;
    const double eta = damping_from_restitution(m, k, e);
    const double tc = contact_duration(m, k, eta);
    EXPECT_NEAR(std::exp(-eta / (2.0 * m) * tc), e, 1e-14) << e;
  }
  EXPECT_NEAR(contact_duration(1.0, 4.0, 0.0), kPi / 2.0, 1e-15);
  EXPECT_NEAR(critical_time(1.0, 4.0 * kPi * kPi), 1.0, 1e-15);
  EXPECT_EQ(reduced_mass(2.0, 2.0), 1.0);
}

TEST(DemContactLaw, NormalForceIsSpringPlusDashpot) {
  ContactParams p{800.0, 800.0, 2.0, 2.0, 0.3};
  Vec2 xi{};
  // Eq. 2 at rest: k overlap = 0.8 N, pushing i away from the partner (along -n).
  ContactForce f = linear_spring_dashpot(p, {{1.0, 0.0}, 1e-3, {0.0, 0.0}}, 1e-4, xi);
  EXPECT_NEAR(f.f.x, -0.8, 1e-15);
  EXPECT_EQ(f.f.y, 0.0);
  // Approaching at 0.5 m/s: the dashpot adds eta v_n = 1 N against the approach.
  f = linear_spring_dashpot(p, {{1.0, 0.0}, 1e-3, {0.5, 0.0}}, 1e-4, xi);
  EXPECT_NEAR(f.f.x, -1.8, 1e-15);
  // Separating at 0.5 m/s with a small overlap: the dashpot tail pulls (no clamping, e at zero overlap).
  f = linear_spring_dashpot(p, {{1.0, 0.0}, 1e-4, {-0.5, 0.0}}, 1e-4, xi);
  EXPECT_NEAR(f.f.x, -0.08 + 1.0, 1e-15);
}

TEST(DemContactLaw, DashpotOfAContactStartingOrEndingInsideTheStep) {
  const double dt = 1e-4;
  // Deep in the contact (overlap >= |vn| dt) the dashpot sees the normal velocity itself.
  EXPECT_EQ(normal_dashpot_velocity(1e-4, 0.5, dt), 0.5);
  EXPECT_EQ(normal_dashpot_velocity(1e-4, -0.5, dt), -0.5);
  EXPECT_EQ(normal_dashpot_velocity(0.0, 0.0, dt), 0.0);
  // Touched 0.2e-4 / 0.5 = 0.4 dt ago: the missed 0.4 dt of dashpot is added to this step.
  EXPECT_NEAR(normal_dashpot_velocity(0.2e-4, 0.5, dt), 0.5 * 1.4, 1e-15);
  // Separates 0.4 dt into the step: the dashpot pulls for that fraction only.
  EXPECT_NEAR(normal_dashpot_velocity(0.2e-4, -0.5, dt), -0.5 * 0.4, 1e-15);
  // The same values from both partners (vn is the same for both), so the law stays antisymmetric.
  ContactParams p{800.0, 800.0, 2.0, 2.0, 0.3};
  Vec2 xi_a{}, xi_b{};
  const ContactForce a = linear_spring_dashpot(p, {{0.6, 0.8}, 0.2e-5, {-0.3, -0.4}}, dt, xi_a);
  const ContactForce b = linear_spring_dashpot(p, {{-0.6, -0.8}, 0.2e-5, {0.3, 0.4}}, dt, xi_b);
  EXPECT_EQ(a.f.x, -b.f.x);
  EXPECT_EQ(a.f.y, -b.f.y);
}

TEST(DemContactLaw, TangentialSpringBelowAndAtTheCoulombLimit) {
  const Vec2 n{0.0, 1.0};
  const double dt = 1e-3;
  {
    // Eq. 3 below the limit: xi = dt v_t = 1e-4 m, f_t = -k_t xi - eta_t v_t = -0.1 - 0.2 = -0.3 N.
    ContactParams p{800.0, 1000.0, 0.0, 2.0, 10.0};
    Vec2 xi{};
    const ContactForce f = linear_spring_dashpot(p, {n, 1e-3, {0.1, 0.0}}, dt, xi);
    EXPECT_NEAR(xi.x, 1e-4, 1e-18);
    EXPECT_NEAR(f.f_t.x, -0.3, 1e-15);
    EXPECT_EQ(f.f_t.y, 0.0);
    EXPECT_NEAR(f.f.y, -0.8, 1e-15);
  }
  {
    // Eqs. 6-7: mu |f_n| = 0.1 * 0.8 N caps the tangential force, against the slip; the spring is reset so
    // that spring plus dashpot give exactly the capped force.
    ContactParams p{800.0, 1000.0, 0.0, 2.0, 0.1};
    Vec2 xi{};
    const ContactForce f = linear_spring_dashpot(p, {n, 1e-3, {0.1, 0.0}}, dt, xi);
    EXPECT_NEAR(f.f_t.x, -0.08, 1e-15);
    EXPECT_EQ(f.f_t.y, 0.0);
    EXPECT_NEAR(-p.k_t * xi.x - p.eta_t * 0.1, f.f_t.x, 1e-15);
  }
  {
    // A spring stretched beyond the limit (no slip now) is cut back to mu |f_n| / k_t, keeping its direction.
    ContactParams p{800.0, 1000.0, 0.0, 0.0, 0.1};
    Vec2 xi{-5e-3, 0.0};
    const ContactForce f = linear_spring_dashpot(p, {n, 1e-3, {0.0, 0.0}}, dt, xi);
    EXPECT_NEAR(f.f_t.x, 0.08, 1e-15);
    EXPECT_NEAR(xi.x, -8e-5, 1e-18);
  }
}

TEST(DemContactLaw, SpringRotatedIntoTheTangentPlaneKeepsItsLength) {
  ContactParams p{800.0, 1000.0, 0.0, 0.0, 1e6};
  for (double a : {0.1, 0.7, 2.0, -1.3}) {
    const Vec2 n{std::cos(a), std::sin(a)};
    Vec2 xi{3e-5, 4e-5};  // length 5e-5, generally not tangent to n
    if (std::abs(cross(n, xi)) < 1e-12) continue;
    const double side = cross(n, xi) > 0.0 ? 1.0 : -1.0;
    linear_spring_dashpot(p, {n, 1e-3, {0.0, 0.0}}, 1e-3, xi);  // no slip: only the rotation acts
    EXPECT_NEAR(norm(xi), 5e-5, 1e-18) << a;
    EXPECT_NEAR(dot(xi, n), 0.0, 1e-19) << a;  // round-off: a few ulps of |xi| = 5e-5
    EXPECT_GT(side * cross(n, xi), 0.0) << a;  // rotated, not flipped
  }
  // A spring exactly along the normal has no tangential direction to go to: it is released.
  Vec2 xi{0.0, 2e-5};
  linear_spring_dashpot(p, {{0.0, 1.0}, 1e-3, {0.0, 0.0}}, 1e-3, xi);
  EXPECT_EQ(norm(xi), 0.0);
}

TEST(DemContactLaw, ExchangingThePartnersNegatesEverythingBitForBit) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int c = 0; c < 2000; ++c) {
    const double a = 3.2 * u(rng);
    const Vec2 n{std::cos(a), std::sin(a)};
    const ContactParams p{800.0, 800.0 * (1.0 + 0.5 * u(rng)), 0.02 * (1.0 + u(rng)), 0.02 * (1.0 + u(rng)),
                          0.3 * (1.0 + u(rng))};
    const double overlap = 1e-4 * (1.0 + u(rng));
    const Vec2 v{u(rng), u(rng)};
    Vec2 xi_i{1e-5 * u(rng), 1e-5 * u(rng)};
    Vec2 xi_j = -xi_i;
    const ContactForce fi = linear_spring_dashpot(p, {n, overlap, v}, 1e-4, xi_i);
    const ContactForce fj = linear_spring_dashpot(p, {-n, overlap, -v}, 1e-4, xi_j);
    ASSERT_EQ(fj.f.x, -fi.f.x) << c;
    ASSERT_EQ(fj.f.y, -fi.f.y) << c;
    ASSERT_EQ(fj.f_t.x, -fi.f_t.x) << c;
    ASSERT_EQ(fj.f_t.y, -fi.f_t.y) << c;
    ASSERT_EQ(xi_j.x, -xi_i.x) << c;
    ASSERT_EQ(xi_j.y, -xi_i.y) << c;
  }
}

}  // namespace
}  // namespace fluidbed
