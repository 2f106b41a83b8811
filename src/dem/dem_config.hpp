#pragma once
// Configuration of the discrete element model; defaults are the paper's Table 1 (DEM column).
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/domain.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

/// Restitution and friction of one kind of contact (paper, Table 3 item 3: per pair, walls separate).
struct InteractionParams {
  double restitution = 0.9;
  double friction = 0.3;
};

/// Plane walls on the low and high side of each axis: x (left, right), y (bottom, top), z (back, front; 3D).
struct WallConfig {
  bool left = true;
  bool right = true;
  bool bottom = true;
  bool top = false;  ///< the paper's top is the gas outlet
  /// Without a top wall: particles whose centre crosses the top are removed and counted (an outflow), instead of
  /// failing the run.
  bool top_outflow = false;
  bool back = true;   ///< z = 0 (3D only)
  bool front = true;  ///< z = depth (3D only)
  /// The same outflow through the other sides, in Wall order (left, right, bottom, -, back, front; the top's is
  /// top_outflow): where such a side has no wall, a particle crossing it is removed and counted.
  std::array<bool, 6> side_outflow{};

  /// Side w (Wall order) lets particles out.
  bool outflow(int w) const { return w == 3 ? top_outflow : side_outflow[static_cast<std::size_t>(w)]; }

  /// The wall on side `high` (0: low, 1: high) of axis a.
  bool enabled(int axis, int high) const {
    switch (axis) {
      case 0: return high ? right : left;
      case 1: return high ? top : bottom;
      default: return high ? front : back;
    }
  }
};

/// Particles added during the run at a steady rate (a feed): each one placed at random in a box, clear of every
/// other particle, from a counter-based random stream, so that the feed depends only on the seed and the time,
/// restarts included.
struct InsertionConfig {
  double rate = 0.0;          ///< particles per second; 0: no insertion
  int species = 0;
  Vec3 region_lo{};           ///< the box the centres are drawn in, m (z used in 3D)
  Vec3 region_hi{};
  Vec3 velocity{};            ///< of every new particle, m/s
  double t_start = 0.0;       ///< s
  double t_end = std::numeric_limits<double>::infinity();  ///< s
  std::uint64_t seed = 1;
  int attempts_per_particle = 50;  ///< tries per particle per step before the rest waits for the next step

  bool enabled() const { return rate > 0.0; }
};

struct DemConfig {
  std::vector<Species> species{Species{}};
  double stiffness = 800.0;              ///< k of Eqs. 2-3, N/m
  double tangential_stiffness_ratio = 1.0;  ///< k_t / k_n (the paper uses one k for both)
  /// Restitution and friction per unordered species pair, row-major n_species x n_species (symmetric).
  std::vector<InteractionParams> pair{InteractionParams{}};
  /// Particle-wall restitution and friction per species.
  std::vector<InteractionParams> wall{InteractionParams{}};
  /// The box [0, width] x [0, height] (x [0, depth] in 3D) and gravity; the DEM reads the first Dim components.
  DomainConfig domain{};
  WallConfig walls{};
  InsertionConfig insertion{};
  double dt = 2e-4;      ///< s
  double skin = 0.0004;  ///< Verlet skin, m (0: rebuild the neighbour list every step)

  std::size_t n_species() const { return species.size(); }
  const InteractionParams& pair_params(int a, int b) const {
    return pair[static_cast<std::size_t>(a) * species.size() + static_cast<std::size_t>(b)];
  }
};

}  // namespace fluidbed
