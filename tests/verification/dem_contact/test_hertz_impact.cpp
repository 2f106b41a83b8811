// Hertz normal impacts against Hertz theory (Johnson 1985, sec. 11.4): delta_max = (15 m* v^2 / (16 E*
// sqrt(R*)))^(2/5), t_c = 2.9432 delta_max / v, for two spheres closing head-on and a sphere on the floor, in 3D
// and 2D, at 0.1, 1 and 5 m/s, elastic (e = 1). Then the Tsuji damping (Tsuji, Tanaka & Ishida 1992): its
// restitution does not depend on the impact speed (the dimensionless impact equation has no speed in it), so the
// measured e must equal the input at every speed from 0.01 to 10 m/s.
// Tolerances: at dt = t_c / 1000 the symplectic Euler update (Eq. 10) errs by O(dt / t_c) in the energy, so the
// peak overlap and the rebound speed are within a few 1e-3 (0.5% and 0.005 allowed); the duration is found by
// interpolating the zero crossing inside the last step (its error O(dt / t_c) too, 0.5%).
#include <gtest/gtest.h>

#include "contact_cases.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.004, kRho = 2700.0;

template <int Dim>
void elastic_impacts(bool wall) {
  const Species sp{kD, kRho};
  const double m_eff = wall ? sp.mass() : 0.5 * sp.mass();
  const double r_eff = wall ? sp.radius() : 0.5 * sp.radius();
  const ElasticMaterial mat{};
  const double e_star = effective_youngs_modulus(mat, mat);
  test::Table t(fmt::format("Hertz elastic impact, {}D, {}: exact vs computed", Dim, wall ? "sphere on the floor" : "two spheres"),
                {"v m/s", "dmax exact", "dmax comp.", "err", "t_c exact", "t_c comp.", "err", "e comp."});
  for (double v : {0.1, 1.0, 5.0}) {
    const HertzImpact h = hertz_impact(m_eff, e_star, r_eff, v);
    DemConfig c = test::hertz_config(Dim, kD, kRho, 1.0, 0.3, h.duration / 1000.0, mat);
    const test::ImpactResult r = test::head_on<Dim>(c, v, wall);
    t.row({v, h.max_overlap, r.max_overlap, test::rel_err(r.max_overlap, h.max_overlap), h.duration, r.duration,
           test::rel_err(r.duration, h.duration), r.restitution});
    EXPECT_LE(test::rel_err(r.max_overlap, h.max_overlap), 0.005) << v;
    EXPECT_LE(test::rel_err(r.duration, h.duration), 0.005) << v;
    EXPECT_NEAR(r.restitution, 1.0, 0.005) << v;
  }
}

TEST(HertzImpact, ContactTimeAndMaxOverlapMatchHertzTheory) {
  const test::ScopedThreads one_thread(1);
  elastic_impacts<3>(false);
  elastic_impacts<3>(true);
  elastic_impacts<2>(false);
  elastic_impacts<2>(true);
}

TEST(HertzImpact, TsujiDampingRestitutionIsTheInputAtEverySpeed) {
  const test::ScopedThreads one_thread(1);
  const Species sp{kD, kRho};
  const ElasticMaterial mat{};
  const double e_star = effective_youngs_modulus(mat, mat);
  for (bool wall : {false, true}) {
    test::Table t(fmt::format("Tsuji damping, 3D, {}: restitution exact (input) vs computed",
                              wall ? "sphere on the floor" : "two spheres"),
                  {"e input", "v m/s", "e comp.", "error"});
    for (double e : {0.3, 0.6, 0.9}) {
      for (double v : {0.01, 0.1, 1.0, 10.0}) {
        const double m_eff = wall ? sp.mass() : 0.5 * sp.mass();
        const double r_eff = wall ? sp.radius() : 0.5 * sp.radius();
        const HertzImpact h = hertz_impact(m_eff, e_star, r_eff, v);
        const DemConfig c = test::hertz_config(3, kD, kRho, e, 0.3, h.duration / 1000.0, mat);
        const test::ImpactResult r = test::head_on<3>(c, v, wall);
        t.row({e, v, r.restitution, r.restitution - e});
        EXPECT_NEAR(r.restitution, e, 0.005) << "e " << e << " v " << v;
      }
    }
  }
}

TEST(HertzImpact, TsujiCoefficientInvertsTheRestitution) {
  // The once-integrated dimensionless impact (RK4, 3e4 steps) inverted by bisection: e(alpha(e)) = e.
  for (double e : {0.1, 0.5, 0.9, 0.99}) {
    const double a = tsuji_alpha_for_hertz(e);
    fmt::print("e = {}: alpha = {:.6f}, e(alpha) = {:.9f}\n", e, a, hertz_tsuji_restitution(a));
    EXPECT_NEAR(hertz_tsuji_restitution(a), e, 1e-8);
  }
  EXPECT_NEAR(hertz_tsuji_restitution(0.0), 1.0, 1e-6);  // undamped: elastic
}

}  // namespace
}  // namespace fluidbed
