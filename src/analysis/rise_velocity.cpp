#include "analysis/rise_velocity.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fluidbed {

namespace {

double rise(double C, double D, double g) {
  if (!(D >= 0.0) || !(g >= 0.0)) throw_input_error(fmt::format("bubble rise velocity: D = {}, g = {}", D, g));
  return C * std::sqrt(g * D);
}

}  // namespace

double bubble_rise_velocity_2d(double D, double g) {
  // Two-dimensional bubble rising through a fluidized bed: U_b = C sqrt(g D) (docs/analysis.md gives the source).
  return rise(rise_constant_2d, D, g);
}

double bubble_rise_velocity_3d(double D, double g) {
  // Davidson and Harrison (1963): a spherical-cap bubble rises at 0.711 sqrt(g D_e).
  return rise(rise_constant_3d, D, g);
}

double bubble_rise_velocity(int dimension, double D, double g) {
  if (dimension == 2) return bubble_rise_velocity_2d(D, g);
  if (dimension == 3) return bubble_rise_velocity_3d(D, g);
  throw_input_error(fmt::format("bubble rise velocity: dimension {} is neither 2 nor 3", dimension));
}

double rise_slope(const std::vector<double>& t, const std::vector<double>& h) {
  const double n = static_cast<double>(t.size());
  double tm = 0.0, hm = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    tm += t[k];
    hm += h[k];
  }
  tm /= n;
  hm /= n;
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    num += (t[k] - tm) * (h[k] - hm);
    den += (t[k] - tm) * (t[k] - tm);
  }
  return den > 0.0 ? num / den : 0.0;
}

}  // namespace fluidbed
