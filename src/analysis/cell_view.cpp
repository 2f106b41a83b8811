#include "analysis/cell_view.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace fluidbed {

CellView<2> cell_view(const Grid2& grid, const Field2& f, const char* name) {
  if (f.nx != grid.nx || f.ny != grid.ny || f.size() != grid.cells())
    throw_input_error(fmt::format("field {} is {}x{}, the grid {}x{}", name, f.nx, f.ny, grid.nx, grid.ny));
  return {cell_geometry(grid), f.v.data()};
}

template <int Dim>
CellView<Dim> cell_view(const CellGeometry<Dim>& geometry, const std::vector<double>& values, const char* name) {
  if (values.size() != geometry.cells())
    throw_input_error(fmt::format("field {} holds {} values, its grid {} cells", name, values.size(), geometry.cells()));
  return {geometry, values.data()};
}

template CellView<2> cell_view(const CellGeometry<2>&, const std::vector<double>&, const char*);
template CellView<3> cell_view(const CellGeometry<3>&, const std::vector<double>&, const char*);

}  // namespace fluidbed
