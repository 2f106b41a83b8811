#pragma once
// The domain cut into blocks of whole gas cells, and the blocks dealt to ranks along a space-filling curve: the
// decomposition of a particle run. A rank owns the particles whose centres lie in its blocks (and, once the gas
// is decomposed, the cells of its blocks). Blocks are at least one ghost reach wide, so a particle near a block's
// side can only be needed by the ranks of the 3^Dim blocks around its own.
//
// The curve is Hilbert's (Skilling, "Programming the Hilbert curve", AIP Conf. Proc. 707, 2004: the transpose
// form, any number of axes): consecutive blocks along it are neighbours, so a run of blocks with about equal cost
// is a compact region. The deal depends only on the blocks' weights (counts of particles, contacts and cells, not
// timings), so every rank computes the same owners from the same numbers without talking to the others.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "core/index_box.hpp"
#include "core/vec.hpp"

namespace fluidbed {

/// Hilbert index of point c (coordinates below 2^bits per axis) on the Dim-dimensional curve of that order.
template <int Dim>
std::uint64_t hilbert_index(std::array<std::uint32_t, Dim> c, int bits) {
  // Skilling's transform to the "transpose" of the index: undo the excess work of the axes, then Gray-encode.
  const std::uint32_t top = bits > 0 ? 1u << (bits - 1) : 0u;
  for (std::uint32_t q = top; q > 1; q >>= 1) {
    const std::uint32_t low = q - 1;
    for (int a = 0; a < Dim; ++a) {
      if (c[a] & q) {
        c[0] ^= low;
      } else {
        const std::uint32_t t = (c[0] ^ c[a]) & low;
        c[0] ^= t;
        c[a] ^= t;
      }
    }
  }
  for (int a = 1; a < Dim; ++a) c[a] ^= c[a - 1];
  std::uint32_t flip = 0;
  for (std::uint32_t q = top; q > 1; q >>= 1) {
    if (c[Dim - 1] & q) flip ^= q - 1;
  }
  for (int a = 0; a < Dim; ++a) c[a] ^= flip;
  // The index's bits, most significant first: bit b of axis 0, of axis 1, ..., then bit b - 1.
  std::uint64_t h = 0;
  for (int b = bits - 1; b >= 0; --b) {
    for (int a = 0; a < Dim; ++a) h = (h << 1) | ((c[a] >> b) & 1u);
  }
  return h;
}

/// The run's cells cut into near-equal blocks of at least `min_per_block` cells per axis (n / min_per_block blocks
/// along an axis of n cells, the first ones a cell wider), over the box origin + [0, n h) with the given periodic
/// axes, and which rank owns each block.
template <int Dim>
class BlockLayout {
 public:
  BlockLayout() = default;
  BlockLayout(const Index<Dim>& cells, const Vec<Dim>& h, const Vec<Dim>& origin, const Index<Dim>& min_per_block,
              const std::array<bool, Dim>& periodic)
      : cells_(cells), h_(h), origin_(origin), periodic_(periodic) {
    std::size_t total = 1;
    for (int a = 0; a < Dim; ++a) {
      if (cells[a] < 1 || min_per_block[a] < 1) throw std::invalid_argument("BlockLayout: no cells");
      counts_[a] = std::max(1, cells[a] / min_per_block[a]);
      total *= static_cast<std::size_t>(counts_[a]);
      // The last block whose first cell is at or below each cell (the inverse of first_cell), looked up per
      // particle at every list build rather than divided out.
      std::vector<int>& t = block_of_cell_[static_cast<std::size_t>(a)];
      t.resize(static_cast<std::size_t>(cells[a]));
      const long k = counts_[a], n = cells[a];
      for (long cell = 0; cell < n; ++cell) t[static_cast<std::size_t>(cell)] = static_cast<int>((cell * k + k - 1) / n);
    }
    owner_.assign(total, 0);
  }

  int blocks() const { return static_cast<int>(owner_.size()); }
  const Index<Dim>& counts() const { return counts_; }
  const Index<Dim>& cells() const { return cells_; }
  const Vec<Dim>& cell_size() const { return h_; }
  bool periodic(int a) const { return periodic_[static_cast<std::size_t>(a)]; }
  /// Length of the domain along axis a, m.
  double length(int a) const { return cells_[a] * h_[a]; }

  /// Block coordinates of block b (axis 0 fastest) and back.
  Index<Dim> coords(int b) const {
    Index<Dim> c{};
    for (int a = 0; a < Dim; ++a) {
      c[a] = b % counts_[a];
      b /= counts_[a];
    }
    return c;
  }
  int block(const Index<Dim>& c) const {
    int b = 0;
    for (int a = Dim - 1; a >= 0; --a) b = b * counts_[a] + c[a];
    return b;
  }
  /// The cells of block b: [floor(c n / k), floor((c + 1) n / k)) along each axis (k blocks over n cells).
  IndexBox<Dim> cells_of(int b) const {
    const Index<Dim> c = coords(b);
    IndexBox<Dim> box;
    for (int a = 0; a < Dim; ++a) {
      box.lo[a] = first_cell(a, c[a]);
      box.hi[a] = first_cell(a, c[a] + 1);
    }
    return box;
  }
  /// The narrowest block along axis a, m.
  double min_width(int a) const { return (cells_[a] / counts_[a]) * h_[a]; }
  /// Low and high corner of block b, m.
  Vec<Dim> lo(int b) const {
    const IndexBox<Dim> box = cells_of(b);
    Vec<Dim> x{};
    for (int a = 0; a < Dim; ++a) x[a] = origin_[a] + box.lo[a] * h_[a];
    return x;
  }
  Vec<Dim> hi(int b) const {
    const IndexBox<Dim> box = cells_of(b);
    Vec<Dim> x{};
    for (int a = 0; a < Dim; ++a) x[a] = origin_[a] + box.hi[a] * h_[a];
    return x;
  }
  /// The block holding point x: the cell of x (clamped to the domain, as Grid::cell does) divided by the block
  /// size, so a particle and the cell its centre lies in always share a block.
  int block_at(const Vec<Dim>& x) const {
    int b = 0;
    for (int a = Dim - 1; a >= 0; --a) {
      const int cell = std::clamp(static_cast<int>(std::floor((x[a] - origin_[a]) / h_[a])), 0, cells_[a] - 1);
      b = b * counts_[a] + block_of_cell_[static_cast<std::size_t>(a)][static_cast<std::size_t>(cell)];
    }
    return b;
  }

  int owner(int b) const { return owner_[static_cast<std::size_t>(b)]; }
  const std::vector<int>& owners() const { return owner_; }
  void set_owners(std::vector<int> o) {
    if (o.size() != owner_.size()) throw std::invalid_argument("BlockLayout::set_owners: one owner per block");
    owner_ = std::move(o);
    ++version_;
  }
  /// Counts the changes of the owners (a cache keyed by the deal compares it).
  std::uint64_t version() const { return version_; }

  /// The blocks in the order of the Hilbert curve through the block grid (ties, from the padding of the grid to
  /// a power of two, cannot occur: every block has its own point).
  std::vector<int> curve_order() const {
    int bits = 0;
    while ((1 << bits) < *std::max_element(counts_.begin(), counts_.end())) ++bits;
    std::vector<std::pair<std::uint64_t, int>> key(owner_.size());
    for (int b = 0; b < blocks(); ++b) {
      const Index<Dim> c = coords(b);
      std::array<std::uint32_t, Dim> u{};
      for (int a = 0; a < Dim; ++a) u[static_cast<std::size_t>(a)] = static_cast<std::uint32_t>(c[a]);
      key[static_cast<std::size_t>(b)] = {hilbert_index<Dim>(u, bits), b};
    }
    std::sort(key.begin(), key.end());
    std::vector<int> order(owner_.size());
    for (std::size_t k = 0; k < key.size(); ++k) order[k] = key[k].second;
    return order;
  }

  /// Deal the blocks to `ranks` ranks as runs along the curve of about equal weight: block b goes to the rank
  /// whose share of the total weight holds the middle of b's own weight (a rank may get none if one block
  /// outweighs a share). weights[b] >= 0, one per block.
  void assign(const std::vector<double>& weights, int ranks) {
    if (weights.size() != owner_.size()) throw std::invalid_argument("BlockLayout::assign: one weight per block");
    const std::vector<int> order = curve_order();
    double total = 0.0;
    for (int b : order) total += weights[static_cast<std::size_t>(b)];
    double before = 0.0;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const auto b = static_cast<std::size_t>(order[k]);
      // Without weight, blocks are dealt by their place on the curve.
      const double mid = total > 0.0 ? (before + 0.5 * weights[b]) / total
                                     : (static_cast<double>(k) + 0.5) / static_cast<double>(order.size());
      before += weights[b];
      owner_[b] = std::clamp(static_cast<int>(std::floor(mid * ranks)), 0, ranks - 1);
    }
    ++version_;
  }

  /// The weight each of `ranks` ranks holds under the current owners.
  std::vector<double> rank_weights(const std::vector<double>& weights, int ranks) const {
    std::vector<double> w(static_cast<std::size_t>(ranks), 0.0);
    for (std::size_t b = 0; b < owner_.size(); ++b) w[static_cast<std::size_t>(owner_[b])] += weights[b];
    return w;
  }

  /// A block next to b (offset -1, 0 or +1 per axis) and the shift, in periods per axis, that carries b's
  /// neighbourhood onto it across a periodic side; returns -1 beyond a side that is not periodic.
  int neighbour(int b, const Index<Dim>& offset, Index<Dim>& shift) const {
    Index<Dim> c = coords(b);
    for (int a = 0; a < Dim; ++a) {
      shift[a] = 0;
      c[a] += offset[a];
      if (c[a] < 0 || c[a] >= counts_[a]) {
        if (!periodic(a)) return -1;
        shift[a] = c[a] < 0 ? -1 : 1;
        c[a] = c[a] < 0 ? c[a] + counts_[a] : c[a] - counts_[a];
      }
    }
    return block(c);
  }

 private:
  int first_cell(int a, int c) const {
    return static_cast<int>(static_cast<long>(c) * cells_[a] / counts_[a]);
  }

  Index<Dim> cells_{};
  Vec<Dim> h_{};
  Vec<Dim> origin_{};
  std::array<bool, Dim> periodic_{};
  Index<Dim> counts_{};
  std::array<std::vector<int>, Dim> block_of_cell_{};
  std::vector<int> owner_;
  std::uint64_t version_ = 0;
};

/// Largest over mean of the ranks' weights: 1 for a perfect balance.
inline double imbalance(const std::vector<double>& rank_weights) {
  if (rank_weights.empty()) return 1.0;
  double total = 0.0, most = 0.0;
  for (double w : rank_weights) {
    total += w;
    most = std::max(most, w);
  }
  const double mean = total / static_cast<double>(rank_weights.size());
  return mean > 0.0 ? most / mean : 1.0;
}

}  // namespace fluidbed
