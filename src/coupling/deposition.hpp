#pragma once
// Particle -> grid in one pass: solids volume, solids momentum and drag coefficient of every cell from the stored
// kernel weights. Each cell sums its particles' shares in a canonical order of the particles (DemSolver's
// canonical_order: ascending order key and id), so a cell's value depends only on the particles that reach it: not
// on the thread count, not on how the particles are stored, and not on how the domain is split over ranks (a rank
// computes its cells from its own particles and the ghosts of its neighbours', in the same order as one rank
// holding them all).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
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

/// Every cell's shares (particle slot, kernel weight), in a given order of the particles (the canonical one:
/// DemSolver::canonical_order) and, for one particle, in the order of its weights: the order of every per-cell sum
/// over particles. Built by a counting sort over the particles in that order, in chunks whose results are laid out
/// chunk after chunk per cell, so the order is the same for any number of chunks (threads). weights[i] are slot
/// i's (storage order).
class CellEntries {
 public:
  template <int Dim>
  void build(const std::vector<CellWeights<Dim>>& weights, std::span<const std::uint32_t> order, std::size_t cells);
  std::size_t cells() const { return start_.empty() ? 0 : start_.size() - 1; }
  std::size_t begin(std::size_t c) const { return start_[c]; }
  std::size_t end(std::size_t c) const { return start_[c + 1]; }
  std::uint32_t slot(std::size_t e) const { return slot_[e]; }
  double weight(std::size_t e) const { return w_[e]; }

 private:
  std::vector<std::size_t> start_;
  std::vector<std::uint32_t> slot_;
  std::vector<double> w_;
  std::vector<std::vector<std::size_t>> chunk_count_;
};

/// Fused deposition with its work buffers kept between calls (no allocation once the sizes have settled).
template <int Dim>
class Deposition {
 public:
  /// Deposits the particles (weights from particle_cell_weights on the owned box, one per particle in storage
  /// order; drag coefficients K_p = p.drag_k) into `out`; V_cell is deposition_volume(grid, depth). Every cell any
  /// particle reaches gets the sums of the particles the store holds.
  void deposit(const ParticleStore<Dim>& p, const std::vector<CellWeights<Dim>>& weights, const Grid<Dim>& grid,
               double depth, const DepositedFields<Dim>& out);
  /// The same, each cell's sum in the order `order` gives the slots (the canonical order, which does not depend
  /// on how the particles are split over ranks; the call above takes ascending id).
  void deposit(const ParticleStore<Dim>& p, const std::vector<CellWeights<Dim>>& weights, const Grid<Dim>& grid,
               double depth, const DepositedFields<Dim>& out, std::span<const std::uint32_t> order);
 private:
  CellEntries entries_;
  std::vector<std::uint32_t> order_;
};

extern template class Deposition<2>;
extern template class Deposition<3>;

}  // namespace fluidbed
