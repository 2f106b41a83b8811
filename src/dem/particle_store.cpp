#include "dem/particle_store.hpp"

#include "dem/selection.hpp"

#include <algorithm>

namespace fluidbed {

template <int Dim>
void ParticleStore<Dim>::permute(const std::vector<std::size_t>& order) {
  if (reads_forward(order)) {
    for_each_array([&](const std::string&, auto& a, ArrayRole) { select_in_place(a, order); });
    return;
  }
  std::vector<double> d;
  std::vector<std::int32_t> i32;
  std::vector<std::int64_t> i64;
  auto scratch_for = [&](auto& a) -> auto& {
    using T = typename std::decay_t<decltype(a)>::value_type;
    if constexpr (std::is_same_v<T, double>) {
      return d;
    } else if constexpr (std::is_same_v<T, std::int32_t>) {
      return i32;
    } else {
      return i64;
    }
  };
  // After the swap a scratch holds the array's old storage: the integer ones are given back before the first
  // double array (for_each_array lists the integer arrays first), so at most one old array is held at a time on
  // top of the store.
  for_each_array([&](const std::string&, auto& a, ArrayRole) {
    auto& scratch = scratch_for(a);
    using T = typename std::decay_t<decltype(a)>::value_type;
    if constexpr (std::is_same_v<T, double>) {
      std::vector<std::int32_t>().swap(i32);
      std::vector<std::int64_t>().swap(i64);
    }
    scratch.resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) scratch[k] = a[order[k]];
    a.swap(scratch);
  });
}

template <int Dim>
void ParticleStore<Dim>::sort_by_id() {
  std::vector<std::size_t> order(size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  if (std::is_sorted(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; })) return;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
  permute(order);
}

template <int Dim>
std::vector<std::uint32_t> ParticleStore<Dim>::slots_in_id_order() const {
  std::vector<std::uint32_t> out(size());
  if (size() == 0) return out;
  const auto [lo, hi] = std::minmax_element(id.begin(), id.end());
  const auto span = static_cast<std::uint64_t>(*hi - *lo) + 1;
  if (span <= 4 * static_cast<std::uint64_t>(size()) + 64) {
    constexpr std::uint32_t kNone = 0xffffffffu;
    std::vector<std::uint32_t> at(span, kNone);
    for (std::size_t i = 0; i < size(); ++i) at[static_cast<std::size_t>(id[i] - *lo)] = static_cast<std::uint32_t>(i);
    std::size_t k = 0;
    for (const std::uint32_t i : at) {
      if (i != kNone) out[k++] = i;
    }
    return out;
  }
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = static_cast<std::uint32_t>(k);
  std::sort(out.begin(), out.end(), [this](std::uint32_t a, std::uint32_t b) { return id[a] < id[b]; });
  return out;
}

template struct ParticleStore<2>;
template struct ParticleStore<3>;

}  // namespace fluidbed
