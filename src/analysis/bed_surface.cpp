#include "analysis/bed_surface.hpp"

#include "core/error.hpp"

namespace fluidbed {

template <int Dim>
int bed_surface_row(const CellView<Dim>& eps, double surface_eps) {
  const CellGeometry<Dim>& g = eps.geometry;
  const int nx = g.n[0], ny = g.n[1];
  const int nz = Dim == 3 ? g.n[Dim - 1] : 1;
  const std::size_t layer = static_cast<std::size_t>(nx) * static_cast<std::size_t>(nz);
  for (int j = ny - 1; j >= 0; --j) {
    double sum = 0.0;
    for (int k = 0; k < nz; ++k) {
      for (int i = 0; i < nx; ++i) {
        Index<Dim> c{};
        c[0] = i;
        c[1] = j;
        if constexpr (Dim == 3) c[2] = k;
        sum += eps[c];
      }
    }
    if (sum / static_cast<double>(layer) < surface_eps) return j;
  }
  return -1;
}

template <int Dim>
std::optional<double> bed_surface_height(const CellView<Dim>& eps, double surface_eps) {
  const int j = bed_surface_row(eps, surface_eps);
  if (j < 0) return std::nullopt;
  return eps.geometry.face(1, j + 1);
}

template int bed_surface_row(const CellView<2>&, double);
template int bed_surface_row(const CellView<3>&, double);
template std::optional<double> bed_surface_height(const CellView<2>&, double);
template std::optional<double> bed_surface_height(const CellView<3>&, double);

}  // namespace fluidbed
