#include "dem/particle_store.hpp"

namespace fluidbed {

namespace {
template <class T>
void apply_order(std::vector<T>& a, const std::vector<std::size_t>& order, std::vector<T>& scratch) {
  scratch.resize(a.size());
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
