#include "dem/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fluidbed {

namespace {

double phi_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }
double phi_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); }

// The standardised variable of d: z = (d - mean) / std, or (ln d - ln median) / sigma.
double standardised(const SizeDistribution& s, double d) {
  return s.law == SizeLaw::Normal ? (d - s.mean) / s.std : std::log(d / s.median) / s.sigma;
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
    case SizeLaw::LogNormal: {
      const double lo = phi_cdf(standardised(s, s.d_min)), hi = phi_cdf(standardised(s, s.d_max));
      return (phi_cdf(standardised(s, d)) - lo) / (hi - lo);
    }
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
      // [Phi(b) - Phi(a)], a and b the standardised cut-offs (Johnson, Kotz and Balakrishnan 1994, ch. 14).
      const double a = standardised(s, s.d_min), b = standardised(s, s.d_max);
      const double z = phi_cdf(b) - phi_cdf(a);
      auto mk = [&](int k) {
        const double ks = k * s.sigma;
        return std::pow(s.median, k) * std::exp(0.5 * ks * ks) * (phi_cdf(b - ks) - phi_cdf(a - ks)) / z;
      };
      return {mk(1), mk(2), mk(3)};
    }
    case SizeLaw::Normal: {
      // Composite Simpson over the standardised range: the integrand is a polynomial times a Gaussian, smooth.
      const double a = standardised(s, s.d_min), b = standardised(s, s.d_max);
      constexpr int n = 4000;
      const double h = (b - a) / n;
      double w0 = 0.0;
      for (int i = 0; i <= n; ++i) {
        const double z = a + i * h;
        const double c = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
        const double w = c * phi_pdf(z);
        const double d = s.mean + s.std * z;
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
  }
  return m;
}

}  // namespace fluidbed
