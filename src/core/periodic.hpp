#pragma once
// Periodic axes of the box: a particle that leaves through one side comes back through the opposite one, and two
// particles interact through the nearest of their periodic images (the minimum-image convention of molecular
// dynamics, Allen and Tildesley, "Computer Simulation of Liquids", 1987, section 1.5.2).
#include <array>

#include "core/vec.hpp"

namespace fluidbed {

template <int Dim>
struct PeriodicBox {
  std::array<bool, Dim> on{};  ///< axis a is periodic
  Vec<Dim> length{};           ///< period of each axis (the box's extent), m

  bool any() const {
    bool a = false;
    for (int k = 0; k < Dim; ++k) a = a || on[static_cast<std::size_t>(k)];
    return a;
  }
  bool periodic(int a) const { return on[static_cast<std::size_t>(a)]; }
  /// The separation d along axis a replaced by its nearest image. Valid for |d| < 1.5 L, which holds for two
  /// points that are both inside [0, L) up to a fraction of the period; exactly antisymmetric in d (rounding is).
  double min_image(int a, double d) const {
    if (!periodic(a)) return d;
    const double L = length[a];
    if (d > 0.5 * L) return d - L;
    if (d < -0.5 * L) return d + L;
    return d;
  }
  Vec<Dim> min_image(Vec<Dim> d) const {
    for (int a = 0; a < Dim; ++a) d[a] = min_image(a, d[a]);
    return d;
  }
  /// Coordinate x mapped into [0, L) on a periodic axis (unchanged on the others). Valid for x in [-L, 2L): a
  /// particle moves far less than a period per step.
  double wrap(int a, double x) const {
    if (!periodic(a)) return x;
    const double L = length[a];
    if (x < 0.0) x += L;
    // x + L can round up to L itself for a tiny negative x: the second test maps that onto 0.
    if (x >= L) x -= L;
    return x;
  }
};

}  // namespace fluidbed
