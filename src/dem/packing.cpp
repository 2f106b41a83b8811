#include "dem/packing.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <random>

#include "core/error.hpp"

namespace fluidbed {

namespace {

struct Lattice {
  double site;
  std::int64_t nx, ny, nz;  // nz = 1 in 2D
  std::int64_t sites() const { return std::max<std::int64_t>(nx, 0) * std::max<std::int64_t>(ny, 0) * std::max<std::int64_t>(nz, 0); }
};

template <int Dim>
Lattice placement_lattice(const DemConfig& dem, const PackingConfig& cfg) {
  double d_max = 0.0;
  for (const Species& s : dem.species) d_max = std::max(d_max, s.d_max());
  const double site = d_max + 2.0 * cfg.min_gap;  // half a gap of margin on each side, one gap of jitter
  Lattice l{site, static_cast<std::int64_t>(std::floor((cfg.x_max - cfg.x_min) / site + 1e-9)),
            static_cast<std::int64_t>(std::floor((cfg.y_max - cfg.y_min) / site + 1e-9)), 1};
  if constexpr (Dim == 3) l.nz = static_cast<std::int64_t>(std::floor((cfg.z_max - cfg.z_min) / site + 1e-9));
  return l;
}

}  // namespace

template <int Dim>
std::int64_t random_placement_capacity(const DemConfig& dem, const PackingConfig& cfg) {
  return placement_lattice<Dim>(dem, cfg).sites();
}

template <int Dim>
ParticleStore<Dim> place_random(const DemConfig& dem, const PackingConfig& cfg) {
  double d_max = 0.0;
  for (const Species& s : dem.species) d_max = std::max(d_max, s.d_max());
  const Lattice lat = placement_lattice<Dim>(dem, cfg);
  const double site = lat.site;
  const double w = cfg.x_max - cfg.x_min;
  const double h = cfg.y_max - cfg.y_min;
  const std::int64_t nx = lat.nx, ny = lat.ny;
  const std::int64_t sites = lat.sites();
  if (cfg.count > sites) {
    if constexpr (Dim == 2) {
      throw_input_error(fmt::format(
          "particles.count = {} particles of diameter {} m do not fit in the placement region {} x {} m "
          "(at most {} with a gap of {} m); make the region taller or use fewer particles",
          cfg.count, d_max, w, h, sites, cfg.min_gap));
    } else {
      throw_input_error(fmt::format(
          "particles.count = {} particles of diameter {} m do not fit in the placement region {} x {} x {} m "
          "(at most {} with a gap of {} m); make the region taller or use fewer particles",
          cfg.count, d_max, w, h, cfg.z_max - cfg.z_min, sites, cfg.min_gap));
    }
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
  // Sizes from a stream of their own, drawn in id order and only for species with a distribution: the sites and
  // jitter of a bed of fixed sizes are those of the same seed without this stream.
  std::mt19937_64 size_rng(cfg.seed ^ 0x9e3779b97f4a7c15ULL);
  auto size_uniform = [&size_rng]() { return static_cast<double>(size_rng() >> 11) * 0x1.0p-53; };
  ParticleStore<Dim> p;
  p.reserve(static_cast<std::size_t>(cfg.count));
  for (std::int64_t k = 0; k < cfg.count; ++k) {
    const std::int64_t s = site_index[static_cast<std::size_t>(k)];
    const Species& species_k = dem.species[static_cast<std::size_t>(species[static_cast<std::size_t>(k)])];
    const Species sp = species_k.sized() ? species_k.of_diameter(size_quantile(species_k.size, size_uniform()))
                                         : species_k;
    // Jitter inside the site keeping half the gap to its edges, so neighbours stay at least min_gap apart.
    const double free = site - sp.diameter - cfg.min_gap;
    const double x = cfg.x_min + (static_cast<double>(s % nx) * site) + 0.5 * cfg.min_gap + sp.radius() + uniform() * free;
    if constexpr (Dim == 2) {
      const double y = cfg.y_min + (static_cast<double>(s / nx) * site) + 0.5 * cfg.min_gap + sp.radius() + uniform() * free;
      p.add(k, species[static_cast<std::size_t>(k)], sp, {x, y});
    } else {
      const double y = cfg.y_min + (static_cast<double>((s / nx) % ny) * site) + 0.5 * cfg.min_gap + sp.radius() + uniform() * free;
      const double z = cfg.z_min + (static_cast<double>(s / (nx * ny)) * site) + 0.5 * cfg.min_gap + sp.radius() + uniform() * free;
      p.add(k, species[static_cast<std::size_t>(k)], sp, {x, y, z});
    }
  }
  return p;
}

template <int Dim>
double bed_height(const ParticleStore<Dim>& p, double width, int columns) {
  std::vector<double> top(static_cast<std::size_t>(columns), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int c = std::clamp(static_cast<int>(p.x[i] / width * columns), 0, columns - 1);
    top[static_cast<std::size_t>(c)] = std::max(top[static_cast<std::size_t>(c)], p.y[i] + p.radius[i]);
  }
  double sum = 0.0;
  for (double t : top) sum += t;
  return sum / columns;
}

template std::int64_t random_placement_capacity<2>(const DemConfig&, const PackingConfig&);
template std::int64_t random_placement_capacity<3>(const DemConfig&, const PackingConfig&);
template ParticleStore<2> place_random<2>(const DemConfig&, const PackingConfig&);
template ParticleStore<3> place_random<3>(const DemConfig&, const PackingConfig&);
template double bed_height<2>(const ParticleStore<2>&, double, int);
template double bed_height<3>(const ParticleStore<3>&, double, int);

}  // namespace fluidbed
