#pragma once
// The ghost layers of a field across the periodic axes of its grid: each ghost holds the entry one period away
// inside the domain. On one process this is the whole halo exchange of a periodic axis; across ranks it is the same
// copy from the rank that owns the other side.
#include "core/field.hpp"
#include "core/grid.hpp"

namespace fluidbed {

/// For every periodic axis a of the grid (in increasing order, so that edge and corner ghosts see the copies of
/// the axes before), every entry of f whose index along a lies outside the domain's cells [lo, lo + n), ghosts
/// included along the other axes, takes the value at the index wrapped by the period n. A face field along a
/// stores n + 1 faces there: its last face lies outside [lo, lo + n) and is tied to the first (the same plane).
/// The owned block must span the domain along a (one process).
template <int Dim>
void fill_periodic_ghosts(const Grid<Dim>& g, Field<Dim>& f) {
  for (int a = 0; a < Dim; ++a) {
    if (!g.periodic[static_cast<std::size_t>(a)]) continue;
    const IndexBox<Dim>& all = f.allocated();
    IndexBox<Dim> low = all;
    low.hi[a] = g.domain.lo[a];
    IndexBox<Dim> high = all;
    high.lo[a] = g.domain.hi[a];
    for (const IndexBox<Dim>& side : {low, high}) {
      for_each(side, [&](const Index<Dim>& c) {
        Index<Dim> w = c;
        w[a] = g.wrap(a, c[a]);
        f[c] = f[w];
      });
    }
  }
}

}  // namespace fluidbed
