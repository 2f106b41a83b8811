#pragma once
// Time-averaged cell fields over a window (issue 15, item 4): voidage, gas velocity, solids velocity weighted two
// ways, granular temperature. Sums of samples of plain cell-centred fields (and, for CFD-DEM, of the particles), so
// the CFD-DEM and the two-fluid model, 2D and 3D share it. docs/analysis.md ("Time averages").
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "analysis/cell_view.hpp"

namespace fluidbed {

/// The window of the case's [averages] section.
struct AveragesConfig {
  bool enabled = false;   ///< set by the loader when the section gives t_end > t_start
  double t_start = 0.0;   ///< s, first sample
  double t_end = 0.0;     ///< s, last sample
  double interval = 0.0;  ///< s between samples; 0: after every model step in the window
};

/// One sample's cell-centred fields (geometry.cells() values each, axis 0 fastest). `us` and `theta` may be null
/// (no solids velocity field; no kinetic-theory temperature).
template <int Dim>
struct AverageFields {
  CellGeometry<Dim> geometry;
  const double* eps = nullptr;
  std::array<const double*, Dim> ug{};
  std::array<const double*, Dim> us{};
  const double* theta = nullptr;  ///< TFM granular temperature, m^2/s^2
};

/// The particles of one sample (CFD-DEM), for the granular temperature. `order`: the order in which they are
/// visited (ascending id, so the sums do not depend on how the store is sorted); empty visits storage order.
template <int Dim>
struct AverageParticles {
  std::array<std::span<const double>, Dim> x{};  ///< centre per axis, m
  std::array<std::span<const double>, Dim> v{};  ///< velocity per axis, m/s
  std::span<const double> radius;                ///< m
  std::span<const std::size_t> order;
};

/// Granular temperature of the particles about their cell mean in one sample (CFD-DEM): for every cell, with the
/// particles whose centre lies in it and weights w = their volume, Theta = (1/Dim) sum_a sum_i w_i (v_ia - V_a)^2 /
/// sum_i w_i with V the weighted cell mean: the 1/Dim trace of the velocity-fluctuation tensor, kinetic theory's
/// Theta = <C.C> / Dim of the fluctuation C about the local mean (in 3D Theta = <C^2> / 3, Gidaspow 1994). `theta` and `weight` (sum of w, m^3; 0 where the
/// cell holds fewer than two particles, whose theta is then 0) get one value per cell.
template <int Dim>
void particle_granular_temperature(const CellGeometry<Dim>& g, const AverageParticles<Dim>& p,
                                   std::vector<double>& theta, std::vector<double>& weight);

/// Running sums of samples and the averages they give. Per cell:
/// - voidage and gas velocity: the plain time mean (each sample counts the same, the cell's own value, as a
///   probe fixed in space records it);
/// - solids velocity, cell-weighted (`solids_velocity_cell`): the plain time mean over the samples in which the
///   cell holds solids (eps < 1), the Eulerian mean of the local solids velocity;
/// - solids velocity, particle-weighted (`solids_velocity_particle`): sum_t eps_s us / sum_t eps_s, eps_s = 1 - eps:
///   weighted by the solids volume in the cell, so by the mass for one solids density, the mean over every particle
///   that passed, as particle tracking (PEPT) and PIV of the particles measure it;
/// - granular temperature: sum_t w Theta / sum_t w, weighted by the solids volume: TFM its Theta with w = eps_s,
///   CFD-DEM particle_granular_temperature() with w its weight.
template <int Dim>
class TimeAverage {
 public:
  explicit TimeAverage(const CellGeometry<Dim>& geometry);

  /// Add one sample. `particles` (CFD-DEM) gives the granular temperature; else fields.theta does, if set.
  /// The fields must be on this average's geometry.
  void add(const AverageFields<Dim>& fields, const AverageParticles<Dim>* particles = nullptr);

  std::int64_t samples() const { return samples_; }
  const CellGeometry<Dim>& geometry() const { return geometry_; }

  /// The averages, one value per cell; NaN where undefined (no sample; no solids; no temperature sample).
  std::vector<double> voidage() const;
  std::array<std::vector<double>, Dim> gas_velocity() const;
  std::array<std::vector<double>, Dim> solids_velocity_cell() const;
  std::array<std::vector<double>, Dim> solids_velocity_particle() const;
  std::vector<double> granular_temperature() const;
  /// Fraction of the samples in which the cell held solids.
  std::vector<double> solids_presence() const;

  /// Everything the next sample depends on, as flat arrays (the checkpoint): restore(state()) continues bit for bit.
  struct State {
    std::int64_t samples = 0;
    std::vector<double> sums;  ///< kSums blocks of geometry.cells() values, in the order of the members below
  };
  State state() const;
  /// Throws std::invalid_argument when the state is not of this geometry.
  void restore(const State& s);

 private:
  // Blocks of the flat state: eps, ug[Dim], solids count, us[Dim], eps_s, eps_s us[Dim], theta weight, w theta.
  static constexpr int kSums = 1 + Dim + 1 + Dim + 1 + Dim + 2;
  std::vector<double>& block(int b) { return sums_[static_cast<std::size_t>(b)]; }
  const std::vector<double>& block(int b) const { return sums_[static_cast<std::size_t>(b)]; }

  CellGeometry<Dim> geometry_;
  std::int64_t samples_ = 0;
  std::array<std::vector<double>, kSums> sums_;
  std::vector<double> theta_, weight_;  // scratch of one sample
};

}  // namespace fluidbed
