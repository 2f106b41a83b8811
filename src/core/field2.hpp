#pragma once
// A scalar field on an (nx x ny) array, i fastest; used for cell-centred and face-centred data alike.
#include <cstddef>
#include <vector>

namespace fluidbed {

struct Field2 {
  int nx = 0;
  int ny = 0;
  std::vector<double> v;

  Field2() = default;
  Field2(int nx_, int ny_, double value = 0.0)
      : nx(nx_), ny(ny_), v(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), value) {}

  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i);
  }
  double& operator()(int i, int j) { return v[index(i, j)]; }
  double operator()(int i, int j) const { return v[index(i, j)]; }
  std::size_t size() const { return v.size(); }
  void fill(double value) { std::fill(v.begin(), v.end(), value); }
};

}  // namespace fluidbed
