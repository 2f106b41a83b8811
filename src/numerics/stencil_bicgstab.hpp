#pragma once
// A nonsymmetric (2 Dim + 1)-point system over the cells of a rank's block, solved by BiCGSTAB (van der Vorst,
// SIAM J. Sci. Stat. Comput. 13, 1992; the steps and the restart of Eigen 3.4's BiCGSTAB) with a Jacobi
// preconditioner, whose iterates are the same bits on any number of ranks:
//  - the product computes each row from its own coefficients in one order (diagonal, then W, E, S, N[, B, F]),
//    reading the neighbours from a ghost layer that the halo exchange (and the periodic images) fill: the same
//    arithmetic whoever owns the row;
//  - an inner product sums each line of cells along axis 0 in one fixed order (four interleaved partial sums from
//    the line's first cell, then the tail), and adds the line sums exactly (ExactSum), reduced exactly over the
//    ranks; so axis 0 is never cut across ranks (refused by name). An exact accumulator per cell would cost
//    8 ns, ten times a product: the two-fluid model's solves are small and frequent, and could not afford it;
//  - when BiCGSTAB stops short (iteration cap or breakdown) every rank gathers the whole system and solves it by
//    the same sparse LU, so the fallback is the same answer on every rank too.
// The solids-fraction correction and the implicit solids continuity of the two-fluid model solve through it.
#include <array>
#include <span>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "numerics/stencil_matrix.hpp"
#include "parallel/comm.hpp"

namespace fluidbed {

template <int Dim>
class StencilBicgstab {
 public:
  static constexpr int kSlots = 2 * Dim;

  /// Rows are grid.owned's cells, axis 0 fastest. Throws an input error when axis 0 is cut across ranks, or a
  /// periodic axis is (its ghosts would need the opposite rank), or a periodic axis has fewer than 3 cells (a row
  /// would meet the same neighbour through both faces). `comm` must outlive the solver.
  StencilBicgstab(const Grid<Dim>& grid, const Comm& comm);

  int rows() const { return static_cast<int>(diag_.size()); }
  /// Row `row` (a local row): the diagonal and the coefficients of the neighbours low and high along each axis in
  /// turn (W, E, S, N[, B, F]). A neighbour beyond a wall must have coefficient 0; across a periodic side it is
  /// the cell at the other end.
  void set_row(int row, double diag, const std::array<double, kSlots>& off) {
    const auto r = static_cast<std::size_t>(row);
    diag_[r] = diag;
    for (int k = 0; k < kSlots; ++k) off_[static_cast<std::size_t>(k)][r] = off[static_cast<std::size_t>(k)];
  }
  void set_tolerance(double tol) { tolerance_ = tol; }
  /// At most n iterations; 0 or less: twice the global number of rows (Eigen's default).
  void set_max_iterations(int n) { max_iterations_ = n; }

  /// Solves A x = b over the local rows; x is the initial guess on entry (zero when empty) and the answer on exit.
  /// The outcome is the same on every rank (bad_row is a global row: the domain's cells, axis 0 fastest).
  LinearSolveOutcome solve(std::span<const double> b, std::vector<double>& x);

 private:
  void multiply(std::span<const double> in, std::vector<double>& out);
  /// The inner products u_k . v_k for k < count, reduced over the ranks in one collective.
  void dots(int count, const std::array<const double*, 2>& u, const std::array<const double*, 2>& v,
            std::array<double, 2>& out) const;
  bool bicgstab(std::span<const double> b, std::vector<double>& x, LinearSolveOutcome& out);
  /// The whole system on every rank, solved by a sparse LU.
  void direct(std::span<const double> b, std::vector<double>& x, LinearSolveOutcome& out) const;
  int global_row(int row) const;

  const Comm& comm_;
  Grid<Dim> grid_;
  std::vector<IndexBox<Dim>> boxes_;  ///< every rank's block (halo partners)
  long global_rows_ = 0;
  int line_length_ = 0;
  std::vector<double> diag_;
  std::array<std::vector<double>, kSlots> off_;
  std::array<std::ptrdiff_t, kSlots> shift_{};  ///< offset of each neighbour in the ghosted field
  std::vector<std::size_t> line_start_;          ///< offset of each line's first cell in the ghosted field
  Field<Dim> ghosted_;                           ///< the product's input with its ghost layer
  double tolerance_ = 1e-12;
  int max_iterations_ = 0;
  std::vector<double> invdiag_, r_, r0_, v_, p_, y_, z_, s_, t_, answer_;
};

extern template class StencilBicgstab<2>;
extern template class StencilBicgstab<3>;

}  // namespace fluidbed
