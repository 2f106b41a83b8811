#pragma once
// Bed surface from a voidage field: the top of the highest horizontal layer of cells (a row in 2D, a slab of
// constant y in 3D) that is still bed on average. Used by the bubble tracker (freeboard, eruption) and to size the
// initial bed of the cell tracers.
#include <optional>

#include "analysis/cell_view.hpp"

namespace fluidbed {

/// Highest layer j (axis 1, up) whose mean voidage is below surface_eps, or -1 when no layer is (no bed).
template <int Dim>
int bed_surface_row(const CellView<Dim>& eps, double surface_eps = 0.7);
/// Top face of bed_surface_row(), m; empty when there is no bed.
template <int Dim>
std::optional<double> bed_surface_height(const CellView<Dim>& eps, double surface_eps = 0.7);

}  // namespace fluidbed
