// Anchor translation unit for the header-mostly core library; instantiates the generic types so that every
// header is compiled once on its own.
#include "core/error.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_box.hpp"
#include "core/vec.hpp"

namespace fluidbed {
template struct IndexBox<2>;
template struct IndexBox<3>;
template struct Grid<2>;
template struct Grid<3>;
template class Field<2>;
template class Field<3>;
template struct FaceFields<2>;
template struct FaceFields<3>;
}  // namespace fluidbed
