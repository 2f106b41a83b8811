#pragma once
// Pressure-correction equation of SIMPLE on cell centres: aP p'_P - sum_nb a_nb p'_nb = b, aP = sum of the
// 2 Dim face coefficients. A structured problem (one coefficient per cell face, cells of a box), so that a
// structured multigrid library (hypre's PFMG/SMG take exactly this) can replace the first backend, Eigen's sparse
// Cholesky, without touching the solvers. Reused by the gas solver and the two-fluid model.
#include <array>
#include <memory>

#include "core/field.hpp"
#include "core/field2.hpp"
#include "core/grid.hpp"
#include "core/grid2.hpp"

namespace fluidbed {

enum class PressureSolverKind {
  Direct,             ///< Eigen SimplicialLDLT, symbolic analysis done once
  ConjugateGradient,  ///< Eigen ConjugateGradient + IncompleteCholesky, warm-started
};

/// A symmetric cell-centred problem on the cells of a grid's owned box: for every cell P,
/// sum over its faces f of a_f (x_P - x_nb(f)) = rhs_P, with a_f = coeff[axis][face]. A coefficient on a face of
/// the domain's boundary couples to x = 0 beyond it (a fixed-pressure boundary); zero there is an impermeable
/// face. On a periodic axis of the grid (Grid::periodic) face 0 couples the first cell to the last (the last face
/// is the same plane and is not read). If no boundary face has a coefficient the system is singular and the domain's first cell is pinned to 0.
template <int Dim>
class StructuredSolver {
 public:
  virtual ~StructuredSolver() = default;
  /// Solves for x over coeff's cells (box = the grid's owned box; ghosts are not read). x is the initial guess on
  /// entry (for iterative backends). With `reuse_factorisation` a backend may precondition with the operator of
  /// its last solve instead of setting up a new one (within one SIMPLE step the coefficients change little).
  /// Throws a simulation error when the coefficients or the right-hand side are not finite or the solve fails.
  virtual void solve(const FaceFields<Dim>& coeff, const Field<Dim>& rhs, Field<Dim>& x,
                     bool reuse_factorisation) = 0;
  /// The backend's name, for reports.
  virtual const char* name() const = 0;
};

/// Whether any face on the boundary of `cells` has a coefficient (a fixed-pressure face); without one the problem
/// is singular and every backend pins the first cell. The faces of a periodic axis couple the two sides' cells
/// to each other, not to a fixed pressure, and do not count.
template <int Dim>
bool couples_to_boundary(const IndexBox<Dim>& cells, const FaceFields<Dim>& coeff,
                         const std::array<bool, Dim>& periodic = {}) {
  bool any = false;
  for (int a = 0; a < Dim; ++a)
    for (bool high : {false, true}) {
      if (periodic[static_cast<std::size_t>(a)]) continue;
      IndexBox<Dim> side = cells.inside(a, high);
      if (high) {
        side.lo[a] += 1;
        side.hi[a] += 1;
      }
      for_each(side, [&](const Index<Dim>& f) { any = any || coeff[a][f] > 0.0; });
    }
  return any;
}

/// Every backend refuses a non-finite row instead of solving it: the error names the cell and its imbalance.
template <int Dim>
[[noreturn]] void throw_non_finite_row(const Index<Dim>& cell, double imbalance);

/// Today's backend: Eigen's sparse Cholesky (Direct: factorised at the first solve of a step, CG preconditioned by
/// that factorisation after, to cg_tolerance) or incomplete-Cholesky CG to cg_tolerance. Serial: the grid's owned box must be its whole domain.
template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_eigen_structured_solver(const Grid<Dim>& grid,
                                                                    PressureSolverKind kind = PressureSolverKind::Direct,
                                                                    double cg_tolerance = 1e-12);

/// The 2D problem on Grid2 / Field2 arrays for the two-fluid model: the Eigen backend behind it.
class PressureCorrectionSolver {
 public:
  explicit PressureCorrectionSolver(const Grid2& grid, PressureSolverKind kind = PressureSolverKind::Direct,
                                    double cg_tolerance = 1e-12);
  ~PressureCorrectionSolver();
  PressureCorrectionSolver(PressureCorrectionSolver&&) noexcept;
  PressureCorrectionSolver& operator=(PressureCorrectionSolver&&) noexcept;

  /// Solves for x (size nx x ny). ax ((nx+1) x ny) and ay (nx x (ny+1)) hold the coupling coefficient of every
  /// face (see StructuredSolver). x is the initial guess on entry (used by ConjugateGradient). Throws a
  /// simulation error on failure.
  ///
  /// With `reuse_factorisation` (Direct kind, after a first solve) the matrix is not factorised again: the system
  /// is solved by conjugate gradients preconditioned with the last factorisation, to a relative residual of
  /// cg_tolerance (also the ConjugateGradient kind's). Within one SIMPLE step the coefficients change little between iterations, so a few CG iterations
  /// (one triangular solve each) replace a factorisation.
  void solve(const Field2& ax, const Field2& ay, const Field2& rhs, Field2& x, bool reuse_factorisation = false);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fluidbed
