#pragma once
// Selections of a store's slots (new slot k takes old slot order[k]). The particles that stay on a rank after
// others left for their new owners keep their slots, and the last of them fill the slots of those that left: made
// in place, such a selection moves only the particles that fill holes, with no second array (no allocation, no
// page faults, no copy of the store).
#include <algorithm>
#include <cstddef>
#include <vector>

namespace fluidbed {

/// order names slots in strictly ascending order: a selection that keeps the survivors' order.
inline bool is_ascending_selection(const std::vector<std::size_t>& order) {
  return std::adjacent_find(order.begin(), order.end(), [](std::size_t a, std::size_t b) { return a >= b; }) ==
         order.end();
}

/// Every new slot k takes an old slot at or after k (an ascending selection, or one whose holes are filled from
/// the end): copied in place from the front, each slot is read before anything overwrites it.
inline bool reads_forward(const std::vector<std::size_t>& order) {
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (order[k] < k) return false;
  }
  return true;
}

/// v[k * stride + c] = v[order[k] * stride + c] for an order that reads forward, then v cut to the selection.
template <class V>
void select_in_place(V& v, const std::vector<std::size_t>& order, std::size_t stride = 1) {
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (order[k] == k) continue;
    for (std::size_t c = 0; c < stride; ++c) v[k * stride + c] = v[order[k] * stride + c];
  }
  v.resize(order.size() * stride);
}

/// v[k * stride + c] = v[order[k] * stride + c] for any order: in place when it reads forward, else through a copy.
template <class V>
void select_slots(V& v, const std::vector<std::size_t>& order, std::size_t stride = 1) {
  if (reads_forward(order)) {
    select_in_place(v, order, stride);
    return;
  }
  V next(order.size() * stride);
  for (std::size_t k = 0; k < order.size(); ++k) {
    for (std::size_t c = 0; c < stride; ++c) next[k * stride + c] = v[order[k] * stride + c];
  }
  v.swap(next);
}

}  // namespace fluidbed
