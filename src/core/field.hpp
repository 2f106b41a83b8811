#pragma once
// A scalar field over a box of cells or faces with `ghost` layers around it, axis 0 fastest. Indices are global
// (a field of a sub-domain is addressed with the domain's indices) and run from box.lo - ghost to box.hi + ghost - 1:
// ghost entries are written by boundary conditions or halo exchange, so stencils read them and never clamp.
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "core/grid.hpp"
#include "core/index_box.hpp"

namespace fluidbed {

template <int Dim>
class Field {
 public:
  Field() = default;
  Field(const IndexBox<Dim>& box, int ghost, double value = 0.0) : box_(box), ghost_(ghost) {
    alloc_ = box.grown(ghost);
    std::size_t s = 1;
    for (int a = 0; a < Dim; ++a) {
      stride_[a] = s;
      s *= static_cast<std::size_t>(alloc_.extent(a));
    }
    v_.assign(s, value);
  }

  /// The entries the field is defined on (without ghosts), and with them.
  const IndexBox<Dim>& box() const { return box_; }
  const IndexBox<Dim>& allocated() const { return alloc_; }
  int ghost() const { return ghost_; }

  std::size_t index(const Index<Dim>& c) const {
    std::size_t k = 0;
    for (int a = 0; a < Dim; ++a) k += static_cast<std::size_t>(c[a] - alloc_.lo[a]) * stride_[a];
    return k;
  }
  std::size_t stride(int a) const { return stride_[a]; }
  double& operator[](const Index<Dim>& c) { return v_[index(c)]; }
  double operator[](const Index<Dim>& c) const { return v_[index(c)]; }
  double& operator()(int i, int j) requires(Dim == 2) { return v_[index({i, j})]; }
  double operator()(int i, int j) const requires(Dim == 2) { return v_[index({i, j})]; }
  double& operator()(int i, int j, int k) requires(Dim == 3) { return v_[index({i, j, k})]; }
  double operator()(int i, int j, int k) const requires(Dim == 3) { return v_[index({i, j, k})]; }

  /// All stored entries, ghosts included (for whole-array arithmetic and checkpoints).
  std::vector<double>& data() { return v_; }
  const std::vector<double>& data() const { return v_; }
  void fill(double value) { std::fill(v_.begin(), v_.end(), value); }
  /// Set every entry of box b (which may include ghosts) to value.
  void fill(const IndexBox<Dim>& b, double value) {
    for_each(intersect(b, alloc_), [&](const Index<Dim>& c) { v_[index(c)] = value; });
  }
  /// The interior values (box(), axis 0 fastest) as one contiguous array, and back.
  std::vector<double> interior() const {
    std::vector<double> out;
    out.reserve(box_.count());
    for_each(box_, [&](const Index<Dim>& c) { out.push_back(v_[index(c)]); });
    return out;
  }
  void set_interior(const std::vector<double>& in) {
    std::size_t k = 0;
    for_each(box_, [&](const Index<Dim>& c) { v_[index(c)] = in[k++]; });
  }

 private:
  IndexBox<Dim> box_{};
  IndexBox<Dim> alloc_{};
  int ghost_ = 0;
  std::array<std::size_t, Dim> stride_{};
  std::vector<double> v_;
};

/// The face-normal velocity components of a staggered grid: component a lives on the faces normal to axis a of
/// the cell box (one more face than cells along a), each with the same ghost layers.
template <int Dim>
struct FaceFields {
  std::array<Field<Dim>, Dim> comp;

  FaceFields() = default;
  FaceFields(const IndexBox<Dim>& cells, int ghost, double value = 0.0) {
    for (int a = 0; a < Dim; ++a) comp[a] = Field<Dim>(cells.faces(a), ghost, value);
  }
  Field<Dim>& operator[](int a) { return comp[a]; }
  const Field<Dim>& operator[](int a) const { return comp[a]; }
};

/// A ghost-free cell field on the grid's owned block, every entry `value`: its stored values are the interior, axis
/// 0 fastest, the contiguous array that the analysis views and the writers read.
template <int Dim>
Field<Dim> cell_field(const Grid<Dim>& grid, double value = 0.0) {
  return Field<Dim>(grid.owned, 0, value);
}

}  // namespace fluidbed
