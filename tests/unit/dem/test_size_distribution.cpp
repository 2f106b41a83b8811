// Truncated normal and log-normal size laws in any tail (src/dem/size_distribution.hpp): moments, CDF and
// quantile against an independent quadrature of the truncated density.
// The quadrature: composite Simpson in d (normal) or ln d (log-normal) of d^k times the density, in log space
// shifted by its largest value on the range so that no tail underflows, with n = 2^16 and 2^17 intervals; its
// error is estimated as |S_2n - S_n| / 15 (Richardson). Tolerance: the 1e-10 relative error that size_moments()
// documents, plus ten times that estimate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "dem/size_distribution.hpp"

namespace fluidbed {
namespace {

struct Quadrature {
  double value = 0.0;  ///< the moment <d^k> of the truncated law (or its CDF)
  double error = 0.0;  ///< estimated absolute error
};

// log of the untruncated density in the integration variable x (d or ln d), plus k ln d, at x.
double log_integrand(const SizeDistribution& s, int k, double x) {
  if (s.law == SizeLaw::Normal) {
    const double z = (x - s.mean) / s.std;
    return -0.5 * z * z + k * std::log(x);
  }
  const double z = (x - std::log(s.median)) / s.sigma;
  return -0.5 * z * z + k * x;  // d = e^x, dd = d dx: the density of x = ln d is the normal one
}

// Composite Simpson of exp(log_integrand - shift) over [x0, x1], n intervals.
double simpson(const SizeDistribution& s, int k, double x0, double x1, int n, double shift) {
  const double h = (x1 - x0) / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double c = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += c * std::exp(log_integrand(s, k, x0 + i * h) - shift);
  }
  return sum * h / 3.0;
}

// Simpson with n and 2n intervals of the log-integrand over [x0, x1], shifted by its largest value at the nodes;
// the integral is exp(shift) times `fine`.
struct Simpson2 {
  double shift = 0.0, coarse = 0.0, fine = 0.0;
};
Simpson2 simpson2(const SizeDistribution& s, int k, double x0, double x1) {
  constexpr int n = 1 << 16;
  Simpson2 r;
  r.shift = -std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 2 * n; ++i) r.shift = std::max(r.shift, log_integrand(s, k, x0 + i * (x1 - x0) / (2 * n)));
  r.coarse = simpson(s, k, x0, x1, n, r.shift);
  r.fine = simpson(s, k, x0, x1, 2 * n, r.shift);
  return r;
}

// The integration variable of d: d (normal) or ln d (log-normal).
double variable(const SizeDistribution& s, double d) { return s.law == SizeLaw::LogNormal ? std::log(d) : d; }

// int_{d_min}^{d} d'^k f(d') dd' / int_{d_min}^{d_max} f, f the untruncated density, with its error estimate.
class TruncatedQuadrature {
 public:
  explicit TruncatedQuadrature(const SizeDistribution& s)
      : s_(s), den_(simpson2(s, 0, variable(s, s.d_min), variable(s, s.d_max))) {}
  Quadrature integral(int k, double d) const {
    const Simpson2 num = simpson2(s_, k, variable(s_, s_.d_min), variable(s_, d));
    const double scale = std::exp(num.shift - den_.shift);
    Quadrature q;
    q.value = scale * num.fine / den_.fine;
    q.error = std::abs(q.value - scale * num.coarse / den_.coarse) / 15.0;
    return q;
  }

 private:
  SizeDistribution s_;
  Simpson2 den_;
};

SizeDistribution normal(double mean, double std, double z_min, double z_max) {
  SizeDistribution s;
  s.law = SizeLaw::Normal;
  s.mean = mean;
  s.std = std;
  s.d_min = mean + z_min * std;
  s.d_max = mean + z_max * std;
  return s;
}

SizeDistribution log_normal(double median, double sigma, double z_min, double z_max) {
  SizeDistribution s;
  s.law = SizeLaw::LogNormal;
  s.median = median;
  s.sigma = sigma;
  s.d_min = median * std::exp(z_min * sigma);
  s.d_max = median * std::exp(z_max * sigma);
  return s;
}

struct TailCase {
  std::string name;
  SizeDistribution s;
};

std::vector<TailCase> cases() {
  return {
      {"log-normal 8 to 9 sigma above the median", log_normal(0.001, 0.25, 8.0, 9.0)},
      {"log-normal 40 to 42 sigma above (mass 1e-350)", log_normal(0.0001, 0.05, 40.0, 42.0)},
      {"log-normal 12 to 10 sigma below", log_normal(0.003, 0.2, -12.0, -10.0)},
      {"normal 20 to 25 std above the mean", normal(0.003, 0.0001, 20.0, 25.0)},
      {"normal 45 to 60 std above (mass 1e-442)", normal(0.003, 0.0001, 45.0, 60.0)},
      {"normal 14.5 to 12 std below", normal(0.003, 0.0002, -14.5, -12.0)},
      {"normal -3 to 270 std (wide range over the mode)", normal(0.003, 0.0001, -3.0, 270.0)},
      {"normal +-3 std (cases/bidisperse)", normal(0.004, 0.0002, -3.0, 3.0)},
      {"log-normal (tests/verification/polydisperse)", log_normal(0.003, 0.25, std::log(2.0 / 3.0) / 0.25,
                                                                  std::log(5.0 / 3.0) / 0.25)},
  };
}

TEST(SizeDistributionTails, MomentsMatchQuadratureAndLieWithinTheCutOffs) {
  for (const TailCase& c : cases()) {
    const SizeDistribution& s = c.s;
    const SizeMoments m = size_moments(s);
    const TruncatedQuadrature quadrature(s);
    const double got[3] = {m.m1, m.m2, m.m3};
    double exact[3];
    for (int k = 1; k <= 3; ++k) {
      const Quadrature q = quadrature.integral(k, s.d_max);
      exact[k - 1] = q.value;
      const double tol = 1e-10 * q.value + 10.0 * q.error;
      std::printf("[ %-48s ] <d^%d> exact %.12e, computed %.12e, error %.1e (tolerance %.1e)\n", c.name.c_str(), k,
                  q.value, got[k - 1], got[k - 1] - q.value, tol);
      EXPECT_NEAR(got[k - 1], q.value, tol) << c.name << ", moment " << k;
      EXPECT_GE(got[k - 1], std::pow(s.d_min, k)) << c.name;
      EXPECT_LE(got[k - 1], std::pow(s.d_max, k)) << c.name;
    }
    EXPECT_NEAR(m.d32(), exact[2] / exact[1], 2e-10 * m.d32()) << c.name;
    EXPECT_TRUE(std::isfinite(m.d32()) && m.d32() >= s.d_min && m.d32() <= s.d_max) << c.name << ": " << m.d32();
  }
}

TEST(SizeDistributionTails, CdfAndQuantileFollowTheTruncatedLaw) {
  for (const TailCase& c : cases()) {
    const SizeDistribution& s = c.s;
    // The CDF inside the range against the quadrature; the quantile inverts it and stays within the cut-offs.
    const TruncatedQuadrature quadrature(s);
    for (const double u : {0.0, 1e-9, 0.37, 0.9, 1.0 - 0x1p-53}) {
      const double d = size_quantile(s, u);
      ASSERT_TRUE(d >= s.d_min && d <= s.d_max) << c.name << ": u = " << u << " gives " << d;
      const Quadrature f = quadrature.integral(0, d);
      EXPECT_NEAR(f.value, u, 1e-9 + 10.0 * f.error) << c.name << ": u = " << u << ", d = " << d;
      EXPECT_NEAR(size_cdf(s, d), f.value, 1e-9 + 10.0 * f.error) << c.name << ": d = " << d;
    }
    EXPECT_EQ(size_cdf(s, s.d_min * (1.0 - 1e-12)), 0.0);
    EXPECT_EQ(size_cdf(s, s.d_max), 1.0);
  }
}

// ln of the probability of [d_min, d_max] under the untruncated law, by the same quadrature (normalised density:
// 1 / (std sqrt(2 pi)) in d, 1 / (sigma sqrt(2 pi)) in ln d).
double log_range_mass(const SizeDistribution& s) {
  const Simpson2 q = simpson2(s, 0, variable(s, s.d_min), variable(s, s.d_max));
  const double spread = s.law == SizeLaw::LogNormal ? s.sigma : s.std;
  return q.shift + std::log(q.fine) - std::log(spread * std::sqrt(2.0 * std::numbers::pi));
}

TEST(SizeDistributionTails, RangeMassAndTheRefusalOfARangeFarInATail) {
  // The mass of each range against the quadrature (the estimated relative error of the quadrature is below 1e-12
  // for these ranges: a tolerance of 1e-9 in its logarithm).
  for (const TailCase& c : cases()) {
    const double exact = log_range_mass(c.s), got = size_range_log_mass(c.s);
    std::printf("[ %-48s ] ln P(d_min <= d <= d_max): exact %.12g, computed %.12g\n", c.name.c_str(), exact, got);
    EXPECT_NEAR(got, exact, 1e-9) << c.name;
  }
  // Log-normal 8 to 9 sigma above the median: 6e-16 of the law, refused at d_min with the keys of the species.
  const auto lognormal = size_range_refusal(log_normal(0.001, 0.25, 8.0, 9.0), "species[1].");
  ASSERT_TRUE(lognormal.has_value());
  std::printf("%s: %s\n", lognormal->key.c_str(), lognormal->message.c_str());
  EXPECT_EQ(lognormal->key, "d_min");
  for (const char* key : {"species[1].d_min", "species[1].d_max", "species[1].median", "species[1].sigma", "above"}) {
    EXPECT_NE(lognormal->message.find(key), std::string::npos) << key;
  }
  // Normal 20 std above the mean (3e-89), and 12 to 14.5 below (5e-34, at d_max); mean and std named.
  const auto above = size_range_refusal(normal(0.003, 0.0001, 20.0, 25.0), "species[0].");
  ASSERT_TRUE(above.has_value());
  std::printf("%s: %s\n", above->key.c_str(), above->message.c_str());
  EXPECT_EQ(above->key, "d_min");
  for (const char* key : {"species[0].d_min", "species[0].d_max", "species[0].mean", "species[0].std"}) {
    EXPECT_NE(above->message.find(key), std::string::npos) << key;
  }
  const auto below = size_range_refusal(normal(0.003, 0.0002, -14.5, -12.0), "species[0].");
  ASSERT_TRUE(below.has_value());
  EXPECT_EQ(below->key, "d_max");
  EXPECT_NE(below->message.find("below"), std::string::npos);
  // A mass beyond double precision is still named (as a power of ten).
  const auto far = size_range_refusal(normal(0.003, 0.0001, 45.0, 60.0), "species[0].");
  ASSERT_TRUE(far.has_value());
  EXPECT_NE(far->message.find("10^-442"), std::string::npos) << far->message;
  // Ranges worth sampling: 6 to 7 sigma out (1e-9), the ordinary cases, and the laws without a tail.
  EXPECT_FALSE(size_range_refusal(log_normal(0.001, 0.25, 6.0, 7.0), "species[0]."));
  EXPECT_FALSE(size_range_refusal(normal(0.004, 0.0002, -3.0, 3.0), "species[0]."));
  EXPECT_FALSE(size_range_refusal(normal(0.003, 0.0001, -3.0, 270.0), "species[0]."));
  EXPECT_FALSE(size_range_refusal(fixed_size(0.004), "species[0]."));
  SizeDistribution uniform;
  uniform.law = SizeLaw::Uniform;
  uniform.d_min = 0.002;
  uniform.d_max = 0.003;
  EXPECT_FALSE(size_range_refusal(uniform, "species[0]."));
  EXPECT_EQ(size_range_log_mass(uniform), 0.0);
}

}  // namespace
}  // namespace fluidbed
