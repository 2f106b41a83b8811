#pragma once
// What the analysis reads of a model's grid and fields: cell counts, sizes and origin per axis, and cell-centred
// values as one contiguous array, axis 0 fastest (the layout of Field<Dim>::interior()). With
// nothing else from the models, the same analysis serves 2D and 3D, CFD-DEM and TFM.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_box.hpp"

namespace fluidbed {

/// A uniform Cartesian block of cells: cell c spans origin + c h to origin + (c + 1) h along every axis.
template <int Dim>
struct CellGeometry {
  Index<Dim> n{};                    ///< cells per axis
  std::array<double, Dim> h{};       ///< cell size per axis, m
  std::array<double, Dim> origin{};  ///< low corner, m

  std::size_t cells() const {
    std::size_t c = 1;
    for (int a = 0; a < Dim; ++a) c *= static_cast<std::size_t>(n[a]);
    return c;
  }
  /// Storage index of cell c, axis 0 fastest.
  std::size_t index(const Index<Dim>& c) const {
    std::size_t k = static_cast<std::size_t>(c[Dim - 1]);
    for (int a = Dim - 2; a >= 0; --a) k = k * static_cast<std::size_t>(n[a]) + static_cast<std::size_t>(c[a]);
    return k;
  }
  /// The cell of storage index k.
  Index<Dim> cell_of(std::size_t k) const {
    Index<Dim> c{};
    for (int a = 0; a < Dim; ++a) {
      c[a] = static_cast<int>(k % static_cast<std::size_t>(n[a]));
      k /= static_cast<std::size_t>(n[a]);
    }
    return c;
  }
  double centre(int a, int i) const { return origin[a] + (i + 0.5) * h[a]; }
  /// Position of the low face of cell i along axis a.
  double face(int a, int i) const { return origin[a] + i * h[a]; }
  double length(int a) const { return n[a] * h[a]; }
  /// Area of a cell in 2D, volume in 3D.
  double cell_measure() const {
    double m = h[0];
    for (int a = 1; a < Dim; ++a) m *= h[a];
    return m;
  }
  /// Cell along axis a holding x, clamped to the block.
  int cell(int a, double x) const {
    return std::clamp(static_cast<int>(std::floor((x - origin[a]) / h[a])), 0, n[a] - 1);
  }
};

/// Cell-centred values over a CellGeometry; the view does not own them.
template <int Dim>
struct CellView {
  CellGeometry<Dim> geometry;
  const double* values = nullptr;  ///< geometry.cells() values, axis 0 fastest

  double operator[](const Index<Dim>& c) const { return values[geometry.index(c)]; }
  double at(std::size_t k) const { return values[k]; }
};

/// The owned block of a Grid<Dim>: the cells whose values Field<Dim>::interior() returns.
template <int Dim>
CellGeometry<Dim> cell_geometry(const Grid<Dim>& g) {
  CellGeometry<Dim> c;
  for (int a = 0; a < Dim; ++a) {
    c.n[a] = g.owned.extent(a);
    c.h[a] = g.h[a];
    c.origin[a] = g.face(a, g.owned.lo[a]);
  }
  return c;
}

/// A view of a ghost-free cell field on the grid's owned block (its stored values are the interior's, in order);
/// throws Error(BadInput) when the field is on another box or has ghost layers.
template <int Dim>
CellView<Dim> cell_view(const Grid<Dim>& grid, const Field<Dim>& f, const char* name);

/// A view of contiguous values (for example Field<Dim>::interior()); throws Error(BadInput) when the count differs.
template <int Dim>
CellView<Dim> cell_view(const CellGeometry<Dim>& geometry, const std::vector<double>& values, const char* name);

}  // namespace fluidbed
