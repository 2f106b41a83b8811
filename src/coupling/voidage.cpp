#include "coupling/voidage.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed {

CellWeights cell_weights(const Grid2& g, VoidageMethod method, double x, double y) {
  CellWeights cw;
  if (method == VoidageMethod::Centre) {
    cw.cell[0] = g.index(g.cell_i(x), g.cell_j(y));
    cw.w[0] = 1.0;
    cw.count = 1;
    return cw;
  }
  // Bilinear weights between the four surrounding cell centres; an index outside the grid is clamped, which
  // folds the weight of the missing ghost cell into the boundary cell.
  const double fx = (x - g.x0) / g.dx - 0.5;
  const double fy = (y - g.y0) / g.dy - 0.5;
  const double ffx = std::floor(fx), ffy = std::floor(fy);
  const double ax = std::clamp(fx - ffx, 0.0, 1.0), ay = std::clamp(fy - ffy, 0.0, 1.0);
  const int i0 = static_cast<int>(ffx), j0 = static_cast<int>(ffy);
  const int ia = std::clamp(i0, 0, g.nx - 1), ib = std::clamp(i0 + 1, 0, g.nx - 1);
  const int ja = std::clamp(j0, 0, g.ny - 1), jb = std::clamp(j0 + 1, 0, g.ny - 1);
  cw.cell = {g.index(ia, ja), g.index(ib, ja), g.index(ia, jb), g.index(ib, jb)};
  cw.w = {(1.0 - ax) * (1.0 - ay), ax * (1.0 - ay), (1.0 - ax) * ay, ax * ay};
  cw.count = 4;
  return cw;
}

double gather(const Field2& f, const CellWeights& cw) {
  double s = 0.0;
  for (int k = 0; k < cw.count; ++k) s += cw.w[static_cast<std::size_t>(k)] * f.v[cw.cell[static_cast<std::size_t>(k)]];
  return s;
}

void particle_cell_weights(const ParticleStore<2>& p, const Grid2& g, VoidageMethod method,
                           std::vector<CellWeights>& out) {
  out.resize(p.size());
  const auto n = static_cast<std::ptrdiff_t>(p.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    out[i] = cell_weights(g, method, p.x[i], p.y[i]);
  }
}

// The scatters below run serially in storage order: a fixed order makes the sums independent of the thread
// count, and they cost little next to the contact forces.
void compute_voidage(const ParticleStore<2>& p, const std::vector<CellWeights>& weights, const Grid2& g, double depth,
                     Field2& eps) {
  if (eps.nx != g.nx || eps.ny != g.ny) eps = Field2(g.nx, g.ny);
  std::vector<double> vol(g.cells(), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double vp = 4.0 / 3.0 * M_PI * p.radius[i] * p.radius[i] * p.radius[i];
    const CellWeights& cw = weights[i];
    for (int k = 0; k < cw.count; ++k) vol[cw.cell[static_cast<std::size_t>(k)]] += cw.w[static_cast<std::size_t>(k)] * vp;
  }
  const double vcell = g.dx * g.dy * depth;
  for (std::size_t c = 0; c < g.cells(); ++c) eps.v[c] = 1.0 - vol[c] / vcell;
}

void compute_voidage(const ParticleStore<2>& p, const Grid2& g, VoidageMethod method, double depth, Field2& eps) {
  std::vector<CellWeights> w;
  particle_cell_weights(p, g, method, w);
  compute_voidage(p, w, g, depth, eps);
}

void cell_solids_velocity(const ParticleStore<2>& p, const std::vector<CellWeights>& weights, const Grid2& g,
                          Field2& us, Field2& vs) {
  if (us.nx != g.nx || us.ny != g.ny) us = Field2(g.nx, g.ny);
  if (vs.nx != g.nx || vs.ny != g.ny) vs = Field2(g.nx, g.ny);
  std::vector<double> vol(g.cells(), 0.0), mu(g.cells(), 0.0), mv(g.cells(), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double vp = p.radius[i] * p.radius[i] * p.radius[i];  // constant factor cancels
    const CellWeights& cw = weights[i];
    for (int k = 0; k < cw.count; ++k) {
      const std::size_t c = cw.cell[static_cast<std::size_t>(k)];
      const double w = cw.w[static_cast<std::size_t>(k)] * vp;
      vol[c] += w;
      mu[c] += w * p.vx[i];
      mv[c] += w * p.vy[i];
    }
  }
  for (std::size_t c = 0; c < g.cells(); ++c) {
    us.v[c] = vol[c] > 0.0 ? mu[c] / vol[c] : 0.0;
    vs.v[c] = vol[c] > 0.0 ? mv[c] / vol[c] : 0.0;
  }
}

void cell_solids_velocity(const ParticleStore<2>& p, const Grid2& g, VoidageMethod method, Field2& us, Field2& vs) {
  std::vector<CellWeights> w;
  particle_cell_weights(p, g, method, w);
  cell_solids_velocity(p, w, g, us, vs);
}

}  // namespace fluidbed
