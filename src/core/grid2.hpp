#pragma once
// Geometry of a uniform Cartesian 2D grid: cell (i, j) spans [x0 + i dx, x0 + (i+1) dx) x [y0 + j dy, ...).
// The 2D grid without ghost layers used by the two-fluid model; the dimension-generic Grid<Dim> (core/grid.hpp)
// carries the owned block and ghost layers of a sub-domain.
#include <cstddef>
#include <algorithm>
#include <cmath>

#include "core/grid.hpp"
#include "core/vec2.hpp"

namespace fluidbed {

struct Grid2 {
  int nx = 0;
  int ny = 0;
  double dx = 0.0;
  double dy = 0.0;
  double x0 = 0.0;
  double y0 = 0.0;

  static Grid2 uniform(double width, double height, int nx_, int ny_) {
    return Grid2{nx_, ny_, width / nx_, height / ny_, 0.0, 0.0};
  }

  double width() const { return nx * dx; }
  double height() const { return ny * dy; }
  std::size_t cells() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
  /// Row-major cell index, i fastest.
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i);
  }
  double xc(int i) const { return x0 + (i + 0.5) * dx; }
  double yc(int j) const { return y0 + (j + 0.5) * dy; }
  Vec2 centre(int i, int j) const { return {xc(i), yc(j)}; }
  /// Cell column holding x, clamped to the grid.
  int cell_i(double x) const { return std::clamp(static_cast<int>(std::floor((x - x0) / dx)), 0, nx - 1); }
  int cell_j(double y) const { return std::clamp(static_cast<int>(std::floor((y - y0) / dy)), 0, ny - 1); }
};

/// The generic grid of a Grid2 (owned block = domain, one ghost layer), and back: for the modules that are still 2D
/// only (the two-fluid model) to share the generic solvers and kernels.
inline Grid<2> to_grid(const Grid2& g) {
  Grid<2> out = Grid<2>::uniform({g.width(), g.height()}, {g.nx, g.ny});
  out.h = {g.dx, g.dy};
  out.origin = {g.x0, g.y0};
  return out;
}
inline Grid2 to_grid2(const Grid<2>& g) { return Grid2{g.n(0), g.n(1), g.h[0], g.h[1], g.origin[0], g.origin[1]}; }

}  // namespace fluidbed
