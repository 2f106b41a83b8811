#pragma once
// Lacey mixing index of coloured particles or tracer balls, on a grid of sample cells of a chosen size, in 2D
// (sample rectangles) or 3D (sample boxes).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "analysis/cell_view.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

template <int Dim>
class BallTracers;

/// Sample cells: the domain cut into cells of about sample_dx x sample_dy (x sample_dz in 3D); 0: the grid's cell
/// size along that axis.
struct MixingConfig {
  double sample_dx = 0.0;  ///< m
  double sample_dy = 0.0;  ///< m
  double sample_dz = 0.0;  ///< m, 3D only
};

struct LaceyResult {
  double index = 0.0;            ///< M = (S0^2 - S^2) / (S0^2 - SR^2); 0 segregated, 1 random
  double s2 = 0.0;               ///< S^2, particle-weighted variance of the sample concentration
  double s0_2 = 0.0;             ///< p (1 - p)
  double sr_2 = 0.0;             ///< p (1 - p) / n
  double p = 0.0;                ///< overall fraction in the group
  double mean_per_sample = 0.0;  ///< n, particles per occupied sample
  int samples = 0;               ///< occupied sample cells
  bool valid = false;            ///< false when the index is undefined (one colour only, n <= 1, no particles)
};

/// The particles of a sample cell and those of them in the group, per sample cell of the sampling grid: the
/// part of the index that adds up over any split of the particles (integers), so that the index of particles spread
/// over ranks is that of all of them.
template <int Dim>
struct LaceyCounts {
  CellGeometry<Dim> samples;
  std::vector<std::int64_t> count, coloured;
};
template <int Dim>
LaceyCounts<Dim> lacey_counts(const std::array<std::span<const double>, Dim>& pos, std::span<const std::uint8_t> in_group,
                              const CellGeometry<Dim>& domain, const MixingConfig& config);
template <int Dim>
LaceyResult lacey_from_counts(const LaceyCounts<Dim>& counts);
/// The counts of the first `first_n` particles of a store (the owned ones of a rank), lower part of the bed
/// (layer < split_layer) against the rest.
template <int Dim>
LaceyCounts<Dim> lacey_counts(const ParticleStore<Dim>& particles, std::size_t first_n, int split_layer,
                              const CellGeometry<Dim>& domain, const MixingConfig& config);

/// Lacey index of the two-colour mixture in_group != 0 vs == 0 at positions pos[a][k] (axis a, particle k), over
/// the box of `domain`.
template <int Dim>
LaceyResult lacey_index(const std::array<std::span<const double>, Dim>& pos, std::span<const std::uint8_t> in_group,
                        const CellGeometry<Dim>& domain, const MixingConfig& config);
/// More than two colours: the index of each group g in [0, n_groups) against all the others, in group order.
template <int Dim>
std::vector<LaceyResult> lacey_index_per_group(const std::array<std::span<const double>, Dim>& pos,
                                               std::span<const std::int32_t> group, int n_groups,
                                               const CellGeometry<Dim>& domain, const MixingConfig& config);
/// Lower part (layer < split_layer) vs upper part of the initial bed, for the tracer balls of either dimension.
template <int Dim>
LaceyResult lacey_index(const BallTracers<Dim>& tracers, int split_layer, const CellGeometry<Dim>& domain,
                        const MixingConfig& config);

/// Lower part (layer < split_layer) vs upper part of the initial bed, for DEM particles.
template <int Dim>
LaceyResult lacey_index(const ParticleStore<Dim>& particles, int split_layer, const CellGeometry<Dim>& domain,
                        const MixingConfig& config);

}  // namespace fluidbed
