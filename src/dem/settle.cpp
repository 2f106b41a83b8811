#include "dem/settle.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed {

template <int Dim>
SettleResult settle_bed(DemSolver<Dim>& dem, double energy_per_particle, double max_time) {
  SettleResult r;
  ParticleStore<Dim>& p = dem.particles();
  // Over every rank (the energy is summed over all of them, exactly, so the verdict is the same on each).
  const double n = std::max<double>(1.0, static_cast<double>(dem.total_particles()));
  const double dt = dem.config().dt;
  const auto check_every = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(0.01 / dt)));
  const auto max_steps = static_cast<std::uint64_t>(std::ceil(max_time / dt));
  std::uint64_t k = 0;
  // Do not stop in the first 0.1 s: particles placed at rest have no kinetic energy before they fall.
  const auto min_steps = static_cast<std::uint64_t>(std::ceil(0.1 / dt));
  while (k < max_steps) {
    dem.step();
    ++k;
    if (k % check_every == 0 && k >= min_steps) {
      r.kinetic_energy_per_particle = dem.kinetic_energy() / n;
      if (r.kinetic_energy_per_particle < energy_per_particle) {
        r.converged = true;
        break;
      }
    }
  }
  r.time = static_cast<double>(k) * dt;
  r.steps = k;
  r.kinetic_energy_per_particle = dem.kinetic_energy() / n;
  for (int a = 0; a < Dim; ++a) std::fill(p.velocity(a).begin(), p.velocity(a).end(), 0.0);
  for (int c = 0; c < kSpinComponents<Dim>; ++c) std::fill(p.spin_component(c).begin(), p.spin_component(c).end(), 0.0);
  dem.set_time(0.0, 0);
  return r;
}

template SettleResult settle_bed<2>(DemSolver<2>&, double, double);
template SettleResult settle_bed<3>(DemSolver<3>&, double, double);

}  // namespace fluidbed
