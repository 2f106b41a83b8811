#pragma once
// A half-open box of integer indices [lo, hi) in Dim dimensions: the cells (or faces) a field stores, the block a
// rank owns, the range a kernel loops over. Loops run with axis 0 fastest, the storage order of Field<Dim>.
#include <array>
#include <cstddef>
#include <type_traits>

namespace fluidbed {

template <int Dim>
using Index = std::array<int, Dim>;

template <int Dim>
struct IndexBox {
  Index<Dim> lo{};
  Index<Dim> hi{};

  constexpr int extent(int a) const { return hi[a] - lo[a]; }
  constexpr bool empty() const {
    for (int a = 0; a < Dim; ++a) {
      if (hi[a] <= lo[a]) return true;
    }
    return false;
  }
  constexpr std::size_t count() const {
    if (empty()) return 0;
    std::size_t n = 1;
    for (int a = 0; a < Dim; ++a) n *= static_cast<std::size_t>(extent(a));
    return n;
  }
  constexpr bool contains(const Index<Dim>& c) const {
    for (int a = 0; a < Dim; ++a) {
      if (c[a] < lo[a] || c[a] >= hi[a]) return false;
    }
    return true;
  }
  constexpr bool contains(const IndexBox& b) const {
    for (int a = 0; a < Dim; ++a) {
      if (b.lo[a] < lo[a] || b.hi[a] > hi[a]) return false;
    }
    return true;
  }
  /// Grown by g on every side of every axis (a ghost-layered box).
  constexpr IndexBox grown(int g) const {
    IndexBox b = *this;
    for (int a = 0; a < Dim; ++a) {
      b.lo[a] -= g;
      b.hi[a] += g;
    }
    return b;
  }
  /// Grown by g on both sides of axis a only.
  constexpr IndexBox grown(int a, int g) const {
    IndexBox b = *this;
    b.lo[a] -= g;
    b.hi[a] += g;
    return b;
  }
  /// The faces normal to axis a of these cells: one more along a.
  constexpr IndexBox faces(int a) const {
    IndexBox b = *this;
    b.hi[a] += 1;
    return b;
  }
  /// The layer of thickness w just outside side `high` (false: below lo) of axis a: ghost cells of that side.
  constexpr IndexBox outside(int a, bool high, int w = 1) const {
    IndexBox b = *this;
    if (high) {
      b.lo[a] = hi[a];
      b.hi[a] = hi[a] + w;
    } else {
      b.hi[a] = lo[a];
      b.lo[a] = lo[a] - w;
    }
    return b;
  }
  /// The layer of thickness w just inside side `high` of axis a.
  constexpr IndexBox inside(int a, bool high, int w = 1) const {
    IndexBox b = *this;
    if (high) {
      b.lo[a] = hi[a] - w;
    } else {
      b.hi[a] = lo[a] + w;
    }
    return b;
  }
  friend constexpr IndexBox intersect(const IndexBox& p, const IndexBox& q) {
    IndexBox b;
    for (int a = 0; a < Dim; ++a) {
      b.lo[a] = p.lo[a] > q.lo[a] ? p.lo[a] : q.lo[a];
      b.hi[a] = p.hi[a] < q.hi[a] ? p.hi[a] : q.hi[a];
    }
    return b;
  }
  friend constexpr bool operator==(const IndexBox&, const IndexBox&) = default;
};

/// Call f(Index<Dim>) for every index of the box, axis 0 fastest.
template <int Dim, class F>
inline void for_each(const IndexBox<Dim>& b, F&& f) {
  if (b.empty()) return;
  if constexpr (Dim == 2) {
    for (int j = b.lo[1]; j < b.hi[1]; ++j) {
      for (int i = b.lo[0]; i < b.hi[0]; ++i) f(Index<2>{i, j});
    }
  } else {
    for (int k = b.lo[2]; k < b.hi[2]; ++k) {
      for (int j = b.lo[1]; j < b.hi[1]; ++j) {
        for (int i = b.lo[0]; i < b.hi[0]; ++i) f(Index<3>{i, j, k});
      }
    }
  }
}

/// Position of index c among the box's indices counted axis 0 fastest (the row numbering of every linear system).
template <int Dim>
constexpr int cell_row(const IndexBox<Dim>& b, const std::type_identity_t<Index<Dim>>& c) {
  int r = 0, stride = 1;
  for (int a = 0; a < Dim; ++a) {
    r += (c[a] - b.lo[a]) * stride;
    stride *= b.extent(a);
  }
  return r;
}

/// The index at position `row` of the box (the inverse of cell_row).
template <int Dim>
constexpr Index<Dim> cell_at(const IndexBox<Dim>& b, long row) {
  Index<Dim> c{};
  for (int a = 0; a < Dim; ++a) {
    c[a] = b.lo[a] + static_cast<int>(row % b.extent(a));
    row /= b.extent(a);
  }
  return c;
}

/// The index one step along axis a (s = +1 or -1).
template <int Dim>
constexpr Index<Dim> shifted(Index<Dim> c, int a, int s) {
  c[a] += s;
  return c;
}

}  // namespace fluidbed
