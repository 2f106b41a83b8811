#pragma once
// A read-only view of a particle set as plain arrays, one per component, for the writers (VTK, CSV, HDF5) in either
// dimension: the 2D store and the 3D one are both seen through it, so the writers do not depend on how a store
// keeps its attributes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace fluidbed {

struct ParticleArrays {
  int dimension = 2;
  std::span<const std::int64_t> id;
  std::array<std::span<const double>, 3> x{};      ///< centre per axis, m (x[2] empty in 2D)
  std::array<std::span<const double>, 3> v{};      ///< velocity per axis, m/s (v[2] empty in 2D)
  /// Spin per axis, rad/s, right-handed; in 2D only omega[2] (about z, anticlockwise positive) is set.
  std::array<std::span<const double>, 3> omega{};
  std::span<const double> radius;       ///< m; may be empty for a writer that does not need it
  std::span<const std::int32_t> species;
  std::span<const std::int32_t> layer;  ///< initial colour layer; may be empty (written as 0)
  /// The particles have their own sizes (not all their species' diameter): the particle CSV then carries a
  /// diameter column (from `radius`), so that the file restores them.
  bool own_sizes = false;

  std::size_t size() const { return id.size(); }
  /// Storage slots in increasing id order (ties in storage order).
  std::vector<std::size_t> order_by_id() const;
};

/// The view of a particle store with members id, species, layer, radius, x, y, vx, vy and, for a 2D store, omega
/// (spin about z), for a 3D one z, vz, omega_x, omega_y, omega_z (vectors of one value per particle). The store
/// must outlive the view.
template <class Store>
ParticleArrays particle_arrays(const Store& s) {
  ParticleArrays a;
  a.id = s.id;
  a.x[0] = s.x;
  a.x[1] = s.y;
  a.v[0] = s.vx;
  a.v[1] = s.vy;
  if constexpr (requires { s.z; }) {
    a.dimension = 3;
    a.x[2] = s.z;
    a.v[2] = s.vz;
    a.omega[0] = s.omega_x;
    a.omega[1] = s.omega_y;
    a.omega[2] = s.omega_z;
  } else {
    a.dimension = 2;
    a.omega[2] = s.omega;
  }
  a.radius = s.radius;
  a.species = s.species;
  a.layer = s.layer;
  return a;
}

}  // namespace fluidbed
