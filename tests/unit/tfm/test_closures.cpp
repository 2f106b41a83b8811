// Unit tests of the TFM closures (paper Eqs. 20-26) and limiter functions against hand-computed values.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "numerics/tvd_limiter.hpp"
#include "numerics/tvd_lines.hpp"
#include "tfm/solids_stress.hpp"

namespace fluidbed::tfm {
namespace {

using tvd::Limiter;
double superbee(double r) { return tvd::SuperbeeLaw::psi(r); }
double minmod(double r) { return tvd::MinmodLaw::psi(r); }
double van_leer(double r) { return tvd::VanLeerLaw::psi(r); }
// 2D strain rate from its three components.
StrainRate<2> d2(double xx, double yy, double xy) {
  StrainRate<2> d;
  d(0, 0) = xx;
  d(1, 1) = yy;
  d(0, 1) = xy;
  return d;
}

constexpr double kPi = 3.14159265358979323846;

TEST(Limiters, TextbookValues) {
  // Sweby-diagram corners: superbee is the upper TVD bound, minmod the lower.
  EXPECT_DOUBLE_EQ(superbee(-1.0), 0.0);
  EXPECT_DOUBLE_EQ(superbee(0.25), 0.5);
  EXPECT_DOUBLE_EQ(superbee(0.75), 1.0);
  EXPECT_DOUBLE_EQ(superbee(1.5), 1.5);
  EXPECT_DOUBLE_EQ(superbee(3.0), 2.0);
  EXPECT_DOUBLE_EQ(minmod(0.5), 0.5);
  EXPECT_DOUBLE_EQ(minmod(4.0), 1.0);
  EXPECT_DOUBLE_EQ(van_leer(1.0), 1.0);
  EXPECT_DOUBLE_EQ(van_leer(3.0), 1.5);
  EXPECT_DOUBLE_EQ(van_leer(-2.0), 0.0);
  for (double r = -2.0; r <= 10.0; r += 0.125) {
    for (Limiter l : {Limiter::Superbee, Limiter::Minmod, Limiter::VanLeer}) {
      const double psi = tvd::psi(l, r);
      // TVD region of Sweby (1984): 0 <= psi <= min(2r, 2) for r > 0, psi = 0 for r <= 0.
      EXPECT_GE(psi, 0.0);
      EXPECT_LE(psi, std::max(0.0, std::min(2.0 * r, 2.0)) + 1e-15);
    }
  }
}

TEST(Limiters, FaceValuePicksUpwindSide) {
  // Linear data phi = 1, 2, 3, 4: r = 1 so every limiter gives the central value 2.5 on the middle face.
  EXPECT_DOUBLE_EQ(tvd::face_value(Limiter::Superbee, 1.0, 1, 2, 3, 4), 2.5);
  EXPECT_DOUBLE_EQ(tvd::face_value(Limiter::Superbee, -1.0, 1, 2, 3, 4), 2.5);
  // Upwind returns the upwind cell for each direction.
  EXPECT_DOUBLE_EQ(tvd::face_value(Limiter::Upwind, 1.0, 1, 2, 3, 4), 2.0);
  EXPECT_DOUBLE_EQ(tvd::face_value(Limiter::Upwind, -1.0, 1, 2, 3, 4), 3.0);
  // At an extremum (2 is a peak) the correction vanishes.
  EXPECT_DOUBLE_EQ(tvd::face_value(Limiter::Superbee, 1.0, 1, 2, 0, 4), 2.0);
}

TEST(Limiters, LineKernelsGiveTheFaceByFaceBits) {
  // tvd::face_values / face_fluxes (branch-free, vectorised, possibly an AVX-512 or AVX2 clone) must give exactly
  // the bits of face_value face by face: values on a coarse lattice so that ties (r = 1, flat regions, up * down
  // = 0), extrema, both flow directions, zero velocity and signed zeros all occur, plus irregular values.
  const int n = 4001;
  std::vector<double> phi(static_cast<std::size_t>(n + 4)), vel(static_cast<std::size_t>(n));
  std::uint64_t x = 88172645463325252ull;
  auto next = [&] {  // xorshift64: a fixed sequence
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  for (std::size_t k = 0; k < phi.size(); ++k) {
    const std::uint64_t r = next();
    phi[k] = (r % 3 == 0) ? static_cast<double>(static_cast<int>(r % 5) - 2) : std::ldexp(static_cast<double>(r >> 11), -53) - 0.5;
    if (r % 17 == 0) phi[k] = -0.0;
  }
  for (std::size_t k = 0; k < vel.size(); ++k) {
    const std::uint64_t r = next();
    vel[k] = (r % 7 == 0) ? ((r % 2) ? 0.0 : -0.0) : std::ldexp(static_cast<double>(r >> 11), -52) - 1.0;
  }
  std::vector<double> values(static_cast<std::size_t>(n)), fluxes(static_cast<std::size_t>(n));
  for (Limiter l : {Limiter::Upwind, Limiter::Minmod, Limiter::VanLeer, Limiter::Superbee}) {
    for (std::ptrdiff_t s : {1, 2}) {
      const int m = n - 2 * static_cast<int>(s);
      const double* p = phi.data() + 2 * s;  // p[i - 2s] .. p[i + s] stay inside phi
      tvd::face_values(l, m, vel.data(), p, s, values.data());
      tvd::face_fluxes(l, m, vel.data(), p, s, fluxes.data());
      int mismatches = 0;
      for (int i = 0; i < m; ++i) {
        const double v = vel[static_cast<std::size_t>(i)];
        const double ref = tvd::face_value(l, v, p[i - 2 * s], p[i - s], p[i], p[i + s]);
        mismatches += std::bit_cast<std::uint64_t>(values[static_cast<std::size_t>(i)]) != std::bit_cast<std::uint64_t>(ref);
        mismatches += std::bit_cast<std::uint64_t>(fluxes[static_cast<std::size_t>(i)]) != std::bit_cast<std::uint64_t>(v * ref);
      }
      EXPECT_EQ(mismatches, 0) << "limiter " << static_cast<int>(l) << ", stride " << s;
    }
  }
}

TEST(KineticTheory, RadialDistributionAsPrinted) {
  // Eq. 26 by hand: eps = 0.5 -> (1/0.5)(1 + 1.5 * 0.5/0.5) = 5; eps -> 1 -> 1.
  EXPECT_DOUBLE_EQ(radial_distribution(0.5), 5.0);
  EXPECT_DOUBLE_EQ(radial_distribution(1.0), 1.0);
  EXPECT_NEAR(radial_distribution(0.43), (1.0 / 0.43) * (1.0 + 1.5 * 0.57 / 0.43), 1e-14);
  // g0 grows monotonically as the bed compacts.
  for (double eps = 0.98; eps > 0.35; eps -= 0.01) EXPECT_GT(radial_distribution(eps), radial_distribution(eps + 0.01));
}

TEST(KineticTheory, HandComputedCoefficients) {
  const GranularMaterial m{0.004, 2700.0, 0.9};
  const double eps = 0.5, theta = 0.01, eps_s = 0.5, g0 = 5.0;
  // Eq. 25 by hand for e = 0.9: sqrt(pi)/(3 * 2.1) = 0.281339..., 0.4 * 1.9 * 1.7 = 1.292.
  const double k2 = 0.5 * 0.004 * 2700.0 *
                    (std::sqrt(kPi) / 6.3 * (1.0 + 1.292 * eps_s * g0) + 8.0 * eps_s * g0 * 1.9 / (5.0 * std::sqrt(kPi)));
  EXPECT_NEAR(kt_k2(m, eps_s, g0), k2, 1e-12 * k2);
  // Pencil-and-paper value: 5.4 * (0.2813394 * 4.23 + 38 / 8.862269) = 29.5807 (7 digits kept).
  EXPECT_NEAR(kt_k2(m, eps_s, g0), 29.5807, 1e-4);
  const double k1 = 4.0 * 0.004 * 2700.0 * 1.9 * 2.5 / (3.0 * std::sqrt(kPi)) - 2.0 / 3.0 * k2;
  EXPECT_NEAR(kt_k1(m, eps_s, g0), k1, 1e-12 * std::abs(k1));
  // Eq. 23: 2 * 1.9 * 2700 * 5 * 0.25 * 0.01 = 128.25 Pa.
  EXPECT_NEAR(kt_pressure(m, eps, theta), 128.25, 1e-10);
  // Eq. 24: mu = K2 eps_s sqrt(Theta) = K2 * 0.5 * 0.1.
  EXPECT_NEAR(kt_shear_viscosity(m, eps, theta), 0.05 * k2, 1e-12);
  EXPECT_NEAR(kt_bulk_viscosity(m, eps, theta), 0.05 * k1, 1e-12);
}

TEST(KineticTheory, DiluteLimitOfViscosity) {
  // eps_s -> 0 in Eq. 25: K2 -> d_p rho_s sqrt(pi) / (6 (3 - e)), so mu_s / eps_s -> that times sqrt(Theta).
  const GranularMaterial m{0.004, 2700.0, 0.9};
  const double theta = 0.04;
  const double limit = 0.004 * 2700.0 * std::sqrt(kPi) / (6.0 * 2.1) * std::sqrt(theta);
  for (double eps_s : {1e-4, 1e-6, 1e-8}) {
    // The O(eps_s g0) corrections decay linearly; 20 eps_s bounds them for these properties.
    EXPECT_NEAR(kt_shear_viscosity(m, 1.0 - eps_s, theta) / eps_s, limit, 20.0 * eps_s * limit);
  }
  EXPECT_DOUBLE_EQ(kt_pressure(m, 1.0, theta), 0.0);
}

TEST(KineticTheory, AlgebraicTemperatureBalancesProductionAndDissipation) {
  const GranularMaterial m{0.004, 2700.0, 0.9};
  for (double eps : {0.45, 0.6, 0.9}) {
    for (const StrainRate<2>& d : {d2(0.0, 0.0, 5.0), d2(2.0, -1.0, 3.0), d2(-4.0, 1.0, 0.5)}) {
      const double theta = algebraic_granular_temperature(m, eps, d);
      ASSERT_GT(theta, 0.0);
      const double eps_s = 1.0 - eps;
      const double g0 = radial_distribution(eps);
      const double p = kt_pressure(m, eps, theta), mu = kt_shear_viscosity(m, eps, theta),
                   lambda = kt_bulk_viscosity(m, eps, theta);
      // Production sigma:D with sigma = -P I + 2 mu D + lambda tr(D) I; dissipation K4 eps_s^2 Theta^1.5.
      const double production = -p * trace(d) + 2.0 * mu * double_dot(d) + lambda * trace(d) * trace(d);
      const double dissipation = kt_k4(m, g0) * eps_s * eps_s * std::pow(theta, 1.5);
      EXPECT_NEAR(production, dissipation, 1e-10 * dissipation) << eps;
    }
  }
  // Pure shear in the dense limit: Theta scales with the square of the shear rate (no intrinsic rate scale).
  const double t1 = algebraic_granular_temperature(m, 0.45, d2(0.0, 0.0, 1.0));
  const double t2 = algebraic_granular_temperature(m, 0.45, d2(0.0, 0.0, 2.0));
  EXPECT_NEAR(t2 / t1, 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(algebraic_granular_temperature(m, 0.45, StrainRate<2>{}), 0.0);
}

TEST(Frictional, HandComputedValues) {
  // Eq. 22: eps* - eps = 0.01 -> 1e24 * 1e-20 = 1e4 Pa; Eq. 21: (1 - 0.42) * 1e4.
  EXPECT_NEAR(frictional_p_star(0.42, 0.43), 1e4, 1e-6);
  EXPECT_NEAR(frictional_pressure(0.42, 0.43), 5800.0, 1e-6);
  EXPECT_DOUBLE_EQ(frictional_p_star(0.44, 0.43), 0.0);
  // Simple shear D_xy = 1: I_2D = 1, mu = 1e4 sin(40 deg) / 2.
  const double phi = 40.0 * kPi / 180.0;
  EXPECT_NEAR(frictional_viscosity(0.42, 0.43, phi, d2(0.0, 0.0, 1.0), 1e9), 0.5e4 * std::sin(phi), 1e-8);
  EXPECT_DOUBLE_EQ(frictional_viscosity(0.42, 0.43, phi, StrainRate<2>{}, 100.0), 100.0);
  EXPECT_NEAR(second_invariant(d2(1.0, -1.0, 0.0)), (4.0 + 1.0 + 1.0) / 6.0, 1e-15);
}

TEST(Frictional, JohnsonJacksonPressureHandValues) {
  const FrictionalParams f{};  // Fr 0.05 Pa, n 2, p 5, onset 0.5, limit 0.63
  EXPECT_DOUBLE_EQ(jj_frictional_pressure(f, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(jj_frictional_pressure(f, 0.3), 0.0);
  // eps_s = 0.58: 0.05 * 0.08^2 / 0.05^5 = 0.05 * 0.0064 / 3.125e-7 = 1024 Pa.
  EXPECT_NEAR(jj_frictional_pressure(f, 0.58), 1024.0, 1024.0 * 1e-13);
  // Continuous at the onset (the excess enters squared) and growing without bound towards the limit.
  EXPECT_LT(jj_frictional_pressure(f, 0.5 + 1e-6), 1e-8);
  EXPECT_GT(jj_frictional_pressure(f, 0.629), 1e9);
}

TEST(Frictional, ViscosityOnAPressureIsSchaefferWithoutTheta) {
  // theta_d2 = 0: sqrt(2) P sin(phi) / (2 sqrt(2 I_2D)) = P sin(phi) / (2 sqrt(I_2D)), Eq. 21's form on P* = 1e4.
  const double phi = 40.0 * kPi / 180.0;
  const StrainRate<2> shear = d2(0.0, 0.0, 1.0);
  EXPECT_NEAR(frictional_viscosity_on(1e4, phi, shear, 0.0, 1e9), frictional_viscosity(0.42, 0.43, phi, shear, 1e9),
              1e-12 * 1e4);
  // Srivastava-Sundaresan: Theta / d^2 adds to S:S = 2 I_2D = 2; with 6 more the root doubles, the viscosity halves.
  EXPECT_NEAR(frictional_viscosity_on(1e4, phi, shear, 6.0, 1e9),
              0.5 * frictional_viscosity_on(1e4, phi, shear, 0.0, 1e9), 1e-12 * 1e4);
  // At rest: the cap without Theta, a finite value with it.
  EXPECT_DOUBLE_EQ(frictional_viscosity_on(1e4, phi, StrainRate<2>{}, 0.0, 100.0), 100.0);
  EXPECT_NEAR(frictional_viscosity_on(10.0, phi, StrainRate<2>{}, 4.0, 100.0),
              std::sqrt(0.5) * 10.0 * std::sin(phi) / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(frictional_viscosity_on(0.0, phi, shear, 0.0, 100.0), 0.0);
}

TEST(StrainRateInvariants, ThreeDimensionalFormReducesToPlaneStrain) {
  // A 3D strain rate with zero out-of-plane components is the 2D one: trace, D:D and Schaeffer's invariant agree
  // to the last bit (the zero terms are exact), so 2D results do not move when the closures are shared with 3D.
  for (const StrainRate<2>& d : {d2(0.3, -1.7, 2.2), d2(-4.0, 1.0, 0.5), d2(1e-3, 2e-3, -7e-4)}) {
    StrainRate<3> e;
    e(0, 0) = d(0, 0);
    e(1, 1) = d(1, 1);
    e(0, 1) = d(0, 1);
    EXPECT_EQ(trace(e), trace(d));
    EXPECT_EQ(double_dot(e), double_dot(d));
    EXPECT_EQ(second_invariant(e), second_invariant(d));
    // The paper's plane-strain formula, written out.
    const double xx = d(0, 0), yy = d(1, 1), xy = d(0, 1);
    EXPECT_EQ(second_invariant(d), ((xx - yy) * (xx - yy) + yy * yy + xx * xx) / 6.0 + xy * xy);
  }
}

TEST(StrainRateInvariants, ThreeDimensionalHandValues) {
  // Uniaxial extension D = diag(1, 0, 0): I_2D = (1 + 0 + 1) / 6 = 1/3; D:D = 1.
  StrainRate<3> a;
  a(0, 0) = 1.0;
  EXPECT_DOUBLE_EQ(second_invariant(a), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(double_dot(a), 1.0);
  // Isotropic D = I: no deviatoric part, I_2D = 0; tr = 3, D:D = 3.
  StrainRate<3> b;
  for (int k = 0; k < 3; ++k) b(k, k) = 1.0;
  EXPECT_DOUBLE_EQ(second_invariant(b), 0.0);
  EXPECT_DOUBLE_EQ(trace(b), 3.0);
  // Shear in the y-z plane, D_yz = 2: I_2D = 4, D:D = 2 * 4; symmetric access (2, 1) is the same slot.
  StrainRate<3> c;
  c(1, 2) = 2.0;
  EXPECT_DOUBLE_EQ(c(2, 1), 2.0);
  EXPECT_DOUBLE_EQ(second_invariant(c), 4.0);
  EXPECT_DOUBLE_EQ(double_dot(c), 8.0);
  // I_2D is frame-invariant: D_xy = 1 (simple shear) rotated by 45 degrees about z is diag(1, -1, 0).
  StrainRate<3> s, r;
  s(0, 1) = 1.0;
  r(0, 0) = 1.0;
  r(1, 1) = -1.0;
  EXPECT_DOUBLE_EQ(second_invariant(s), second_invariant(r));
}

TEST(Modulus, Eq20ExponentialForm) {
  const ModulusParams p{1.0, 600.0};
  EXPECT_DOUBLE_EQ(modulus_g(p, 0.43, 0.43), 1.0);
  EXPECT_NEAR(modulus_g(p, 0.42, 0.43), std::exp(6.0), 1e-9);
  // dP_s/d eps = -G: central difference of the pressure reproduces the modulus.
  const double h = 1e-6;
  const double dp = (modulus_pressure(p, 0.42 + h, 0.43) - modulus_pressure(p, 0.42 - h, 0.43)) / (2.0 * h);
  EXPECT_NEAR(-dp, modulus_g(p, 0.42, 0.43), 1e-6 * modulus_g(p, 0.42, 0.43));
  EXPECT_NEAR(modulus_pressure(p, modulus_voidage_for_pressure(p, 8000.0, 0.43), 0.43), 8000.0, 1e-8);
}

}  // namespace
}  // namespace fluidbed::tfm
