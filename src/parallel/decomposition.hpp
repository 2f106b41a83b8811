#pragma once
// The domain's cells cut into a Cartesian array of blocks, one per rank: the owned boxes of a decomposed grid.
// Pure index arithmetic, so every rank computes every other rank's box without communication.
#include <array>
#include <cstdint>
#include <limits>

#include "core/index_box.hpp"

namespace fluidbed {

/// Rank r's block of `domain` cut into blocks[a] slabs per axis (block coordinates axis 0 fastest, as the cells);
/// along each axis the first n mod p blocks hold one cell more than the others.
template <int Dim>
IndexBox<Dim> block_of(const IndexBox<Dim>& domain, const Index<Dim>& blocks, int rank) {
  IndexBox<Dim> b;
  for (int a = 0; a < Dim; ++a) {
    const int p = blocks[a];
    const int c = rank % p;
    rank /= p;
    const int n = domain.extent(a);
    const int base = n / p, extra = n % p;
    b.lo[a] = domain.lo[a] + c * base + (c < extra ? c : extra);
    b.hi[a] = b.lo[a] + base + (c < extra ? 1 : 0);
  }
  return b;
}

/// The blocks per axis for `ranks` ranks over n cells per axis: of the factorisations with at least one cell per
/// block on every axis, the one with the fewest cell faces between blocks (the halo each step exchanges); ties go
/// to the first found, axis 0 cut least. All zeros when no factorisation fits (more ranks than cells).
template <int Dim>
Index<Dim> block_counts(int ranks, const Index<Dim>& n) {
  Index<Dim> best{};
  std::int64_t best_faces = std::numeric_limits<std::int64_t>::max();
  Index<Dim> p{};
  auto visit = [&](auto&& self, int a, int left) -> void {
    if (a == Dim - 1) {
      p[a] = left;
      std::int64_t faces = 0;
      for (int d = 0; d < Dim; ++d) {
        if (p[d] > n[d]) return;
        std::int64_t cross = p[d] - 1;  // internal cuts normal to axis d, each a plane of the other axes' cells
        for (int e = 0; e < Dim; ++e) cross *= e == d ? 1 : n[e];
        faces += cross;
      }
      if (faces < best_faces) {
        best_faces = faces;
        best = p;
      }
      return;
    }
    for (int f = 1; f <= left; ++f) {
      if (left % f != 0) continue;
      p[a] = f;
      self(self, a + 1, left / f);
    }
  };
  if (ranks >= 1) visit(visit, 0, ranks);
  return best;
}

}  // namespace fluidbed
