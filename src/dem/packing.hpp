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
  double z_min = 0.0, z_max = 0.0;  ///< 3D only
  double min_gap = 0.0002;          ///< smallest surface-to-surface gap between placed particles, m
  std::uint64_t seed = 1998;
  /// Fraction of particles per species (empty: all species 0).
  std::vector<double> species_fraction{};
};

/// How many particles `place_random` can place in the region of `cfg`.
template <int Dim>
std::int64_t random_placement_capacity(const DemConfig& dem, const PackingConfig& cfg);

/// Place `count` particles at random without overlap: each occupies a distinct, randomly chosen site of a
/// lattice of spacing (largest diameter + 2 gap; a square lattice in 2D, cubic in 3D) and is jittered at random inside its site, keeping half a gap to
/// its edges, so neighbours stay at least one gap apart. O(N), reproducible
/// for a given seed; throws a bad-input error when the particles do not fit in the region.
template <int Dim>
ParticleStore<Dim> place_random(const DemConfig& dem, const PackingConfig& cfg);

/// Height of the settled bed: the mean top of the highest particles in each of `columns` vertical strips
/// (strips across x; in 3D each spans the depth).
template <int Dim>
double bed_height(const ParticleStore<Dim>& p, double width, int columns);

}  // namespace fluidbed
