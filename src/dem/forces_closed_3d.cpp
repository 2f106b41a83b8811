// The force pass of 3D runs in closed boxes (force_pass.hpp), in a unit of its own.
#include "dem/force_pass.hpp"

namespace fluidbed {
template double DemSolver<3>::compute_forces_on<false>(double dt);
}  // namespace fluidbed
