#include "dem/particle_store.hpp"

#include <algorithm>

namespace fluidbed {

namespace {
template <class T>
void apply_order(std::vector<T>& a, const std::vector<std::size_t>& order, std::vector<T>& scratch) {
  scratch.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) scratch[k] = a[order[k]];
  a.swap(scratch);
}
}  // namespace

void ParticleStore::permute(const std::vector<std::size_t>& order) {
  std::vector<double> d;
  std::vector<std::int32_t> i32;
  std::vector<std::int64_t> i64;
  apply_order(id, order, i64);
  apply_order(species, order, i32);
  apply_order(layer, order, i32);
  for (auto* a : {&x, &y, &vx, &vy, &omega, &radius, &mass, &inv_mass, &inv_inertia, &fx, &fy, &torque, &fx_ext,
                  &fy_ext, &drag_k, &ugx, &ugy}) {
    apply_order(*a, order, d);
  }
}

void ParticleStore::clear() {
  id.clear();
  species.clear();
  layer.clear();
  for (auto* a : {&x, &y, &vx, &vy, &omega, &radius, &mass, &inv_mass, &inv_inertia, &fx, &fy, &torque, &fx_ext,
                  &fy_ext, &drag_k, &ugx, &ugy}) {
    a->clear();
  }
}

}  // namespace fluidbed

namespace fluidbed {

void ParticleStore::sort_by_id() {
  std::vector<std::size_t> order(size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  if (std::is_sorted(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; })) return;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
  permute(order);
}

}  // namespace fluidbed
