#include "dem/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/format.h>

namespace fluidbed {

namespace {

constexpr double kSqrtPi = 1.7724538509055160273;  // sqrt(pi)

double phi_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }
double phi_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); }

// The standardised variable of d: z = (d - mean) / std, or (ln d - ln median) / sigma.
double standardised(const SizeDistribution& s, double d) {
  return s.law == SizeLaw::Normal ? (d - s.mean) / s.std : std::log(d / s.median) / s.sigma;
}

// erfcx(x) = exp(x^2) erfc(x), x >= 0: the product while erfc(x) is a normal double, x^2 split exactly so that
// exp(x^2) loses no digit; beyond, the asymptotic series (Abramowitz and Stegun 7.1.23), whose ninth term is below
// 1e-18 there.
double erfcx(double x) {
  if (x < 26.0) {
    const double x2 = x * x;
    return std::exp(x2) * std::erfc(x) * (1.0 + std::fma(x, x, -x2));
  }
  const double r = 0.5 / (x * x);
  double term = 1.0, sum = 1.0;
  for (int n = 1; n <= 8; ++n) {
    term *= -(2 * n - 1) * r;
    sum += term;
  }
  return sum / (x * kSqrtPi);
}

// Q(z) exp(c^2 / 2) for z >= c >= 0, Q the upper tail of the standard normal: erfcx(z / sqrt 2) / 2 times
// exp(-(z - c)(z + c) / 2), finite and to full precision however far out c lies (Q(40) underflows).
double scaled_upper_tail(double z, double c) {
  return 0.5 * erfcx(z / std::numbers::sqrt2) * std::exp(-0.5 * (z - c) * (z + c));
}

// P(a <= Z <= b) of the standard normal as m exp(-e). With the mode inside, Phi(b) - Phi(a) (e = 0); on one side
// of it, measured from the end nearer the mode, c: Q(c) - Q(far) scaled by exp(c^2 / 2), so that a far tail
// neither underflows nor cancels to 1 - 1.
struct ScaledMass {
  double m = 0.0, e = 0.0;
};
ScaledMass normal_mass(double a, double b) {
  if (a > 0.0) return {scaled_upper_tail(a, a) - scaled_upper_tail(b, a), 0.5 * a * a};
  if (b < 0.0) return normal_mass(-b, -a);
  return {phi_cdf(b) - phi_cdf(a), 0.0};
}

// The CDF at z of the standard normal truncated to [a, b]; on one side of the mode, both masses from the end
// nearer it, so that their scales are the same and cancel.
double truncated_normal_cdf(double a, double b, double z) {
  if (a <= 0.0 && b >= 0.0) {
    const double lo = phi_cdf(a), hi = phi_cdf(b);
    return (phi_cdf(z) - lo) / (hi - lo);
  }
  const ScaledMass all = normal_mass(a, b);
  return a > 0.0 ? normal_mass(a, z).m / all.m : 1.0 - normal_mass(z, b).m / all.m;
}

// Composite Simpson of the number moments over n intervals (n even); node(i) gives d and the density, up to a
// constant factor, at node i.
template <class Node>
SizeMoments simpson_moments(int n, Node node) {
  SizeMoments m;
  double w0 = 0.0;
  for (int i = 0; i <= n; ++i) {
    const auto [d, f] = node(i);
    const double c = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    const double w = c * f;
    w0 += w;
    m.m1 += w * d;
    m.m2 += w * d * d;
    m.m3 += w * d * d * d;
  }
  m.m1 /= w0;
  m.m2 /= w0;
  m.m3 /= w0;
  return m;
}

// Truncated normal by quadrature: the integrand is a polynomial times a Gaussian, smooth. With the mode inside,
// over the standardised range as far as phi is a normal double (|z| < 37.5), steps of at most 0.005; on one side
// of the mode, over the distance y from the cut-off nearer it (c standard deviations from the mean), where the
// density falls as exp(-y (y + 2c) / 2), as far as it is 1e-20 of its value at the cut-off.
SizeMoments normal_moments(const SizeDistribution& s) {
  const double a = standardised(s, s.d_min), b = standardised(s, s.d_max);
  if (a <= 0.0 && b >= 0.0) {
    const double z0 = std::max(a, -37.5), z1 = std::min(b, 37.5);
    const int n = std::max(4000, 2 * static_cast<int>(std::ceil((z1 - z0) / 0.01)));
    const double h = (z1 - z0) / n;
    return simpson_moments(n, [&](int i) {
      const double z = z0 + i * h;
      return std::pair{s.mean + s.std * z, phi_pdf(z)};
    });
  }
  const bool above = a > 0.0;
  const double c = above ? a : -b, d_c = above ? s.d_min : s.d_max, dir = above ? 1.0 : -1.0;
  const double y1 = std::min(b - a, 92.0 / (c + std::sqrt(c * c + 92.0)));  // y (y + 2c) = 92: exp(-46) = 1e-20
  constexpr int n = 8000;
  const double h = y1 / n;
  return simpson_moments(n, [&](int i) {
    const double y = i * h;
    return std::pair{d_c + dir * s.std * y, std::exp(-0.5 * y * (y + 2.0 * c))};
  });
}

}  // namespace

const char* size_law_name(SizeLaw law) {
  switch (law) {
    case SizeLaw::Fixed: return "fixed";
    case SizeLaw::Uniform: return "uniform";
    case SizeLaw::Normal: return "normal";
    case SizeLaw::LogNormal: return "log-normal";
    case SizeLaw::List: return "list";
  }
  return "fixed";
}

SizeDistribution fixed_size(double d) {
  SizeDistribution s;
  s.d_min = s.d_max = d;
  return s;
}

double size_cdf(const SizeDistribution& s, double d) {
  if (d < s.d_min) return 0.0;
  if (d >= s.d_max) return 1.0;
  switch (s.law) {
    case SizeLaw::Fixed: return 0.0;
    case SizeLaw::Uniform: return (d - s.d_min) / (s.d_max - s.d_min);
    case SizeLaw::List: {
      double f = 0.0;
      for (std::size_t k = 0; k < s.diameters.size(); ++k) f += s.diameters[k] <= d ? s.fractions[k] : 0.0;
      return f;
    }
    case SizeLaw::Normal:
    case SizeLaw::LogNormal:
      return truncated_normal_cdf(standardised(s, s.d_min), standardised(s, s.d_max), standardised(s, d));
  }
  return 0.0;
}

double size_quantile(const SizeDistribution& s, double u) {
  switch (s.law) {
    case SizeLaw::Fixed: return s.d_min;
    case SizeLaw::Uniform: return s.d_min + u * (s.d_max - s.d_min);
    case SizeLaw::List: {
      double acc = 0.0;
      for (std::size_t k = 0; k < s.diameters.size(); ++k) {
        acc += s.fractions[k];
        if (u < acc) return s.diameters[k];
      }
      return s.diameters.back();
    }
    case SizeLaw::Normal:
    case SizeLaw::LogNormal: {
      // Bisection of the CDF: monotone, and exact to round-off whatever the cut-offs (an inverse-Phi formula
      // loses digits far in a tail).
      double lo = s.d_min, hi = s.d_max;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
        const double mid = s.law == SizeLaw::LogNormal ? std::sqrt(lo * hi) : 0.5 * (lo + hi);
        (size_cdf(s, mid) <= u ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    }
  }
  return s.d_min;
}

double size_range_log_mass(const SizeDistribution& s) {
  if (s.law != SizeLaw::Normal && s.law != SizeLaw::LogNormal) return 0.0;
  const ScaledMass p = normal_mass(standardised(s, s.d_min), standardised(s, s.d_max));
  return std::log(p.m) - p.e;
}

std::optional<SizeRangeRefusal> size_range_refusal(const SizeDistribution& s, const std::string& prefix) {
  const double log_mass = size_range_log_mass(s);
  if (log_mass >= std::log(kMinSizeRangeMass)) return std::nullopt;
  const bool normal = s.law == SizeLaw::Normal;
  const double a = standardised(s, s.d_min), b = standardised(s, s.d_max);
  const std::string& p = prefix;
  const std::string mass = log_mass > -700.0 ? fmt::format("{:.2g}", std::exp(log_mass))
                                             : fmt::format("10^{:.0f}", log_mass / std::numbers::ln10);
  const std::string law = normal ? fmt::format("the normal law of {}mean = {} m and {}std = {} m", p, s.mean, p, s.std)
                                 : fmt::format("the log-normal law of {}median = {} m and {}sigma = {}", p, s.median,
                                               p, s.sigma);
  const char* unit = normal ? "standard deviations" : "sigma";
  const char* centre = normal ? "mean" : "median";
  const std::string where = a > 0.0   ? fmt::format("{:.3g} to {:.3g} {} above the {}", a, b, unit, centre)
                            : b < 0.0 ? fmt::format("{:.3g} to {:.3g} {} below the {}", -a, -b, unit, centre)
                                      : std::string("about the mode");
  return SizeRangeRefusal{
      a > 0.0 ? "d_min" : "d_max",
      fmt::format("the cut-offs {}d_min = {} m and {}d_max = {} m lie {}: they hold {} of {}, below {:g}, so the "
                  "sizes placed could not follow that law; bring the cut-offs toward the {} or correct {}",
                  p, s.d_min, p, s.d_max, where, mass, law, kMinSizeRangeMass, centre,
                  normal ? "mean and std" : "median and sigma")};
}

SizeMoments size_moments(const SizeDistribution& s) {
  SizeMoments m;
  switch (s.law) {
    case SizeLaw::Fixed: {
      const double d = s.d_min;
      return {d, d * d, d * d * d};
    }
    case SizeLaw::Uniform: {
      // <d^k> = (b^(k+1) - a^(k+1)) / ((k + 1)(b - a))
      const double a = s.d_min, b = s.d_max;
      if (b == a) return {a, a * a, a * a * a};
      const double w = b - a;
      return {(b * b - a * a) / (2.0 * w), (b * b * b - a * a * a) / (3.0 * w), (b * b * b * b - a * a * a * a) / (4.0 * w)};
    }
    case SizeLaw::List:
      for (std::size_t k = 0; k < s.diameters.size(); ++k) {
        const double d = s.diameters[k], f = s.fractions[k];
        m.m1 += f * d;
        m.m2 += f * d * d;
        m.m3 += f * d * d * d;
      }
      return m;
    case SizeLaw::LogNormal: {
      // Truncated log-normal: <d^k> = median^k exp(k^2 sigma^2 / 2) [Phi(b - k sigma) - Phi(a - k sigma)] /
      // [Phi(b) - Phi(a)], a and b the standardised cut-offs (Johnson, Kotz and Balakrishnan 1994, ch. 14); the
      // masses scaled (normal_mass), their scales in the exponent, so that a far tail neither underflows nor cancels.
      const double a = standardised(s, s.d_min), b = standardised(s, s.d_max);
      const ScaledMass z = normal_mass(a, b);
      auto mk = [&](int k) {
        const double ks = k * s.sigma;
        const ScaledMass zk = normal_mass(a - ks, b - ks);
        const double v = std::pow(s.median, k) * std::exp(0.5 * ks * ks + z.e - zk.e) * zk.m / z.m;
        return std::clamp(v, std::pow(s.d_min, k), std::pow(s.d_max, k));  // round-off at a cut-off the mass sits on
      };
      return {mk(1), mk(2), mk(3)};
    }
    case SizeLaw::Normal:
      return normal_moments(s);
  }
  return m;
}

}  // namespace fluidbed
