#pragma once
// Rise velocity of an isolated bubble in a fluidized bed, U_b = C sqrt(g D), the reference curve of the bubble
// report: the constant differs between a two-dimensional (disc-like) bed and a three-dimensional one.
#include <vector>

namespace fluidbed {

/// C of U_b = C sqrt(g D) for two-dimensional bubbles, D the area-equivalent diameter; docs/analysis.md gives the
/// source.
inline constexpr double rise_constant_2d = 0.5;
/// C for three-dimensional (spherical-cap) bubbles, D the sphere-equivalent diameter: Davidson and Harrison (1963).
inline constexpr double rise_constant_3d = 0.711;

/// The constant for a bed of dimension Dim.
template <int Dim>
constexpr double rise_constant() {
  static_assert(Dim == 2 || Dim == 3);
  return Dim == 2 ? rise_constant_2d : rise_constant_3d;
}

/// U_b = C sqrt(g D) with D the area-equivalent diameter of the 2D bubble, m; g in m/s^2.
double bubble_rise_velocity_2d(double D, double g = 9.81);
/// U_b = 0.711 sqrt(g D) with D the sphere-equivalent diameter (6 V / pi)^(1/3) of the 3D bubble, m.
double bubble_rise_velocity_3d(double D, double g = 9.81);
/// The one of the two for a bed of dimension 2 or 3; throws Error(BadInput) for another dimension.
double bubble_rise_velocity(int dimension, double D, double g = 9.81);

/// Rise velocity from heights h[k] at times t[k]: the least-squares slope, exact for a point moving at constant
/// speed and the backward difference for two samples; 0 when the times do not differ.
double rise_slope(const std::vector<double>& t, const std::vector<double>& h);

}  // namespace fluidbed
