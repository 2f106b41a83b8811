#include "dem/packing.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <random>

#include "core/error.hpp"

namespace fluidbed {

std::int64_t random_placement_capacity(const DemConfig& dem, const PackingConfig& cfg) {
  double d_max = 0.0;
  for (const Species& s : dem.species) d_max = std::max(d_max, s.diameter);
  const double site = d_max + 2.0 * cfg.min_gap;  // half a gap of margin on each side, one gap of jitter
  const auto nx = static_cast<std::int64_t>(std::floor((cfg.x_max - cfg.x_min) / site + 1e-9));
  const auto ny = static_cast<std::int64_t>(std::floor((cfg.y_max - cfg.y_min) / site + 1e-9));
  return std::max<std::int64_t>(nx, 0) * std::max<std::int64_t>(ny, 0);
}

ParticleStore place_random(const DemConfig& dem, const PackingConfig& cfg) {
  double d_max = 0.0;
  for (const Species& s : dem.species) d_max = std::max(d_max, s.diameter);
  const double site = d_max + 2.0 * cfg.min_gap;  // half a gap of margin on each side, one gap of jitter
  const double w = cfg.x_max - cfg.x_min;
  const double h = cfg.y_max - cfg.y_min;
  const auto nx = static_cast<std::int64_t>(std::floor(w / site + 1e-9));
  const auto ny = static_cast<std::int64_t>(std::floor(h / site + 1e-9));
  const std::int64_t sites = std::max<std::int64_t>(nx, 0) * std::max<std::int64_t>(ny, 0);
  if (cfg.count > sites) {
    throw_input_error(fmt::format(
        "particles.count = {} particles of diameter {} m do not fit in the placement region {} x {} m "
        "(at most {} with a gap of {} m); make the region taller or use fewer particles",
        cfg.count, d_max, w, h, sites, cfg.min_gap));
  }
  // A seeded Mersenne twister with our own integer-to-real mapping: the same seed gives the same bed with
  // every standard library.
  std::mt19937_64 rng(cfg.seed);
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  std::vector<std::int64_t> site_index(static_cast<std::size_t>(sites));
  for (std::int64_t k = 0; k < sites; ++k) site_index[static_cast<std::size_t>(k)] = k;
  for (std::int64_t k = 0; k < cfg.count; ++k) {  // partial Fisher-Yates shuffle
    const auto r = k + static_cast<std::int64_t>(uniform() * static_cast<double>(sites - k));
    std::swap(site_index[static_cast<std::size_t>(k)], site_index[static_cast<std::size_t>(std::min(r, sites - 1))]);
  }
  // Species by fraction, assigned in id order.
  std::vector<std::int32_t> species(static_cast<std::size_t>(cfg.count), 0);
  if (!cfg.species_fraction.empty()) {
    double acc = 0.0;
    std::int64_t k = 0;
    for (std::size_t s = 0; s < cfg.species_fraction.size(); ++s) {
      acc += cfg.species_fraction[s];
      const auto end = std::min<std::int64_t>(cfg.count, std::llround(acc * static_cast<double>(cfg.count)));
      for (; k < end; ++k) species[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(s);
    }
    for (; k < cfg.count; ++k) species[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(cfg.species_fraction.size() - 1);
  }
  ParticleStore p;
  p.reserve(static_cast<std::size_t>(cfg.count));
  for (std::int64_t k = 0; k < cfg.count; ++k) {
    const std::int64_t s = site_index[static_cast<std::size_t>(k)];
    const Species& sp = dem.species[static_cast<std::size_t>(species[static_cast<std::size_t>(k)])];
    // Jitter inside the site keeping half the gap to its edges, so neighbours stay at least min_gap apart.
    const double free = site - sp.diameter - cfg.min_gap;
    const double x = cfg.x_min + (static_cast<double>(s % nx) * site) + 0.5 * cfg.min_gap + sp.radius() + uniform() * free;
    const double y = cfg.y_min + (static_cast<double>(s / nx) * site) + 0.5 * cfg.min_gap + sp.radius() + uniform() * free;
    p.add(k, species[static_cast<std::size_t>(k)], sp, {x, y});
  }
  return p;
}

double bed_height(const ParticleStore& p, double width, int columns) {
  std::vector<double> top(static_cast<std::size_t>(columns), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int c = std::clamp(static_cast<int>(p.x[i] / width * columns), 0, columns - 1);
    top[static_cast<std::size_t>(c)] = std::max(top[static_cast<std::size_t>(c)], p.y[i] + p.radius[i]);
  }
  double sum = 0.0;
  for (double t : top) sum += t;
  return sum / columns;
}

}  // namespace fluidbed
