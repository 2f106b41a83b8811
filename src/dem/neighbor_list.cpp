#include "dem/neighbor_list.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <omp.h>
#include <span>
#include <string>

#include "core/error.hpp"
#include "core/team.hpp"
#include "dem/growth.hpp"

namespace fluidbed {

namespace {

/// Cells covering the particles' bounding box, with a CSR of the slots in each cell (ascending slot order).
template <int Dim>
struct CellBins {
  std::array<double, Dim> lo{};
  double size = 1.0;
  std::array<int, Dim> n{};
  std::vector<std::uint32_t> cell_of;  // per particle
  std::vector<std::size_t> start;      // per cell + 1
  std::vector<std::uint32_t> slots;    // particle slots grouped by cell
  // Copies of the coordinates and radii in the order of `slots`: a row of three neighbouring cells is one
  // contiguous run, so the search streams through memory whatever the storage order of the particles.
  std::array<std::vector<double>, Dim> xs;
  std::vector<double> rs;

  // Clamp before the conversion: a far (or non-finite) coordinate must not overflow the int.
  int cell(int a, double x) const {
    const double f = (x - lo[a]) / size;
    return f > 0.0 ? static_cast<int>(std::min(f, n[a] - 1.0)) : 0;
  }
  /// Row-major cell number, x fastest.
  std::size_t flat(const std::array<int, Dim>& c) const {
    std::size_t k = static_cast<std::size_t>(c[Dim - 1]);
    for (int a = Dim - 2; a >= 0; --a) k = k * static_cast<std::size_t>(n[a]) + static_cast<std::size_t>(c[a]);
    return k;
  }
};

/// The points a search bins: the particles themselves or, on periodic axes, the particles and their images.
template <int Dim>
using Coords = std::array<const std::vector<double>*, Dim>;

template <int Dim>
Coords<Dim> coords_of(const ParticleStore<Dim>& p) {
  Coords<Dim> c;
  for (int a = 0; a < Dim; ++a) c[static_cast<std::size_t>(a)] = &p.coord(a);
  return c;
}

template <int Dim>
CellBins<Dim> bin_points(const Coords<Dim>& xs, double cell_size) {
  CellBins<Dim> b;
  const std::size_t np = xs[0]->size();
  b.size = cell_size;
  b.n.fill(1);
  if (np == 0) {
    b.start.assign(2, 0);
    return b;
  }
  // Cap the grid so a stray far-away particle cannot make it huge; clamping keeps the search correct
  // because a clamped edge cell is at least as large as the others.
  const double max_cells = 4.0 * static_cast<double>(np) + 16.0;
  double cells_below = 1.0;  // cells of the axes before this one
  for (int a = 0; a < Dim; ++a) {
    const std::vector<double>& x = *xs[static_cast<std::size_t>(a)];
    const auto [mn, mx] = std::minmax_element(x.begin(), x.end());
    // On the lattice of the order keys (DemSolver::assign_order_keys: cells from the origin), so that a search by
    // cell rows meets the partners that have kept their cells in canonical order already.
    b.lo[a] = std::floor(*mn / cell_size) * cell_size;
    const double cap = a == 0 ? max_cells : max_cells / cells_below + 1.0;
    b.n[a] = std::max(1, static_cast<int>(std::min((*mx - b.lo[a]) / cell_size + 1.0, cap)));
    cells_below *= b.n[a];
  }
  std::size_t ncell = 1;
  for (int a = 0; a < Dim; ++a) ncell *= static_cast<std::size_t>(b.n[a]);
  b.cell_of.resize(np);
  b.start.assign(ncell + 1, 0);
  for (std::size_t i = 0; i < np; ++i) {
    std::array<int, Dim> c;
    for (int a = 0; a < Dim; ++a) c[a] = b.cell(a, (*xs[static_cast<std::size_t>(a)])[i]);
    const auto k = static_cast<std::uint32_t>(b.flat(c));
    b.cell_of[i] = k;
    ++b.start[k + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) b.start[c + 1] += b.start[c];
  b.slots.resize(np);
  std::vector<std::size_t> fill(b.start.begin(), b.start.end() - 1);
  for (std::size_t i = 0; i < np; ++i) b.slots[fill[b.cell_of[i]]++] = static_cast<std::uint32_t>(i);
  return b;
}

template <int Dim>
CellBins<Dim> bin_particles(const ParticleStore<Dim>& p, double cell_size) {
  return bin_points<Dim>(coords_of(p), cell_size);
}

template <int Dim>
void add_cell_ordered_copies(const ParticleStore<Dim>& p, CellBins<Dim>& b) {
  const std::size_t n = b.slots.size();
  for (int a = 0; a < Dim; ++a) b.xs[a].resize(n);
  b.rs.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = b.slots[k];
    for (int a = 0; a < Dim; ++a) b.xs[a][k] = p.coord(a)[i];
    b.rs[k] = p.radius[i];
  }
}

/// The particles and, for each one within `reach` of a periodic side, its images shifted by a period across that
/// side (and across both sides of a corner in 3D); owner[q] is the particle slot point q stands for.
template <int Dim>
struct ImagePoints {
  std::array<std::vector<double>, Dim> x;
  std::vector<std::uint32_t> owner;
};

template <int Dim>
ImagePoints<Dim> with_images(const ParticleStore<Dim>& p, const PeriodicBox<Dim>& box, double reach) {
  ImagePoints<Dim> q;
  const std::size_t n = p.size();
  for (int a = 0; a < Dim; ++a) q.x[a].assign(p.coord(a).begin(), p.coord(a).end());
  q.owner.resize(n);
  for (std::size_t i = 0; i < n; ++i) q.owner[i] = static_cast<std::uint32_t>(i);
  for (std::size_t i = 0; i < n; ++i) {
    // Shift -1, 0 or +1 period per periodic axis: a particle near the low side is seen again beyond the high one.
    std::array<int, Dim> lo{}, hi{};
    for (int a = 0; a < Dim; ++a) {
      if (!box.periodic(a)) continue;
      const double x = p.coord(a)[i];
      if (x < reach) hi[a] = 1;
      if (x >= box.length[a] - reach) lo[a] = -1;
    }
    std::array<int, Dim> s = lo;
    while (true) {
      bool self = true;
      for (int a = 0; a < Dim; ++a) self = self && s[a] == 0;
      if (!self) {
        for (int a = 0; a < Dim; ++a) q.x[a].push_back(p.coord(a)[i] + s[a] * box.length[a]);
        q.owner.push_back(static_cast<std::uint32_t>(i));
      }
      int a = 0;
      while (a < Dim && s[a] == hi[a]) {
        s[a] = lo[a];
        ++a;
      }
      if (a == Dim) break;
      ++s[a];
    }
  }
  return q;
}

/// Bins of the particles and their periodic images; the slots name the particles the points stand for, so the
/// search finds a partner across a periodic side by its own slot.
template <int Dim>
CellBins<Dim> bin_with_images(const ParticleStore<Dim>& p, const PeriodicBox<Dim>& box, double cell_size) {
  const ImagePoints<Dim> q = with_images(p, box, cell_size);
  Coords<Dim> c;
  for (int a = 0; a < Dim; ++a) c[static_cast<std::size_t>(a)] = &q.x[a];
  CellBins<Dim> b = bin_points<Dim>(c, cell_size);
  const std::size_t n = b.slots.size();
  for (int a = 0; a < Dim; ++a) b.xs[a].resize(n);
  b.rs.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t pt = b.slots[k];
    for (int a = 0; a < Dim; ++a) b.xs[a][k] = q.x[a][pt];
    b.slots[k] = q.owner[pt];
    b.rs[k] = p.radius[b.slots[k]];
  }
  return b;
}

/// Appends to `out`, from position `used`, every particle j != i within r_i + r_j + skin of particle i, in a
/// fixed order (cell rows by z, then y, then within a row by cell and then by slot); returns the new `used`. The
/// candidates are written unconditionally and kept by advancing the end, which avoids a hard-to-predict branch
/// (about a third of the candidates of a 3 x 3 cell search are in reach).
template <int Dim>
std::size_t append_near(const ParticleStore<Dim>& p, const CellBins<Dim>& b, std::size_t i, double skin,
                        std::vector<std::uint32_t>& out, std::size_t used) {
  std::array<double, Dim> x;
  std::array<int, Dim> c, d_lo, d_hi;
  for (int a = 0; a < Dim; ++a) {
    x[a] = p.coord(a)[i];
    c[a] = b.cell(a, x[a]);
    // A clamped edge cell may hold particles farther than one cell size away: widen the search there.
    d_lo[a] = (c[a] == 0) ? 0 : -1;
    d_hi[a] = (c[a] == b.n[a] - 1) ? 0 : 1;
  }
  // (r_i + r_j) + skin, the same sum seen from either partner: a pair is in both lists or in neither.
  const double ri = p.radius[i];
  const auto self = static_cast<std::uint32_t>(i);
  auto row = [&](std::array<int, Dim> rc) {
    rc[0] = c[0] + d_lo[0];
    const std::size_t k_begin = b.start[b.flat(rc)];
    rc[0] = c[0] + d_hi[0];
    const std::size_t k_end = b.start[b.flat(rc) + 1];
    if (out.size() < used + (k_end - k_begin)) resize_with_room(out, used + (k_end - k_begin) + 64);
    std::uint32_t* dst = out.data();
    const double* xs = b.xs[0].data();
    const double* ys = b.xs[1].data();
    const double* zs = b.xs[Dim - 1].data();
    const double* rs = b.rs.data();
    const std::uint32_t* slots = b.slots.data();
    for (std::size_t k = k_begin; k < k_end; ++k) {
      const double dx = xs[k] - x[0];
      const double dy = ys[k] - x[1];
      double d2 = dx * dx + dy * dy;
      if constexpr (Dim == 3) {
        const double dz = zs[k] - x[2];
        d2 += dz * dz;
      }
      const double reach = (ri + rs[k]) + skin;
      dst[used] = slots[k];
      used += static_cast<std::size_t>((d2 < reach * reach) & (slots[k] != self));
    }
  };
  if constexpr (Dim == 2) {
    for (int dj = d_lo[1]; dj <= d_hi[1]; ++dj) row({c[0], c[1] + dj});
  } else {
    for (int dk = d_lo[2]; dk <= d_hi[2]; ++dk) {
      for (int dj = d_lo[1]; dj <= d_hi[1]; ++dj) row({c[0], c[1] + dj, c[2] + dk});
    }
  }
  return used;
}

}  // namespace

template <int Dim>
std::vector<std::size_t> sort_by_cell(const ParticleStore<Dim>& p, double cell_size) {
  const CellBins<Dim> b = bin_particles(p, cell_size);
  return {b.slots.begin(), b.slots.end()};
}

template <int Dim>
void build_neighbor_list(const ParticleStore<Dim>& p, double cell_size, double skin, NeighborList<Dim>& out) {
  NeighborScratch scratch;
  build_neighbor_list(p, cell_size, skin, out, scratch);
}

template <int Dim>
void build_neighbor_list(const ParticleStore<Dim>& p, double cell_size, double skin, NeighborList<Dim>& out,
                         NeighborScratch& scratch) {
  build_neighbor_list(p, cell_size, skin, out, scratch, PeriodicBox<Dim>{});
}

template <int Dim>
void build_neighbor_list(const ParticleStore<Dim>& p, double cell_size, double skin, NeighborList<Dim>& out,
                         NeighborScratch& scratch, const PeriodicBox<Dim>& periodic) {
  build_neighbor_list(p, p.size(), cell_size, skin, out, scratch, periodic, {});
  out.history.assign(out.entries(), Vec<Dim>{});
}

namespace {
/// Each particle's entries in the canonical order of the partners (rank[j]: partner j's place in it; empty: the
/// slots are in that order): the order its contact forces are summed in, the same on any storage order and any
/// split of the particles among ranks.
template <int Dim>
void sort_entries_by_rank(NeighborList<Dim>& out, std::span<const std::uint32_t> rank) {
  const std::size_t n = out.offset.size() - 1;
  std::uint32_t* partner = out.partner.data();
  const auto sn = static_cast<std::ptrdiff_t>(n);
  if (rank.empty()) {
    // Slots in canonical order: sort the slots themselves (no table to look up).
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      std::uint32_t* e = partner + out.offset[i];
      const std::size_t m = out.offset[i + 1] - out.offset[i];
      for (std::size_t q = 1; q < m; ++q) {
        const std::uint32_t x = e[q];
        std::size_t r = q;
        while (r > 0 && e[r - 1] > x) {
          e[r] = e[r - 1];
          --r;
        }
        e[r] = x;
      }
    }
    return;
  }
  const std::uint32_t* id = rank.data();
#pragma omp parallel
  {
    // The partners' ranks read once per entry into a buffer of (rank, slot) pairs, sorted there by insertion: a few
    // to a few tens of entries per particle.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> buf;
#pragma omp for schedule(static)
    for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const std::size_t k0 = out.offset[i], m = out.offset[i + 1] - k0;
      if (m < 2) continue;
      // Partners found in the order of their cells, most of them still in the cells of their order keys, often
      // come in canonical order already (ranks are distinct: in order means sorted).
      std::size_t q0 = 1;
      while (q0 < m && id[partner[k0 + q0 - 1]] < id[partner[k0 + q0]]) ++q0;
      if (q0 == m) continue;
      buf.resize(m);
      for (std::size_t q = 0; q < m; ++q) buf[q] = {id[partner[k0 + q]], partner[k0 + q]};
      for (std::size_t q = q0; q < m; ++q) {
        const auto e = buf[q];
        std::size_t r = q;
        while (r > 0 && buf[r - 1].first > e.first) {
          buf[r] = buf[r - 1];
          --r;
        }
        buf[r] = e;
      }
      for (std::size_t q = 0; q < m; ++q) partner[k0 + q] = buf[q].second;
    }
  }
}
}  // namespace

template <int Dim>
void build_neighbor_list(const ParticleStore<Dim>& p, std::size_t owned, double cell_size, double skin,
                         NeighborList<Dim>& out, NeighborScratch& scratch, const PeriodicBox<Dim>& periodic,
                         std::span<const std::uint32_t> rank) {
  const std::size_t n = p.size();
  CellBins<Dim> b;
  if (periodic.any()) {
    b = bin_with_images(p, periodic, cell_size);
  } else {
    b = bin_particles(p, cell_size);
    add_cell_ordered_copies(p, b);
  }
  // Partners a block is first given room for: the last list's mean per particle with a quarter to spare (a bed
  // changes little between rebuilds), else a guess; append_near doubles a buffer that runs out. Sized so, the kept
  // buffers hold about the list's own size, not a fixed 8 (2D) or 16 (3D) partners per particle.
  const std::size_t last = out.offset.size() > 1 ? out.offset.back() : 0;
  const double per_particle = last > 0 && out.offset.size() == n + 1 ? 1.25 * static_cast<double>(last) / static_cast<double>(n)
                                                                      : (Dim == 2 ? 4.0 : 8.0);
  out.offset.assign(n + 1, 0);
  // One search pass over the owned particles (all of them on one rank): each thread fills its own buffer for a
  // contiguous block of particles, and the blocks are joined in block order, so the list is the same for any
  // number of threads. Ghosts (slots from `owned` on) are not searched: they take the mirror entries of their
  // owned partners below, and pairs of two ghosts are left to the ranks that own them. The first block's entries
  // are the list's first: its buffer is the list itself (the old list is not read here), so one thread needs no
  // second copy of the list.
  const int max_threads = omp_get_max_threads();
  std::vector<std::vector<std::uint32_t>>& found = scratch.found;
  if (found.size() < static_cast<std::size_t>(max_threads)) found.resize(static_cast<std::size_t>(max_threads));
  found[0] = {};
  std::vector<std::size_t> block(static_cast<std::size_t>(max_threads) + 1, owned);
  block[0] = 0;
  auto buffer = [&](std::size_t t) -> std::vector<std::uint32_t>& { return t == 0 ? out.partner : found[t]; };
#pragma omp parallel num_threads(max_threads)
  {
    const auto [t, nt] = team_slot();
    const std::size_t lo = owned * t / nt, hi = owned * (t + 1) / nt;
    block[t + 1] = hi;
    std::vector<std::uint32_t>& mine = buffer(t);
    const auto room = static_cast<std::size_t>(per_particle * static_cast<double>(hi - lo)) + 64;
    if (mine.capacity() < room) mine.reserve(room);  // exactly: the room has its quarter to spare
    if (mine.size() < room) mine.resize(room);
    std::size_t used = 0;
    for (std::size_t i = lo; i < hi; ++i) {
      const std::size_t before = used;
      used = append_near(p, b, i, skin, mine, used);
      out.offset[i + 1] = static_cast<std::uint32_t>(used - before);  // at most one bin row's particles
    }
    mine.resize(used);
  }
  // A ghost's entries: its owned partners, in their slot order.
  std::vector<std::size_t> ghost_count(n - owned, 0);
  if (owned < n) {
    for (std::size_t t = 0; t < static_cast<std::size_t>(max_threads); ++t) {
      if (block[t] >= block[t + 1]) continue;
      for (std::uint32_t j : buffer(t)) {
        if (j >= owned) ++ghost_count[j - owned];
      }
    }
    for (std::size_t g = 0; g < n - owned; ++g) out.offset[owned + g + 1] = static_cast<std::uint32_t>(ghost_count[g]);
  }
  // The prefix sum in 64 bits: a list whose entries do not fit the 32-bit offsets and links is refused.
  std::size_t total = 0;
  for (std::size_t i = 0; i < n; ++i) total += out.offset[i + 1];
  if (total > std::numeric_limits<std::uint32_t>::max()) {
    throw_simulation_error("neighbour list too long for 32-bit offsets (" + std::to_string(total) + " entries)");
  }
  for (std::size_t i = 0; i < n; ++i) out.offset[i + 1] += out.offset[i];
  resize_with_room(out.partner, out.offset[n]);  // the first block's entries stay where they are
  // No springs per entry: the solver keeps them by contact (DemSolver::spring_).
  out.history = {};
  out.rolling = {};
  for (std::size_t t = 1; t < static_cast<std::size_t>(max_threads); ++t) {
    if (block[t] < block[t + 1]) std::copy(found[t].begin(), found[t].end(), out.partner.begin() + static_cast<std::ptrdiff_t>(out.offset[block[t]]));
  }
  if (owned < n) {
    std::vector<std::size_t> fill(out.offset.begin() + static_cast<std::ptrdiff_t>(owned), out.offset.end() - 1);
    for (std::size_t i = 0; i < owned; ++i) {
      for (std::size_t k = out.offset[i]; k < out.offset[i + 1]; ++k) {
        const std::uint32_t j = out.partner[k];
        if (j >= owned) out.partner[fill[j - owned]++] = static_cast<std::uint32_t>(i);
      }
    }
  }
  sort_entries_by_rank(out, rank);
}

template <int Dim>
std::vector<std::pair<std::int64_t, std::int64_t>> brute_force_contacts(const ParticleStore<Dim>& p, double skin) {
  return brute_force_contacts(p, skin, PeriodicBox<Dim>{});
}

template <int Dim>
std::vector<std::pair<std::int64_t, std::int64_t>> brute_force_contacts(const ParticleStore<Dim>& p, double skin,
                                                                        const PeriodicBox<Dim>& periodic) {
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const Vec<Dim> d = periodic.min_image(p.pos(j) - p.pos(i));
      const double reach = p.radius[i] + p.radius[j] + skin;
      if (norm2(d) < reach * reach) pairs.emplace_back(std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

template std::vector<std::size_t> sort_by_cell<2>(const ParticleStore<2>&, double);
template std::vector<std::size_t> sort_by_cell<3>(const ParticleStore<3>&, double);
template void build_neighbor_list<2>(const ParticleStore<2>&, double, double, NeighborList<2>&);
template void build_neighbor_list<3>(const ParticleStore<3>&, double, double, NeighborList<3>&);
template void build_neighbor_list<2>(const ParticleStore<2>&, double, double, NeighborList<2>&, NeighborScratch&);
template void build_neighbor_list<3>(const ParticleStore<3>&, double, double, NeighborList<3>&, NeighborScratch&);
template std::vector<std::pair<std::int64_t, std::int64_t>> brute_force_contacts<2>(const ParticleStore<2>&, double);
template std::vector<std::pair<std::int64_t, std::int64_t>> brute_force_contacts<3>(const ParticleStore<3>&, double);
template void build_neighbor_list<2>(const ParticleStore<2>&, double, double, NeighborList<2>&, NeighborScratch&,
                                     const PeriodicBox<2>&);
template void build_neighbor_list<2>(const ParticleStore<2>&, std::size_t, double, double, NeighborList<2>&,
                                     NeighborScratch&, const PeriodicBox<2>&, std::span<const std::uint32_t>);
template void build_neighbor_list<3>(const ParticleStore<3>&, std::size_t, double, double, NeighborList<3>&,
                                     NeighborScratch&, const PeriodicBox<3>&, std::span<const std::uint32_t>);
template void build_neighbor_list<3>(const ParticleStore<3>&, double, double, NeighborList<3>&, NeighborScratch&,
                                     const PeriodicBox<3>&);
template std::vector<std::pair<std::int64_t, std::int64_t>> brute_force_contacts<2>(const ParticleStore<2>&, double,
                                                                                     const PeriodicBox<2>&);
template std::vector<std::pair<std::int64_t, std::int64_t>> brute_force_contacts<3>(const ParticleStore<3>&, double,
                                                                                     const PeriodicBox<3>&);

}  // namespace fluidbed
