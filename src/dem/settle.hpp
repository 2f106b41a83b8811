#pragma once
// The paper's initial condition: particles placed at random fall under gravity in vacuum until settled.
#include <cstdint>

#include "dem/dem_solver.hpp"

namespace fluidbed {

struct SettleResult {
  double time = 0.0;                        ///< simulated settling time, s
  std::uint64_t steps = 0;                  ///< DEM steps taken
  double kinetic_energy_per_particle = 0.0; ///< at the end, J
  bool converged = false;
};

/// Step `dem` (no gas) until the mean kinetic energy per particle is below `energy_per_particle` (checked every
/// 0.01 s of simulated time) or `max_time` has passed. Velocities are then zeroed: the bed starts at rest.
template <int Dim>
SettleResult settle_bed(DemSolver<Dim>& dem, double energy_per_particle, double max_time);

}  // namespace fluidbed
