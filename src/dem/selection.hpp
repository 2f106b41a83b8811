#pragma once
// Selections of a store's slots (new slot k takes old slot order[k]). The particles that stay on a rank after
// others left for their new owners are such a selection in ascending order: kept in place, from the front, it
// needs no second array (no allocation, no page faults, half the memory traffic of a copy).
#include <algorithm>
#include <cstddef>
#include <vector>

namespace fluidbed {

/// order names slots in strictly ascending order: a selection that keeps the survivors' order.
inline bool is_ascending_selection(const std::vector<std::size_t>& order) {
  return std::adjacent_find(order.begin(), order.end(), [](std::size_t a, std::size_t b) { return a >= b; }) ==
         order.end();
}

/// v[k * stride + c] = v[order[k] * stride + c] for an ascending selection (order[k] >= k, so no element is read
/// after it was overwritten), then v cut to the selection.
template <class V>
void select_in_place(V& v, const std::vector<std::size_t>& order, std::size_t stride = 1) {
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (order[k] == k) continue;
    for (std::size_t c = 0; c < stride; ++c) v[k * stride + c] = v[order[k] * stride + c];
  }
  v.resize(order.size() * stride);
}

}  // namespace fluidbed
