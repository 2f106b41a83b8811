#pragma once
// Checkpoint datasets by component name, for either dimension: a vector attribute is stored as one dataset per
// axis ("x", "y", "z"; "vx", "vy", "vz"; "omega_x", ...), a field as its stored values with its box, so that a
// model's save() and load() are a few calls and a reader names the dataset that does not fit.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/field.hpp"
#include "io/hdf5_file.hpp"
#include "io/particle_arrays.hpp"

namespace fluidbed {

/// Per-axis dataset names of a vector attribute: axis_names<3>("v") = {"vx", "vy", "vz"},
/// axis_names<3>("omega_") = {"omega_x", "omega_y", "omega_z"}, axis_names<2>("") = {"x", "y"}.
template <int Dim>
std::array<std::string, Dim> axis_names(const std::string& prefix) {
  static constexpr const char* axes[] = {"x", "y", "z"};
  std::array<std::string, Dim> out;
  for (int a = 0; a < Dim; ++a) out[static_cast<std::size_t>(a)] = prefix + axes[a];
  return out;
}

/// One named dataset of doubles.
struct NamedComponent {
  std::string name;
  std::span<const double> values;
};

/// Write each component as `group/name` (the group is created when missing).
void write_components(Hdf5File& file, const std::string& group, const std::vector<NamedComponent>& components);

/// Read `group/name` for each name, each of exactly `count` values. Throws Error(BadInput, "<file>: group/name has
/// N values, M expected") or the reader's error for a missing dataset.
std::vector<std::vector<double>> read_components(const Hdf5File& file, const std::string& group,
                                                 const std::vector<std::string>& names, std::size_t count);

/// A field's stored values (ghost layers included, so that a restart needs no boundary pass to be bit-identical)
/// as dataset `name`, with attributes dimension, ghost, lo0, hi0, lo1, hi1[, lo2, hi2] (its box).
template <int Dim>
void write_field(Hdf5File& file, const std::string& name, const Field<Dim>& field);

/// Read dataset `name` into `field`, whose box and ghost width must be those written (else Error(BadInput)
/// naming the dataset and both shapes).
template <int Dim>
void read_field(const Hdf5File& file, const std::string& name, Field<Dim>& field);

/// The particle arrays as datasets of `group`: id (int64), species, layer (int32), the centre per axis (x, y[, z]),
/// the velocity (vx, vy[, vz]) and the spin: omega in 2D (the names of today's 2D checkpoints), omega_x, omega_y,
/// omega_z in 3D. The radius is not written (it follows from the species). The group is created when missing.
void write_particle_arrays(Hdf5File& file, const std::string& group, const ParticleArrays& particles);

/// What read_particle_arrays gives back: owned arrays of one dimension (2D: x[2], v[2], omega[0..1] empty).
struct ParticleArraysData {
  int dimension = 2;
  std::vector<std::int64_t> id;
  std::vector<std::int32_t> species, layer;
  std::array<std::vector<double>, 3> x, v, omega;
  /// A view of these arrays (radius empty).
  ParticleArrays view() const;
};

/// Read the datasets write_particle_arrays writes for `dimension`; every array must have as many values as `id`.
ParticleArraysData read_particle_arrays(const Hdf5File& file, const std::string& group, int dimension);

}  // namespace fluidbed
