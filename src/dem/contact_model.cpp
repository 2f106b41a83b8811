#include "dem/contact_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fluidbed {

const char* to_string(NormalModel m) { return m == NormalModel::Hertz ? "hertz" : "linear"; }
const char* to_string(DampingModel m) { return m == DampingModel::Tsuji ? "tsuji" : "paper"; }
const char* to_string(TangentialModel m) { return m == TangentialModel::Mindlin ? "mindlin" : "linear"; }
const char* to_string(RollingModel m) {
  switch (m) {
    case RollingModel::Constant: return "constant";
    case RollingModel::Epsd: return "epsd";
    case RollingModel::None: break;
  }
  return "none";
}

double effective_youngs_modulus(const ElasticMaterial& a, const ElasticMaterial& b) {
  const auto c = [](const ElasticMaterial& m) { return (1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus; };
  return 1.0 / (c(a) + c(b));
}

double effective_shear_modulus(const ElasticMaterial& a, const ElasticMaterial& b) {
  const auto c = [](const ElasticMaterial& m) {
    return 2.0 * (2.0 - m.poisson_ratio) * (1.0 + m.poisson_ratio) / m.youngs_modulus;
  };
  return 1.0 / (c(a) + c(b));
}

double hertz_tsuji_restitution(double alpha) {
  // X'' = -X^(3/2) - c X^(1/4) X', X(0) = 0, X'(0) = 1; the undamped contact lasts 2.94 time units.
  const double c = alpha * std::sqrt(1.5);
  const auto acc = [c](double x, double v) {
    const double xp = std::max(x, 0.0);
    return -xp * std::sqrt(xp) - c * std::sqrt(std::sqrt(xp)) * v;
  };
  constexpr double h = 1e-4;
  double x = 0.0, v = 1.0;
  for (int k = 0; k < 4000000; ++k) {
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    const double xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    const double vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    if (k > 0 && xn <= 0.0) {
      // Separation inside the step: the velocity there by linear interpolation in X.
      const double s = x / (x - xn);
      return -(v + s * (vn - v));
    }
    x = xn;
    v = vn;
  }
  return 0.0;
}

double tsuji_alpha_for_hertz(double e) {
  if (e >= 1.0) return 0.0;
  double lo = 0.0, hi = 1.0;
  while (hertz_tsuji_restitution(hi) > e && hi < 1e3) hi *= 2.0;
  for (int it = 0; it < 60 && hi - lo > 1e-10; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (hertz_tsuji_restitution(mid) > e) lo = mid; else hi = mid;
  }
  return 0.5 * (lo + hi);
}

double tsuji_alpha_for_linear(double e) {
  const double l = std::log(1.0 / e);
  return 2.0 * l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);  // Eq. 8 over sqrt(m k)
}

HertzImpact hertz_impact(double m_eff, double e_star, double r_eff, double v) {
  const double d = std::pow(15.0 * m_eff * v * v / (16.0 * e_star * std::sqrt(r_eff)), 0.4);
  // int_0^1 (1 - x^(5/2))^(-1/2) dx = (2/5) B(2/5, 1/2)
  const double integral = 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  return {d, 2.0 * integral * d / v};
}

}  // namespace fluidbed
