#pragma once
// Pressure-correction equation of SIMPLE on cell centres: aP p'_P - sum_nb a_nb p'_nb = b, aP = sum of the
// four face coefficients. Reused by the gas solver and the two-fluid model.
#include <memory>

#include "core/field2.hpp"
#include "core/grid2.hpp"

namespace fluidbed {

enum class PressureSolverKind {
  Direct,             ///< Eigen SimplicialLDLT, symbolic analysis done once
  ConjugateGradient,  ///< Eigen ConjugateGradient + IncompleteCholesky, warm-started
};

class PressureCorrectionSolver {
 public:
  explicit PressureCorrectionSolver(const Grid2& grid, PressureSolverKind kind = PressureSolverKind::Direct,
                                    double cg_tolerance = 1e-12);
  ~PressureCorrectionSolver();
  PressureCorrectionSolver(PressureCorrectionSolver&&) noexcept;
  PressureCorrectionSolver& operator=(PressureCorrectionSolver&&) noexcept;

  /// Solves for x (size nx x ny). ax ((nx+1) x ny) and ay (nx x (ny+1)) hold the coupling coefficient of every
  /// face; a coefficient on a boundary face couples to p' = 0 outside (a fixed-pressure boundary); zero there means
  /// an impermeable face. If no boundary face has a coefficient the system is singular and cell (0, 0) is pinned
  /// to p' = 0. x is the initial guess on entry (used by ConjugateGradient). Throws a simulation error on failure.
  ///
  /// With `reuse_factorisation` (Direct kind, after a first solve) the matrix is not factorised again: the system
  /// is solved by conjugate gradients preconditioned with the last factorisation, to a relative residual of
  /// 1e-12. Within one SIMPLE step the coefficients change little between iterations, so a few CG iterations
  /// (one triangular solve each) replace a factorisation.
  void solve(const Field2& ax, const Field2& ay, const Field2& rhs, Field2& x, bool reuse_factorisation = false);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fluidbed
