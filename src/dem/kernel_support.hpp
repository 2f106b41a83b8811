#pragma once
// Small helpers of the DEM kernels, shared by the solver's units (dem_solver.cpp, the force pass of force_pass.hpp):
// raw per-axis pointers hoisted out of the particle loops, and the squared length of a spin.
#include <array>

#include "core/vec.hpp"

namespace fluidbed::dem_kernel {

/// Raw pointers to the arrays a kernel reads per axis, hoisted out of the particle loop.
template <int Dim>
struct AxisPtrs {
  std::array<double*, Dim> a;
  double* operator[](int k) const { return a[static_cast<std::size_t>(k)]; }
};
template <int Dim, class Get>
AxisPtrs<Dim> axis_ptrs(Get&& get, int n) {
  AxisPtrs<Dim> p{};
  for (int k = 0; k < n; ++k) p.a[static_cast<std::size_t>(k)] = get(k).data();
  return p;
}

template <int Dim>
double spin_norm2(Spin<Dim> w) {
  if constexpr (Dim == 2) {
    return w * w;
  } else {
    return dot(w, w);
  }
}

}  // namespace fluidbed::dem_kernel
