#include "dem/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace fluidbed {

namespace {

/// Cells covering the particles' bounding box, with a CSR of the slots in each cell (ascending slot order).
struct CellBins {
  double x_min = 0.0, y_min = 0.0, size = 1.0;
  int nx = 1, ny = 1;
  std::vector<std::uint32_t> cell_of;  // per particle
  std::vector<std::size_t> start;      // per cell + 1
  std::vector<std::uint32_t> slots;    // particle slots grouped by cell
  // Copies of x, y, r in the order of `slots`: a row of three neighbouring cells is one contiguous run, so the
  // search streams through memory whatever the storage order of the particles.
  std::vector<double> xs, ys, rs;

  // Clamp before the conversion: a far (or non-finite) coordinate must not overflow the int.
  int ci(double x) const { const double f = (x - x_min) / size; return f > 0.0 ? static_cast<int>(std::min(f, nx - 1.0)) : 0; }
  int cj(double y) const { const double f = (y - y_min) / size; return f > 0.0 ? static_cast<int>(std::min(f, ny - 1.0)) : 0; }
};

CellBins bin_particles(const ParticleStore& p, double cell_size) {
  CellBins b;
  const std::size_t n = p.size();
  b.size = cell_size;
  if (n == 0) {
    b.start.assign(2, 0);
    return b;
  }
  const auto [xmin, xmax] = std::minmax_element(p.x.begin(), p.x.end());
  const auto [ymin, ymax] = std::minmax_element(p.y.begin(), p.y.end());
  b.x_min = *xmin;
  b.y_min = *ymin;
  // Cap the grid so a stray far-away particle cannot make it huge; clamping keeps the search correct
  // because a clamped edge cell is at least as large as the others.
  const double max_cells = 4.0 * static_cast<double>(n) + 16.0;
  b.nx = std::max(1, static_cast<int>(std::min((*xmax - b.x_min) / cell_size + 1.0, max_cells)));
  b.ny = std::max(1, static_cast<int>(std::min((*ymax - b.y_min) / cell_size + 1.0, max_cells / b.nx + 1.0)));
  const std::size_t ncell = static_cast<std::size_t>(b.nx) * static_cast<std::size_t>(b.ny);
  b.cell_of.resize(n);
  b.start.assign(ncell + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<std::uint32_t>(static_cast<std::size_t>(b.cj(p.y[i])) * b.nx + b.ci(p.x[i]));
    b.cell_of[i] = c;
    ++b.start[c + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) b.start[c + 1] += b.start[c];
  b.slots.resize(n);
  std::vector<std::size_t> fill(b.start.begin(), b.start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) b.slots[fill[b.cell_of[i]]++] = static_cast<std::uint32_t>(i);
  return b;
}

void add_cell_ordered_copies(const ParticleStore& p, CellBins& b) {
  const std::size_t n = b.slots.size();
  b.xs.resize(n);
  b.ys.resize(n);
  b.rs.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = b.slots[k];
    b.xs[k] = p.x[i];
    b.ys[k] = p.y[i];
    b.rs[k] = p.radius[i];
  }
}

/// Appends to `out`, from position `used`, every particle j != i within r_i + r_j + skin of particle i, in a
/// fixed order (cell rows bottom to top, within a row by cell and then by slot); returns the new `used`. The
/// candidates are written unconditionally and kept by advancing the end, which avoids a hard-to-predict branch
/// (about a third of the candidates of a 3 x 3 cell search are in reach).
std::size_t append_near(const ParticleStore& p, const CellBins& b, std::size_t i, double skin,
                        std::vector<std::uint32_t>& out, std::size_t used) {
  const double x = p.x[i], y = p.y[i], r = p.radius[i] + skin;
  const int ci = b.ci(x);
  const int cj = b.cj(y);
  // A clamped edge cell may hold particles farther than one cell size away: widen the search there.
  const int di_lo = (ci == 0) ? 0 : -1, di_hi = (ci == b.nx - 1) ? 0 : 1;
  const int dj_lo = (cj == 0) ? 0 : -1, dj_hi = (cj == b.ny - 1) ? 0 : 1;
  const auto self = static_cast<std::uint32_t>(i);
  for (int dj = dj_lo; dj <= dj_hi; ++dj) {
    const std::size_t row = static_cast<std::size_t>(cj + dj) * static_cast<std::size_t>(b.nx);
    const std::size_t k_begin = b.start[row + static_cast<std::size_t>(ci + di_lo)];
    const std::size_t k_end = b.start[row + static_cast<std::size_t>(ci + di_hi) + 1];
    if (out.size() < used + (k_end - k_begin)) out.resize(2 * (used + (k_end - k_begin)));
    std::uint32_t* dst = out.data();
    for (std::size_t k = k_begin; k < k_end; ++k) {
      const double dx = b.xs[k] - x;
      const double dy = b.ys[k] - y;
      const double reach = r + b.rs[k];
      dst[used] = b.slots[k];
      used += static_cast<std::size_t>((dx * dx + dy * dy < reach * reach) & (b.slots[k] != self));
    }
  }
  return used;
}

}  // namespace

std::vector<std::size_t> sort_by_cell(const ParticleStore& p, double cell_size) {
  const CellBins b = bin_particles(p, cell_size);
  return {b.slots.begin(), b.slots.end()};
}

void build_neighbor_list(const ParticleStore& p, double cell_size, double skin, NeighborList& out) {
  const std::size_t n = p.size();
  CellBins b = bin_particles(p, cell_size);
  add_cell_ordered_copies(p, b);
  out.offset.assign(n + 1, 0);
  // One search pass: each thread fills its own buffer for a contiguous block of particles, and the blocks are
  // joined in block order, so the list is the same for any number of threads.
#ifdef _OPENMP
  const int max_threads = omp_get_max_threads();
#else
  const int max_threads = 1;
#endif
  std::vector<std::vector<std::uint32_t>> found(static_cast<std::size_t>(max_threads));
  std::vector<std::size_t> block(static_cast<std::size_t>(max_threads) + 1, n);
  block[0] = 0;
#pragma omp parallel num_threads(max_threads)
  {
#ifdef _OPENMP
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto nt = static_cast<std::size_t>(omp_get_num_threads());
#else
    const std::size_t t = 0, nt = 1;
#endif
    const std::size_t lo = n * t / nt, hi = n * (t + 1) / nt;
    block[t + 1] = hi;
    std::vector<std::uint32_t>& mine = found[t];
    mine.resize((hi - lo) * 8 + 64);
    std::size_t used = 0;
    for (std::size_t i = lo; i < hi; ++i) {
      const std::size_t before = used;
      used = append_near(p, b, i, skin, mine, used);
      out.offset[i + 1] = used - before;
    }
    mine.resize(used);
  }
  for (std::size_t i = 0; i < n; ++i) out.offset[i + 1] += out.offset[i];
  out.partner.resize(out.offset[n]);
  out.history.assign(out.offset[n], Vec2{});
  for (std::size_t t = 0; t < found.size(); ++t) {
    if (block[t] < block[t + 1]) std::copy(found[t].begin(), found[t].end(), out.partner.begin() + static_cast<std::ptrdiff_t>(out.offset[block[t]]));
  }
}

std::vector<std::pair<std::int64_t, std::int64_t>> brute_force_contacts(const ParticleStore& p, double skin) {
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double dx = p.x[j] - p.x[i];
      const double dy = p.y[j] - p.y[i];
      const double reach = p.radius[i] + p.radius[j] + skin;
      if (dx * dx + dy * dy < reach * reach) pairs.emplace_back(std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace fluidbed
