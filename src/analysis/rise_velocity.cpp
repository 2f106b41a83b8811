#include "analysis/rise_velocity.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fluidbed {

double bubble_rise_velocity_2d(double D, double g) {
  if (!(D >= 0.0) || !(g >= 0.0)) throw_input_error(fmt::format("bubble rise velocity: D = {}, g = {}", D, g));
  // Two-dimensional bubble rising through a fluidized bed: U_b = C sqrt(g D) (docs/analysis.md gives the source).
  return rise_constant_2d * std::sqrt(g * D);
}

}  // namespace fluidbed
