#include "fluid/stencil_matrix.hpp"

namespace fluidbed {

void StencilMatrix::build(int n, const std::vector<std::array<int, 4>>& neighbours) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(n) * kSlots);
  for (int r = 0; r < n; ++r) {
    triplets.emplace_back(r, r, 1.0);
    for (int c : neighbours[static_cast<std::size_t>(r)])
      if (c >= 0) triplets.emplace_back(r, c, 0.0);
  }
  matrix_ = Matrix(n, n);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();
  offset_.assign(static_cast<std::size_t>(n) * kSlots, -1);
  const int* outer = matrix_.outerIndexPtr();
  const int* inner = matrix_.innerIndexPtr();
  const auto find = [&](int r, int c) {
    for (int k = outer[r]; k < outer[r + 1]; ++k)
      if (inner[k] == c) return k;
    return -1;
  };
  for (int r = 0; r < n; ++r) {
    offset_[static_cast<std::size_t>(r) * kSlots] = find(r, r);
    for (int k = 0; k < 4; ++k) {
      const int c = neighbours[static_cast<std::size_t>(r)][static_cast<std::size_t>(k)];
      offset_[static_cast<std::size_t>(r) * kSlots + 1 + k] = c >= 0 ? find(r, c) : -1;
    }
  }
}

void StencilMatrix::build_cells(int nx, int ny) {
  std::vector<std::array<int, 4>> nb(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      nb[static_cast<std::size_t>(r)] = {i > 0 ? r - 1 : -1, i < nx - 1 ? r + 1 : -1, j > 0 ? r - nx : -1,
                                         j < ny - 1 ? r + nx : -1};
    }
  build(nx * ny, nb);
}

}  // namespace fluidbed
