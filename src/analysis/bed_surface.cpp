#include "analysis/bed_surface.hpp"

#include "core/error.hpp"

namespace fluidbed {

int bed_surface_row(const Grid2& grid, const Field2& eps, double surface_eps) {
  if (eps.nx != grid.nx || eps.ny != grid.ny) throw_input_error("bed surface: voidage field does not match the grid");
  for (int j = grid.ny - 1; j >= 0; --j) {
    double sum = 0.0;
    for (int i = 0; i < grid.nx; ++i) sum += eps(i, j);
    if (sum / grid.nx < surface_eps) return j;
  }
  return -1;
}

std::optional<double> bed_surface_height(const Grid2& grid, const Field2& eps, double surface_eps) {
  const int j = bed_surface_row(grid, eps, surface_eps);
  if (j < 0) return std::nullopt;
  return grid.y0 + (j + 1) * grid.dy;
}

}  // namespace fluidbed
