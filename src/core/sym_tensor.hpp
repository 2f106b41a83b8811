#pragma once
// Dimension-generic symmetric second-order tensor (a strain rate, a stress): Dim diagonal and Dim(Dim-1)/2
// off-diagonal components, indexed by axis pair so that kernels written per axis can fill it.
#include <array>

namespace fluidbed {

/// Symmetric Dim x Dim tensor; in 2D the out-of-plane components are zero (plane strain) and not stored.
template <int Dim>
struct SymTensor {
  static_assert(Dim == 2 || Dim == 3, "SymTensor<Dim>: Dim is 2 or 3");
  static constexpr int dim = Dim;
  std::array<double, Dim> diag{};                ///< xx, yy[, zz]
  std::array<double, Dim*(Dim - 1) / 2> off{};   ///< xy[, xz, yz]

  /// Storage slot of the off-diagonal pair (a, b), a != b: xy 0, xz 1, yz 2.
  static constexpr int off_index(int a, int b) { return a + b - 1; }
  constexpr double& operator()(int a, int b) { return a == b ? diag[a] : off[off_index(a, b)]; }
  constexpr double operator()(int a, int b) const { return a == b ? diag[a] : off[off_index(a, b)]; }
};

/// tr(D).
template <int Dim>
constexpr double trace(const SymTensor<Dim>& d) {
  double s = d.diag[0];
  for (int a = 1; a < Dim; ++a) s += d.diag[a];
  return s;
}

/// D:D = tr(D . D).
template <int Dim>
constexpr double double_dot(const SymTensor<Dim>& d) {
  double s = d.diag[0] * d.diag[0];
  for (int a = 1; a < Dim; ++a) s += d.diag[a] * d.diag[a];
  double o = d.off[0] * d.off[0];
  for (int k = 1; k < static_cast<int>(d.off.size()); ++k) o += d.off[k] * d.off[k];
  return s + 2.0 * o;
}

}  // namespace fluidbed
