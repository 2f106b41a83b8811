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

void assign_layers(ParticleStore<2>& particles, int n_layers, double bed_height) {
  if (n_layers < 1) throw_input_error(fmt::format("number of tracer layers must be at least 1, got {}", n_layers));
  if (!(bed_height > 0.0)) throw_input_error(fmt::format("layer bed height must be positive, got {}", bed_height));
  particles.layer.resize(particles.size());
  for (std::size_t k = 0; k < particles.size(); ++k)
    particles.layer[k] = layer_of(particles.y[k], 0.0, bed_height, n_layers);
}

CellTracers::CellTracers(const Grid2& grid, double bed_height, int n_layers) : grid_(grid) {
  if (n_layers < 1) throw_input_error(fmt::format("number of tracer layers must be at least 1, got {}", n_layers));
  if (!(bed_height > 0.0)) throw_input_error(fmt::format("tracer bed height must be positive, got {}", bed_height));
  std::int64_t next = 0;
  for (int j = 0; j < grid.ny; ++j) {
    if (grid.yc(j) >= grid.y0 + bed_height) break;
    for (int i = 0; i < grid.nx; ++i) {
      id.push_back(next++);
      x.push_back(grid.xc(i));
      y.push_back(grid.yc(j));
      layer.push_back(layer_of(grid.yc(j), grid.y0, bed_height, n_layers));
    }
  }
}

CellTracers::CellTracers(const Grid2& grid, std::vector<std::int64_t> ids, std::vector<double> xs,
                         std::vector<double> ys, std::vector<std::int32_t> layers)
    : id(std::move(ids)), x(std::move(xs)), y(std::move(ys)), layer(std::move(layers)), grid_(grid) {
  if (x.size() != id.size() || y.size() != id.size() || layer.size() != id.size()) {
    throw_input_error(fmt::format("cell tracers: {} ids, {} x, {} y and {} layers", id.size(), x.size(), y.size(),
                                  layer.size()));
  }
  const double x_hi = grid_.x0 + grid_.width(), y_hi = grid_.y0 + grid_.height();
  for (std::size_t k = 0; k < id.size(); ++k) {
    if (!(x[k] >= grid_.x0 && x[k] <= x_hi && y[k] >= grid_.y0 && y[k] <= y_hi)) {
      throw_input_error(fmt::format("cell tracers: ball {} at ({}, {}) m lies outside the grid", id[k], x[k], y[k]));
    }
  }
}

void CellTracers::advance(const Field2& us, const Field2& vs, double dt) {
  if (us.nx != grid_.nx || us.ny != grid_.ny || vs.nx != grid_.nx || vs.ny != grid_.ny)
    throw_input_error("cell tracers: solids velocity field does not match the tracer grid");
  const double x_lo = grid_.x0, x_hi = grid_.x0 + grid_.width();
  const double y_lo = grid_.y0, y_hi = grid_.y0 + grid_.height();
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(x.size());
  // A serial loop: one ball per cell is ~10^3 balls, far too little work to share between threads.
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const int i = grid_.cell_i(x[k]);
    const int j = grid_.cell_j(y[k]);
    // Paper, Section 3 (Fig. 4b/c): the ball takes the solids velocity of the cell it is in, no collisions.
    x[k] = std::clamp(x[k] + us(i, j) * dt, x_lo, x_hi);
    y[k] = std::clamp(y[k] + vs(i, j) * dt, y_lo, y_hi);
  }
}

std::string tracer_csv(const CellTracers& tracers) {
  std::string out = "ball_id,x,y,layer\n";
  for (std::size_t k = 0; k < tracers.size(); ++k)
    out += fmt::format("{},{},{},{}\n", tracers.id[k], tracers.x[k], tracers.y[k], tracers.layer[k]);
  return out;
}

}  // namespace fluidbed
