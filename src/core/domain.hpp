#pragma once
// The box every model lives in, and gravity: read once from [domain] and handed to each model, so that the DEM,
// the gas and the two-fluid model cannot disagree on them. Stored with three components whatever the dimension;
// a 2D model reads the first two (x across, y up) and a 3D one adds z (the depth, between front and back).
#include <array>

#include "core/periodic.hpp"
#include "core/vec.hpp"

namespace fluidbed {

struct DomainConfig {
  int dimension = 2;          ///< 2: a monolayer in the x-y plane; 3: a box
  double width = 0.6;         ///< x, m (Table 1)
  double height = 1.0;        ///< y, m
  double depth = 0.0;         ///< z, m (3D only)
  Vec3 gravity{0.0, -9.81, 0.0};  ///< m/s^2
  /// Periodic axes (x, y, z): particles and gas leave through one side and re-enter through the other, with no
  /// walls there. x, and z in 3D, may be periodic; y (gravity, inlet and outlet) never is.
  std::array<bool, 3> periodic{false, false, false};

  template <int Dim>
  Vec<Dim> extent() const {
    if constexpr (Dim == 2) {
      return {width, height};
    } else {
      return {width, height, depth};
    }
  }
  template <int Dim>
  PeriodicBox<Dim> periodic_box() const {
    PeriodicBox<Dim> b;
    b.length = extent<Dim>();
    for (int a = 0; a < Dim; ++a) b.on[static_cast<std::size_t>(a)] = periodic[static_cast<std::size_t>(a)];
    return b;
  }
  bool any_periodic() const { return periodic[0] || periodic[1] || periodic[2]; }
  template <int Dim>
  Vec<Dim> gravity_vector() const {
    if constexpr (Dim == 2) {
      return {gravity.x, gravity.y};
    } else {
      return gravity;
    }
  }
};

}  // namespace fluidbed
