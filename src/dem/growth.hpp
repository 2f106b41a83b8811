#pragma once
// How the DEM's long-lived buffers grow. libstdc++'s resize beyond the capacity allocates twice the old size, so a
// list or a record array that grows by a few percent as a bed compacts would keep up to twice what it holds, for
// the rest of the run (docs/performance.md section 39: with the copies, 2.6 kB of heap a settled 3D sphere; 1.5 kB
// without).
// An eighth to spare instead: a bed that grows from nothing reallocates an array about nine times its final
// size in all (page faults of a few ms over a run), and holds at most an eighth more than it needs.
#include <cstddef>

namespace fluidbed {

/// Capacity for m, with room for m + m / 8 when it must grow (for a caller that then fills v itself).
template <class V>
void reserve_with_room(V& v, std::size_t m) {
  if (v.capacity() < m) v.reserve(m + m / 8);
}

/// v.resize(m), with room for m + m / 8 when it must grow.
template <class V>
void resize_with_room(V& v, std::size_t m) {
  reserve_with_room(v, m);
  v.resize(m);
}

}  // namespace fluidbed
