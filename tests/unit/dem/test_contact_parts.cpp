// The composed contact-law parts (contact_law.hpp) against their formulas, and the antisymmetry the solver's
// mirrored pair evaluation relies on (exchanging the partners negates force, spring and rolling torque bit for
// bit).
#include <gtest/gtest.h>

#include <random>

#include "dem/contact_model.hpp"

namespace fluidbed {
namespace {

using HertzMindlinEpsd = ContactLaw<HertzNormal, TsujiDamping, MindlinTangential, EpsdRolling>;

ContactParams hertz_params() {
  ContactParams p;
  p.e_star = 3.7e10;
  p.g_star = 1.6e10;
  p.alpha = tsuji_alpha_for_hertz(0.8);
  p.mu = 0.4;
  p.mu_r = 0.1;
  p.eta_r = 0.3;
  return p;
}

TEST(DemContactParts, HertzAndMindlinFollowTheirFormulas) {
  const ContactParams p = hertz_params();
  const double r = 1e-3, d = 2e-6;
  const NormalSpring s = HertzNormal::spring(p, d, r);
  EXPECT_DOUBLE_EQ(s.force, 4.0 / 3.0 * p.e_star * std::sqrt(r) * std::pow(d, 1.5));  // Hertz 1882
  EXPECT_DOUBLE_EQ(s.stiffness, 2.0 * p.e_star * std::sqrt(r * d));                   // dF/d delta
  EXPECT_DOUBLE_EQ(MindlinTangential::stiffness(p, d, r), 8.0 * p.g_star * std::sqrt(r * d));
  EXPECT_NEAR(tsuji_alpha_for_linear(0.9) * std::sqrt(2.0 * 800.0), damping_from_restitution(2.0, 800.0, 0.9), 1e-12);
}

TEST(DemContactParts, EpsdSpringCapsAtTheRollingFrictionTorque) {
  const ContactParams p = hertz_params();
  ContactKinematics<3> c{{0.0, 1.0, 0.0}, 2e-6, {}, 1e-3, 1e-4, 1e-9};
  const ContactForce<3> cf{{}, {}, -0.5, 1e5};
  Vec3 m_k{};
  Vec3 t{};
  for (int k = 0; k < 2000; ++k) t = HertzMindlinEpsd::rolling_torque<3>(p, c, cf, Vec3{3.0, 0.0, 0.0}, 1e-4, m_k);
  // Ai et al. 2011 Eq. 14: at full mobilisation |M| = mu_r R* F_n, against the rolling, no dashpot.
  EXPECT_NEAR(t.x, -p.mu_r * c.r_eff * 0.5, 1e-15);
  EXPECT_EQ(t.y, 0.0);  // the twisting component (along n) is not resisted
  EXPECT_EQ(t.z, 0.0);
}

TEST(DemContactParts, ExchangingThePartnersNegatesEverythingBitForBit) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const ContactParams p = hertz_params();
  for (int k = 0; k < 2000; ++k) {
    Vec3 n{u(rng), u(rng), u(rng)};
    n = (1.0 / norm(n)) * n;
    const Vec3 v{u(rng), u(rng), u(rng)};
    const double overlap = 1e-6 * (1.5 + u(rng));
    ContactKinematics<3> ci{n, overlap, v, 1e-3, 1e-4, 1e-9};
    ContactKinematics<3> cj{-n, overlap, -v, 1e-3, 1e-4, 1e-9};
    Vec3 xi_i{1e-7 * u(rng), 1e-7 * u(rng), 1e-7 * u(rng)};
    Vec3 xi_j = -xi_i;
    const ContactForce<3> fi = HertzMindlinEpsd::force<3>(p, ci, 1e-6, xi_i);
    const ContactForce<3> fj = HertzMindlinEpsd::force<3>(p, cj, 1e-6, xi_j);
    EXPECT_TRUE(fi.f == -fj.f && xi_i == -xi_j) << k;
    const Vec3 w{u(rng), u(rng), u(rng)};
    Vec3 mi{1e-9 * u(rng), 1e-9 * u(rng), 1e-9 * u(rng)};
    Vec3 mj = -mi;
    const Vec3 ti = HertzMindlinEpsd::rolling_torque<3>(p, ci, fi, w, 1e-6, mi);
    const Vec3 tj = HertzMindlinEpsd::rolling_torque<3>(p, cj, fj, -w, 1e-6, mj);
    EXPECT_TRUE(ti == -tj && mi == -mj) << k;
  }
}

}  // namespace
}  // namespace fluidbed
