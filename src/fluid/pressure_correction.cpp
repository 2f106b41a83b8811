#include "fluid/pressure_correction.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "fluid/stencil_matrix.hpp"

namespace fluidbed {

namespace {

/// An Eigen preconditioner that applies a factorisation computed earlier for a nearby matrix.
class StaleLdltPreconditioner {
 public:
  using Ldlt = Eigen::SimplicialLDLT<StencilMatrix::Matrix>;
  StaleLdltPreconditioner() = default;
  template <typename M>
  explicit StaleLdltPreconditioner(const M&) {}
  void use(const Ldlt* ldlt) { ldlt_ = ldlt; }
  template <typename M>
  StaleLdltPreconditioner& analyzePattern(const M&) { return *this; }
  template <typename M>
  StaleLdltPreconditioner& factorize(const M&) { return *this; }
  template <typename M>
  StaleLdltPreconditioner& compute(const M&) { return *this; }
  template <typename Rhs>
  auto solve(const Eigen::MatrixBase<Rhs>& b) const { return ldlt_->solve(b); }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  const Ldlt* ldlt_ = nullptr;
};

}  // namespace

struct PressureCorrectionSolver::Impl {
  Grid2 grid;
  PressureSolverKind kind;
  StencilMatrix a;
  Eigen::SimplicialLDLT<StencilMatrix::Matrix> ldlt;
  Eigen::ConjugateGradient<StencilMatrix::Matrix, Eigen::Lower | Eigen::Upper,
                           Eigen::IncompleteCholesky<double>>
      cg;
  Eigen::ConjugateGradient<StencilMatrix::Matrix, Eigen::Lower | Eigen::Upper, StaleLdltPreconditioner> pcg;
  bool analysed = false;
  bool factorised = false;
  Eigen::VectorXd b;
  Eigen::VectorXd x;
};

PressureCorrectionSolver::PressureCorrectionSolver(const Grid2& grid, PressureSolverKind kind, double cg_tolerance)
    : impl_(std::make_unique<Impl>()) {
  impl_->grid = grid;
  impl_->kind = kind;
  const int nx = grid.nx;
  const int ny = grid.ny;
  impl_->a.build_cells(nx, ny);
  impl_->cg.setTolerance(cg_tolerance);
  impl_->pcg.setTolerance(1e-12);
  impl_->b.resize(nx * ny);
  impl_->x.resize(nx * ny);
}

PressureCorrectionSolver::~PressureCorrectionSolver() = default;
PressureCorrectionSolver::PressureCorrectionSolver(PressureCorrectionSolver&&) noexcept = default;
PressureCorrectionSolver& PressureCorrectionSolver::operator=(PressureCorrectionSolver&&) noexcept = default;

void PressureCorrectionSolver::solve(const Field2& ax, const Field2& ay, const Field2& rhs, Field2& x,
                                     bool reuse_factorisation) {
  Impl& s = *impl_;
  const int nx = s.grid.nx;
  const int ny = s.grid.ny;
  bool has_boundary = false;
  for (int j = 0; j < ny; ++j) has_boundary = has_boundary || ax(0, j) > 0.0 || ax(nx, j) > 0.0;
  for (int i = 0; i < nx; ++i) has_boundary = has_boundary || ay(i, 0) > 0.0 || ay(i, ny) > 0.0;
  // Pinning the first cell of an all-Neumann problem: drop its couplings from both its row and its neighbours'
  // rows, which keeps the matrix symmetric (the pinned value is zero, so the dropped terms vanish).
  const bool pin = !has_boundary;
#pragma omp parallel for schedule(static) if (nx * ny >= kParallelCells)
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      const double aw = ax(i, j);
      const double ae = ax(i + 1, j);
      const double as = ay(i, j);
      const double an = ay(i, j + 1);
      std::array<double, 4> off{-aw, -ae, -as, -an};
      double diag = aw + ae + as + an;
      double b = rhs(i, j);
      if (pin) {
        if (r == 0) {
          off = {0.0, 0.0, 0.0, 0.0};
          diag = 1.0;
          b = 0.0;
        } else {
          if (r == 1) off[0] = 0.0;
          if (r == nx) off[2] = 0.0;
        }
      }
      if (!(diag > 0.0)) diag = 1.0;  // a cell with no open face: p' is free, keep it at zero
      s.a.set_row(r, diag, off);
      s.b[r] = b;
      s.x[r] = x(i, j);
    }
  // A non-finite coefficient or imbalance makes any answer meaningless: name the cell instead of solving.
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (!std::isfinite(rhs(i, j)) || !std::isfinite(ax(i, j)) || !std::isfinite(ax(i + 1, j)) ||
          !std::isfinite(ay(i, j)) || !std::isfinite(ay(i, j + 1))) {
        throw_simulation_error("gas pressure correction: the mass imbalance or a face coefficient of cell (" +
                               std::to_string(i) + ", " + std::to_string(j) + ") is not finite (imbalance " +
                               std::to_string(rhs(i, j)) + ")");
      }
    }
  bool solved = false;
  if (s.kind == PressureSolverKind::Direct && reuse_factorisation && s.factorised) {
    s.pcg.compute(s.a.matrix());
    s.pcg.preconditioner().use(&s.ldlt);
    const Eigen::VectorXd guess = s.x;
    s.x = s.pcg.solveWithGuess(s.b, guess);
    solved = s.pcg.info() == Eigen::Success && s.x.allFinite();
    if (!solved) s.x = guess;  // the matrix moved too far from the factorised one: factorise it below
  }
  std::string cg_failure;
  if (!solved && s.kind == PressureSolverKind::ConjugateGradient) {
    s.cg.compute(s.a.matrix());
    const Eigen::VectorXd guess = s.x;
    s.x = s.cg.solveWithGuess(s.b, guess);
    solved = s.cg.info() == Eigen::Success && s.x.allFinite();
    if (!solved) {
      // Not accepted: the factorisation below answers instead (it does not depend on convergence).
      cg_failure = "conjugate gradient stopped at relative residual " + std::to_string(s.cg.error()) + " after " +
                   std::to_string(s.cg.iterations()) + " iterations; ";
      s.x = guess;
    }
  }
  if (!solved) {
    if (!s.analysed) {
      s.ldlt.analyzePattern(s.a.matrix());
      s.analysed = true;
    }
    s.ldlt.factorize(s.a.matrix());
    if (s.ldlt.info() != Eigen::Success) {
      throw_simulation_error("gas pressure correction: " + cg_failure +
                             "the LDLT factorisation failed (the matrix is not positive definite: a face coefficient "
                             "is negative or not finite)");
    }
    s.factorised = true;
    s.x = s.ldlt.solve(s.b);
    // Finite and backward stable, or not accepted (a zero pivot that LDLT does not report shows up here).
    const double err = backward_error(s.a.matrix(), s.x, s.b);
    if (!(err <= kDirectBackwardError)) {
      throw_simulation_error("gas pressure correction: " + cg_failure + "the LDLT answer has backward error " +
                             std::to_string(err) + " (the matrix is singular or not finite)");
    }
  }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) x(i, j) = s.x[j * nx + i];
}

}  // namespace fluidbed
