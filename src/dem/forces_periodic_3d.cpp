// The force pass of 3D runs with periodic axes (force_pass.hpp), in a unit of its own.
#include "dem/force_pass.hpp"

namespace fluidbed {
template double DemSolver<3>::compute_forces_on<true>(double dt);
}  // namespace fluidbed
