#pragma once
// Particle -> grid in one pass: solids volume, solids momentum and drag coefficient of every cell from the stored
// kernel weights, threaded over fixed blocks of particles whose partial sums are added in block order, so that the
// result is independent of the thread count (the blocks do not depend on it).
#include <array>
#include <cstddef>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "coupling/voidage.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

/// The cell fields of one deposition, on the grid's owned box.
template <int Dim>
struct DepositedFields {
  Field<Dim>* eps = nullptr;                      ///< 1 - solids volume / V_cell, not clipped
  std::array<Field<Dim>, Dim>* us = nullptr;      ///< volume-weighted mean particle velocity (0 in empty cells)
  Field<Dim>* beta = nullptr;                     ///< sum of the particles' K_p per unit cell volume (Eq. 12's beta)
  std::array<Field<Dim>, Dim>* us_gas = nullptr;  ///< K-weighted mean particle velocity (us where no drag)
};

/// Fused deposition with its work buffers kept between calls (no allocation once the sizes have settled).
template <int Dim>
class Deposition {
 public:
  /// Particles per block: fixed, so that the order of the additions does not depend on the thread count.
  static constexpr std::size_t kBlock = 2048;

  /// Deposits the particles (weights from particle_cell_weights on the owned box, one per particle in storage
  /// order; drag coefficients K_p = p.drag_k) into `out`; V_cell is deposition_volume(grid, depth).
  void deposit(const ParticleStore<Dim>& p, const std::vector<CellWeights<Dim>>& weights, const Grid<Dim>& grid,
               double depth, const DepositedFields<Dim>& out);

 private:
  // Per cell: solids volume, volume-weighted velocity sums, K, K-weighted velocity sums.
  static constexpr std::size_t kStride = 2 + 2 * Dim;
  struct Block {
    std::size_t first_cell = 0, end_cell = 0;  // the cells this block's particles touch
    std::vector<double> sums;                  // kStride per cell of [first_cell, end_cell)
  };
  std::vector<Block> blocks_;
  std::vector<double> total_;
};

extern template class Deposition<2>;
extern template class Deposition<3>;

}  // namespace fluidbed
