#pragma once
// Initial particle placement: the paper's random, non-overlapping placement in the domain (section 2.1.1),
// before settling under gravity in vacuum.
#include <cstdint>
#include <vector>

#include "dem/dem_config.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

struct PackingConfig {
  std::int64_t count = 22000;
  double x_min = 0.0, x_max = 0.6;  ///< placement region, m
  double y_min = 0.0, y_max = 1.0;
  double min_gap = 0.0002;          ///< smallest surface-to-surface gap between placed particles, m
  std::uint64_t seed = 1998;
  /// Fraction of particles per species (empty: all species 0).
  std::vector<double> species_fraction{};
};

/// How many particles `place_random` can place in the region of `cfg`.
std::int64_t random_placement_capacity(const DemConfig& dem, const PackingConfig& cfg);

/// Place `count` particles at random without overlap: each occupies a distinct, randomly chosen site of a
/// lattice of spacing (largest diameter + 2 gap) and is jittered at random inside its site, keeping half a gap to
/// its edges, so neighbours stay at least one gap apart. O(N), reproducible
/// for a given seed; throws a bad-input error when the particles do not fit in the region.
ParticleStore place_random(const DemConfig& dem, const PackingConfig& cfg);

/// Height of the settled bed: the mean top of the highest particles in each of `columns` vertical strips.
double bed_height(const ParticleStore& p, double width, int columns);

}  // namespace fluidbed
