#include "analysis/layer_tracers.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fluidbed {

int layer_of(double y, double y_bottom, double bed_height, int n_layers) {
  const double thickness = bed_height / n_layers;
  const int l = static_cast<int>(std::floor((y - y_bottom) / thickness));
  return std::clamp(l, 0, n_layers - 1);
}

void assign_layers(std::span<const double> y, std::span<std::int32_t> layer, int n_layers, double bed_height) {
  if (n_layers < 1) throw_input_error(fmt::format("number of tracer layers must be at least 1, got {}", n_layers));
  if (!(bed_height > 0.0)) throw_input_error(fmt::format("layer bed height must be positive, got {}", bed_height));
  if (y.size() != layer.size())
    throw_input_error(fmt::format("assign layers: {} heights for {} layers", y.size(), layer.size()));
  for (std::size_t k = 0; k < y.size(); ++k) layer[k] = layer_of(y[k], 0.0, bed_height, n_layers);
}

template <int Dim>
void assign_layers(ParticleStore<Dim>& particles, int n_layers, double bed_height) {
  if (n_layers < 1) throw_input_error(fmt::format("number of tracer layers must be at least 1, got {}", n_layers));
  if (!(bed_height > 0.0)) throw_input_error(fmt::format("layer bed height must be positive, got {}", bed_height));
  particles.layer.resize(particles.size());
  assign_layers(particles.y, particles.layer, n_layers, bed_height);
}

template <int Dim>
BallTracers<Dim>::BallTracers(const CellGeometry<Dim>& grid, double bed_height, int n_layers) : geometry_(grid) {
  if (n_layers < 1) throw_input_error(fmt::format("number of tracer layers must be at least 1, got {}", n_layers));
  if (!(bed_height > 0.0)) throw_input_error(fmt::format("tracer bed height must be positive, got {}", bed_height));
  const double top = grid.origin[1] + bed_height;
  std::int64_t next = 0;
  for (std::size_t k = 0; k < grid.cells(); ++k) {
    const Index<Dim> c = grid.cell_of(k);
    const double yc = grid.centre(1, c[1]);
    if (yc >= top) continue;
    id.push_back(next++);
    for (int a = 0; a < Dim; ++a) coord(a).push_back(grid.centre(a, c[a]));
    layer.push_back(layer_of(yc, grid.origin[1], bed_height, n_layers));
  }
}

template <int Dim>
BallTracers<Dim>::BallTracers(const CellGeometry<Dim>& grid, std::vector<std::int64_t> ids,
                              std::array<std::vector<double>, Dim> pos, std::vector<std::int32_t> layers)
    : id(std::move(ids)), layer(std::move(layers)), geometry_(grid) {
  for (int a = 0; a < Dim; ++a) coord(a) = std::move(pos[static_cast<std::size_t>(a)]);
  bool same = layer.size() == id.size();
  for (int a = 0; a < Dim; ++a) same = same && coord(a).size() == id.size();
  if (!same) {
    if constexpr (Dim == 2) {
      throw_input_error(fmt::format("cell tracers: {} ids, {} x, {} y and {} layers", id.size(), x.size(), y.size(),
                                    layer.size()));
    } else {
      throw_input_error(fmt::format("cell tracers: {} ids, {} x, {} y, {} z and {} layers", id.size(), x.size(),
                                    y.size(), z.size(), layer.size()));
    }
  }
  for (std::size_t k = 0; k < id.size(); ++k) {
    bool inside = true;
    for (int a = 0; a < Dim; ++a) {
      const double v = coord(a)[k];
      inside = inside && v >= grid.origin[a] && v <= grid.origin[a] + grid.length(a);
    }
    if (inside) continue;
    if constexpr (Dim == 2) {
      throw_input_error(fmt::format("cell tracers: ball {} at ({}, {}) m lies outside the grid", id[k], x[k], y[k]));
    } else {
      throw_input_error(
          fmt::format("cell tracers: ball {} at ({}, {}, {}) m lies outside the grid", id[k], x[k], y[k], z[k]));
    }
  }
}

template <int Dim>
void BallTracers<Dim>::advance(const std::array<CellView<Dim>, Dim>& velocity, double dt) {
  for (const CellView<Dim>& v : velocity) {
    if (v.geometry.n != geometry_.n)
      throw_input_error("cell tracers: solids velocity field does not match the tracer grid");
  }
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(x.size());
  // A serial loop: one ball per cell is ~10^3 balls in 2D, far too little work to share between threads.
  for (std::ptrdiff_t b = 0; b < n; ++b) {
    const std::size_t k = static_cast<std::size_t>(b);
    Index<Dim> c{};
    for (int a = 0; a < Dim; ++a) c[a] = geometry_.cell(a, coord(a)[k]);
    // Paper, Section 3 (Fig. 4b/c): the ball takes the solids velocity of the cell it is in, no collisions.
    for (int a = 0; a < Dim; ++a) {
      const double lo = geometry_.origin[a], hi = geometry_.origin[a] + geometry_.length(a);
      const double moved = coord(a)[k] + velocity[static_cast<std::size_t>(a)][c] * dt;
      if (periodic_[static_cast<std::size_t>(a)]) {
        const double L = hi - lo;
        double w = moved - L * std::floor((moved - lo) / L);
        if (w >= hi) w -= L;  // rounding of a tiny negative offset up to the period
        coord(a)[k] = w;
      } else {
        coord(a)[k] = std::clamp(moved, lo, hi);
      }
    }
  }
}

template void assign_layers(ParticleStore<2>&, int, double);
template void assign_layers(ParticleStore<3>&, int, double);
template class BallTracers<2>;
template class BallTracers<3>;

}  // namespace fluidbed
