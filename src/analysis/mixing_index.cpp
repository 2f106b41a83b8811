#include "analysis/mixing_index.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "analysis/layer_tracers.hpp"
#include "core/error.hpp"

namespace fluidbed {

LaceyResult lacey_index(std::span<const double> x, std::span<const double> y, std::span<const std::uint8_t> in_group,
                        const Grid2& domain, const MixingConfig& config) {
  if (x.size() != y.size() || x.size() != in_group.size())
    throw_input_error("lacey index: positions and colours differ in length");
  const double sdx = config.sample_dx > 0.0 ? config.sample_dx : domain.dx;
  const double sdy = config.sample_dy > 0.0 ? config.sample_dy : domain.dy;
  if (!(sdx > 0.0) || !(sdy > 0.0)) throw_input_error("lacey index: sample size must be positive");
  const int nsx = std::max(1, static_cast<int>(std::lround(domain.width() / sdx)));
  const int nsy = std::max(1, static_cast<int>(std::lround(domain.height() / sdy)));
  const Grid2 samples{nsx, nsy, domain.width() / nsx, domain.height() / nsy, domain.x0, domain.y0};

  std::vector<double> count(samples.cells(), 0.0), coloured(samples.cells(), 0.0);
  double total = 0.0, total_coloured = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const std::size_t c = samples.index(samples.cell_i(x[k]), samples.cell_j(y[k]));
    count[c] += 1.0;
    total += 1.0;
    if (in_group[k]) {
      coloured[c] += 1.0;
      total_coloured += 1.0;
    }
  }
  LaceyResult r;
  if (total == 0.0) return r;
  r.p = total_coloured / total;
  for (std::size_t c = 0; c < count.size(); ++c) {
    if (count[c] == 0.0) continue;
    ++r.samples;
    const double dc = coloured[c] / count[c] - r.p;
    // Weighted by the particles in the sample, so that a random mixture has E[S^2] = p(1-p)/n exactly.
    r.s2 += count[c] * dc * dc;
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

std::vector<LaceyResult> lacey_index_per_group(std::span<const double> x, std::span<const double> y,
                                               std::span<const std::int32_t> group, int n_groups, const Grid2& domain,
                                               const MixingConfig& config) {
  if (group.size() != x.size()) throw_input_error("lacey index: positions and colours differ in length");
  std::vector<LaceyResult> out;
  std::vector<std::uint8_t> in(group.size());
  for (int g = 0; g < n_groups; ++g) {
    for (std::size_t k = 0; k < group.size(); ++k) in[k] = group[k] == g ? 1 : 0;
    out.push_back(lacey_index(x, y, in, domain, config));
  }
  return out;
}

LaceyResult lacey_index(const ParticleStore<2>& particles, int split_layer, const Grid2& domain,
                        const MixingConfig& config) {
  std::vector<std::uint8_t> lower(particles.size());
  for (std::size_t k = 0; k < particles.size(); ++k) lower[k] = particles.layer[k] < split_layer ? 1 : 0;
  return lacey_index(particles.x, particles.y, lower, domain, config);
}

LaceyResult lacey_index(const CellTracers& tracers, int split_layer, const Grid2& domain, const MixingConfig& config) {
  std::vector<std::uint8_t> lower(tracers.size());
  for (std::size_t k = 0; k < tracers.size(); ++k) lower[k] = tracers.layer[k] < split_layer ? 1 : 0;
  return lacey_index(tracers.x, tracers.y, lower, domain, config);
}

}  // namespace fluidbed
