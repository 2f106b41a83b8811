#pragma once
// Pressure-correction equation of SIMPLE on cell centres: aP p'_P - sum_nb a_nb p'_nb = b, aP = sum of the
// 2 Dim face coefficients. A structured problem (one coefficient per cell face, cells of a box), solved behind one
// interface by three backends: Eigen's sparse Cholesky here, hypre's structured multigrid
// (structured_solver_hypre.hpp) and the band LDL^T of thin slabs (band_pressure_solver.hpp). The CFD-DEM gas
// solver and the two-fluid model both solve through it.
#include <array>
#include <memory>

#include "core/field.hpp"
#include "core/grid.hpp"

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
  /// The relative residual the iterative solves stop at from now on (a direct backend's solves are exact and
  /// ignore it). The CFD-DEM gas tightens it for the last correction of a step that SIMPLE ends early, so that
  /// continuity still holds to its mass tolerance.
  virtual void set_tolerance(double relative) = 0;
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

/// The Eigen backend: sparse Cholesky (Direct: factorised at the first solve of a step, CG preconditioned by
/// that factorisation after, to cg_tolerance) or incomplete-Cholesky CG to cg_tolerance. Serial: the grid's owned box must be its whole domain.
template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_eigen_structured_solver(const Grid<Dim>& grid,
                                                                    PressureSolverKind kind = PressureSolverKind::Direct,
                                                                    double cg_tolerance = 1e-12);

}  // namespace fluidbed
