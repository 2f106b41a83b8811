#pragma once
// Rise velocity of an isolated bubble in a two-dimensional bed, the reference curve of the bubble report.

namespace fluidbed {

/// Constant C of U_b = C sqrt(g D) for two-dimensional (disc-like) bubbles; see docs/analysis.md for the source.
inline constexpr double rise_constant_2d = 0.5;

/// U_b = C sqrt(g D) with D the area-equivalent diameter of the 2D bubble, m; g in m/s^2.
double bubble_rise_velocity_2d(double D, double g = 9.81);

}  // namespace fluidbed
