#pragma once
// Bed surface from a voidage field: the top of the highest row that is still bed on average. Used by the bubble
// tracker (freeboard, eruption) and to size the initial bed of the cell tracers.
#include <optional>

#include "core/field2.hpp"
#include "core/grid2.hpp"

namespace fluidbed {

/// Highest row j whose mean voidage is below surface_eps, or -1 when no row is (no bed).
int bed_surface_row(const Grid2& grid, const Field2& eps, double surface_eps = 0.7);

/// Top face of bed_surface_row(), m; empty when there is no bed.
std::optional<double> bed_surface_height(const Grid2& grid, const Field2& eps, double surface_eps = 0.7);

}  // namespace fluidbed
