#include "analysis/cell_view.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace fluidbed {

template <int Dim>
CellView<Dim> cell_view(const Grid<Dim>& grid, const Field<Dim>& f, const char* name) {
  if (f.box() != grid.owned || f.ghost() != 0) {
    throw_input_error(fmt::format("field {} is not a ghost-free cell field on the grid's {} cells", name, grid.owned.count()));
  }
  return {cell_geometry(grid), f.data().data()};
}

template <int Dim>
CellView<Dim> cell_view(const CellGeometry<Dim>& geometry, const std::vector<double>& values, const char* name) {
  if (values.size() != geometry.cells())
    throw_input_error(fmt::format("field {} holds {} values, its grid {} cells", name, values.size(), geometry.cells()));
  return {geometry, values.data()};
}

template CellView<2> cell_view(const CellGeometry<2>&, const std::vector<double>&, const char*);
template CellView<3> cell_view(const CellGeometry<3>&, const std::vector<double>&, const char*);
template CellView<2> cell_view(const Grid<2>&, const Field<2>&, const char*);
template CellView<3> cell_view(const Grid<3>&, const Field<3>&, const char*);

}  // namespace fluidbed
