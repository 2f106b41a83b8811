#include "analysis/mixing_index.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "analysis/layer_tracers.hpp"
#include "core/error.hpp"

namespace fluidbed {

template <int Dim>
LaceyCounts<Dim> lacey_counts(const std::array<std::span<const double>, Dim>& pos, std::span<const std::uint8_t> in_group,
                              const CellGeometry<Dim>& domain, const MixingConfig& config) {
  for (const auto& p : pos) {
    if (p.size() != in_group.size()) throw_input_error("lacey index: positions and colours differ in length");
  }
  const std::array<double, 3> wanted{config.sample_dx, config.sample_dy, config.sample_dz};
  LaceyCounts<Dim> out;
  CellGeometry<Dim>& samples = out.samples;
  for (int a = 0; a < Dim; ++a) {
    const double sd = wanted[static_cast<std::size_t>(a)] > 0.0 ? wanted[static_cast<std::size_t>(a)] : domain.h[a];
    if (!(sd > 0.0)) throw_input_error("lacey index: sample size must be positive");
    samples.n[a] = std::max(1, static_cast<int>(std::lround(domain.length(a) / sd)));
    samples.h[a] = domain.length(a) / samples.n[a];
    samples.origin[a] = domain.origin[a];
  }
  out.count.assign(samples.cells(), 0);
  out.coloured.assign(samples.cells(), 0);
  for (std::size_t k = 0; k < in_group.size(); ++k) {
    Index<Dim> cell{};
    for (int a = 0; a < Dim; ++a) cell[a] = samples.cell(a, pos[static_cast<std::size_t>(a)][k]);
    const std::size_t c = samples.index(cell);
    ++out.count[c];
    if (in_group[k]) ++out.coloured[c];
  }
  return out;
}

template <int Dim>
LaceyResult lacey_from_counts(const LaceyCounts<Dim>& counts) {
  double total = 0.0, total_coloured = 0.0;
  for (std::size_t c = 0; c < counts.count.size(); ++c) {
    total += static_cast<double>(counts.count[c]);
    total_coloured += static_cast<double>(counts.coloured[c]);
  }
  LaceyResult r;
  if (total == 0.0) return r;
  r.p = total_coloured / total;
  for (std::size_t c = 0; c < counts.count.size(); ++c) {
    if (counts.count[c] == 0) continue;
    ++r.samples;
    const double n = static_cast<double>(counts.count[c]);
    const double dc = static_cast<double>(counts.coloured[c]) / n - r.p;
    // Weighted by the particles in the sample, so that a random mixture has E[S^2] = p(1-p)/n exactly.
    r.s2 += n * dc * dc;
  }
  r.s2 /= total;
  r.mean_per_sample = total / r.samples;
  r.s0_2 = r.p * (1.0 - r.p);
  r.sr_2 = r.s0_2 / r.mean_per_sample;
  // Lacey (1954): M = (S0^2 - S^2) / (S0^2 - SR^2).
  const double den = r.s0_2 - r.sr_2;
  r.valid = den > 0.0;
  r.index = r.valid ? (r.s0_2 - r.s2) / den : 0.0;
  return r;
}

template <int Dim>
LaceyResult lacey_index(const std::array<std::span<const double>, Dim>& pos, std::span<const std::uint8_t> in_group,
                        const CellGeometry<Dim>& domain, const MixingConfig& config) {
  return lacey_from_counts(lacey_counts<Dim>(pos, in_group, domain, config));
}

template <int Dim>
std::vector<LaceyResult> lacey_index_per_group(const std::array<std::span<const double>, Dim>& pos,
                                               std::span<const std::int32_t> group, int n_groups,
                                               const CellGeometry<Dim>& domain, const MixingConfig& config) {
  for (const auto& p : pos) {
    if (p.size() != group.size()) throw_input_error("lacey index: positions and colours differ in length");
  }
  std::vector<LaceyResult> out;
  std::vector<std::uint8_t> in(group.size());
  for (int g = 0; g < n_groups; ++g) {
    for (std::size_t k = 0; k < group.size(); ++k) in[k] = group[k] == g ? 1 : 0;
    out.push_back(lacey_index<Dim>(pos, in, domain, config));
  }
  return out;
}

namespace {

// Lower part (layer < split_layer) against the rest, for any set with size(), layer[] and coord(axis): the tracer
// balls and the DEM particles alike.
template <int Dim, class Layered>
LaceyResult lacey_of_layers(const Layered& set, int split_layer, const CellGeometry<Dim>& domain,
                            const MixingConfig& config) {
  std::vector<std::uint8_t> lower(set.size());
  for (std::size_t k = 0; k < set.size(); ++k) lower[k] = set.layer[k] < split_layer ? 1 : 0;
  std::array<std::span<const double>, Dim> pos;
  for (int a = 0; a < Dim; ++a) pos[static_cast<std::size_t>(a)] = set.coord(a);
  return lacey_index<Dim>(pos, lower, domain, config);
}

}  // namespace

template <int Dim>
LaceyResult lacey_index(const BallTracers<Dim>& tracers, int split_layer, const CellGeometry<Dim>& domain,
                        const MixingConfig& config) {
  return lacey_of_layers<Dim>(tracers, split_layer, domain, config);
}

template <int Dim>
LaceyResult lacey_index(const ParticleStore<Dim>& particles, int split_layer, const CellGeometry<Dim>& domain,
                        const MixingConfig& config) {
  return lacey_of_layers<Dim>(particles, split_layer, domain, config);
}

template <int Dim>
LaceyCounts<Dim> lacey_counts(const ParticleStore<Dim>& particles, std::size_t first_n, int split_layer,
                              const CellGeometry<Dim>& domain, const MixingConfig& config) {
  std::vector<std::uint8_t> lower(first_n);
  for (std::size_t k = 0; k < first_n; ++k) lower[k] = particles.layer[k] < split_layer ? 1 : 0;
  std::array<std::span<const double>, Dim> pos;
  for (int a = 0; a < Dim; ++a) pos[static_cast<std::size_t>(a)] = std::span<const double>(particles.coord(a)).first(first_n);
  return lacey_counts<Dim>(pos, lower, domain, config);
}

template LaceyResult lacey_index<2>(const std::array<std::span<const double>, 2>&, std::span<const std::uint8_t>,
                                    const CellGeometry<2>&, const MixingConfig&);
template LaceyResult lacey_index<3>(const std::array<std::span<const double>, 3>&, std::span<const std::uint8_t>,
                                    const CellGeometry<3>&, const MixingConfig&);
template std::vector<LaceyResult> lacey_index_per_group<2>(const std::array<std::span<const double>, 2>&,
                                                           std::span<const std::int32_t>, int, const CellGeometry<2>&,
                                                           const MixingConfig&);
template std::vector<LaceyResult> lacey_index_per_group<3>(const std::array<std::span<const double>, 3>&,
                                                           std::span<const std::int32_t>, int, const CellGeometry<3>&,
                                                           const MixingConfig&);
template LaceyResult lacey_index<2>(const BallTracers<2>&, int, const CellGeometry<2>&, const MixingConfig&);
template LaceyResult lacey_index<3>(const BallTracers<3>&, int, const CellGeometry<3>&, const MixingConfig&);

template LaceyResult lacey_index<2>(const ParticleStore<2>&, int, const CellGeometry<2>&, const MixingConfig&);
template LaceyCounts<2> lacey_counts<2>(const ParticleStore<2>&, std::size_t, int, const CellGeometry<2>&, const MixingConfig&);
template LaceyCounts<3> lacey_counts<3>(const ParticleStore<3>&, std::size_t, int, const CellGeometry<3>&, const MixingConfig&);
template LaceyResult lacey_from_counts<2>(const LaceyCounts<2>&);
template LaceyResult lacey_from_counts<3>(const LaceyCounts<3>&);
template LaceyResult lacey_index<3>(const ParticleStore<3>&, int, const CellGeometry<3>&, const MixingConfig&);

}  // namespace fluidbed
