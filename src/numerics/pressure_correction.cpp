#include "numerics/pressure_correction.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "numerics/stencil_matrix.hpp"

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


template <int Dim>
class EigenStructuredSolver final : public StructuredSolver<Dim> {
 public:
  EigenStructuredSolver(const Grid<Dim>& grid, PressureSolverKind kind, double cg_tolerance)
      : cells_(grid.owned), periodic_(grid.periodic), kind_(kind) {
    if (!(grid.owned == grid.domain))
      throw_input_error("pressure correction: the Eigen backend solves on one process (owned box = domain)");
    const int n = static_cast<int>(cells_.count());
    // Rows numbered axis 0 fastest; neighbours low and high along each axis in turn (W, E, S, N[, B, F]).
    std::vector<std::array<int, 2 * Dim>> nb(static_cast<std::size_t>(n));
    for_each(cells_, [&](const Index<Dim>& c) {
      std::array<int, 2 * Dim> nbr{};
      for (int a = 0; a < Dim; ++a) {
        nbr[static_cast<std::size_t>(2 * a)] = c[a] > cells_.lo[a] ? row(shifted<Dim>(c, a, -1)) : -1;
        nbr[static_cast<std::size_t>(2 * a + 1)] = c[a] < cells_.hi[a] - 1 ? row(shifted<Dim>(c, a, 1)) : -1;
        if (periodic_[static_cast<std::size_t>(a)]) {
          // The neighbour across the periodic plane: the cell at the other end of the row.
          if (c[a] == cells_.lo[a]) nbr[static_cast<std::size_t>(2 * a)] = row(shifted<Dim>(c, a, cells_.extent(a) - 1));
          if (c[a] == cells_.hi[a] - 1)
            nbr[static_cast<std::size_t>(2 * a + 1)] = row(shifted<Dim>(c, a, 1 - cells_.extent(a)));
        }
      }
      nb[static_cast<std::size_t>(row(c))] = nbr;
    });
    a_.build(n, nb);
    cg_.setTolerance(cg_tolerance);
    pcg_.setTolerance(cg_tolerance);
    b_.resize(n);
    x_.resize(n);
  }

  const char* name() const override { return "eigen"; }
  void set_tolerance(double relative) override {
    cg_.setTolerance(relative);
    pcg_.setTolerance(relative);
  }

  void solve(const FaceFields<Dim>& coeff, const Field<Dim>& rhs, Field<Dim>& x, bool reuse_factorisation) override {
    const bool has_boundary = couples_to_boundary<Dim>(cells_, coeff, periodic_);
    // Pinning the first cell of an all-Neumann problem: drop its couplings from both its row and its neighbours'
    // rows, which keeps the matrix symmetric (the pinned value is zero, so the dropped terms vanish).
    const bool pin = !has_boundary;
    const IndexBox<Dim>& b = cells_;
    // Rows along axis 0, in parallel over the others.
    IndexBox<Dim> lines = b;
    lines.hi[0] = lines.lo[0] + 1;
    std::vector<Index<Dim>> starts;
    starts.reserve(lines.count());
    for_each(lines, [&](const Index<Dim>& c) { starts.push_back(c); });
    const int n_lines = static_cast<int>(starts.size());
#pragma omp parallel for schedule(static) if (static_cast<int>(b.count()) >= kParallelCells)
    for (int l = 0; l < n_lines; ++l) {
      Index<Dim> c = starts[static_cast<std::size_t>(l)];
      for (c[0] = b.lo[0]; c[0] < b.hi[0]; ++c[0]) {
        const int r = row(c);
        std::array<double, 2 * Dim> off{};
        double diag = 0.0;
        for (int a = 0; a < Dim; ++a) {
          const double lo = coeff[a][c];
          // On a periodic axis the last face is the first one (the same plane, tied by fill_periodic_ghosts).
          const bool wraps = periodic_[static_cast<std::size_t>(a)] && c[a] == b.hi[a] - 1;
          const double hi = coeff[a][wraps ? shifted<Dim>(c, a, 1 - b.extent(a)) : shifted<Dim>(c, a, 1)];
          off[static_cast<std::size_t>(2 * a)] = -lo;
          off[static_cast<std::size_t>(2 * a + 1)] = -hi;
          diag = a == 0 ? lo + hi : diag + lo + hi;
        }
        double rb = rhs[c];
        if (pin) {
          if (r == 0) {
            off.fill(0.0);
            diag = 1.0;
            rb = 0.0;
          } else {
            for (int a = 0; a < Dim; ++a) {
              if (c == shifted<Dim>(b.lo, a, 1)) off[static_cast<std::size_t>(2 * a)] = 0.0;
              if (periodic_[static_cast<std::size_t>(a)] && c == shifted<Dim>(b.lo, a, b.extent(a) - 1))
                off[static_cast<std::size_t>(2 * a + 1)] = 0.0;
            }
          }
        }
        if (!(diag > 0.0)) diag = 1.0;  // a cell with no open face: p' is free, keep it at zero
        a_.set_row(r, diag, off);
        b_[r] = rb;
        x_[r] = x[c];
      }
    }
    // A non-finite coefficient or imbalance makes any answer meaningless: name the cell instead of solving.
    for_each(b, [&](const Index<Dim>& c) {
      bool finite = std::isfinite(rhs[c]);
      for (int a = 0; a < Dim; ++a)
        finite = finite && std::isfinite(coeff[a][c]) && std::isfinite(coeff[a][shifted<Dim>(c, a, 1)]);
      if (!finite) {
        throw_non_finite_row<Dim>(c, rhs[c]);
      }
    });
    bool solved = false;
    if (kind_ == PressureSolverKind::Direct && reuse_factorisation && factorised_) {
      pcg_.compute(a_.matrix());
      pcg_.preconditioner().use(&ldlt_);
      const Eigen::VectorXd guess = x_;
      x_ = pcg_.solveWithGuess(b_, guess);
      solved = pcg_.info() == Eigen::Success && x_.allFinite();
      if (!solved) x_ = guess;  // the matrix moved too far from the factorised one: factorise it below
    }
    std::string cg_failure;
    if (!solved && kind_ == PressureSolverKind::ConjugateGradient) {
      cg_.compute(a_.matrix());
      const Eigen::VectorXd guess = x_;
      x_ = cg_.solveWithGuess(b_, guess);
      solved = cg_.info() == Eigen::Success && x_.allFinite();
      if (!solved) {
        // Not accepted: the factorisation below answers instead (it does not depend on convergence).
        cg_failure = "conjugate gradient stopped at relative residual " + std::to_string(cg_.error()) + " after " +
                     std::to_string(cg_.iterations()) + " iterations; ";
        x_ = guess;
      }
    }
    if (!solved) {
      if (!analysed_) {
        ldlt_.analyzePattern(a_.matrix());
        analysed_ = true;
      }
      ldlt_.factorize(a_.matrix());
      if (ldlt_.info() != Eigen::Success) {
        throw_simulation_error("gas pressure correction: " + cg_failure +
                               "the LDLT factorisation failed (the matrix is not positive definite: a face "
                               "coefficient is negative or not finite)");
      }
      factorised_ = true;
      x_ = ldlt_.solve(b_);
      // Finite and backward stable, or not accepted (a zero pivot that LDLT does not report shows up here).
      const double err = backward_error(a_.matrix(), x_, b_);
      if (!(err <= kDirectBackwardError)) {
        throw_simulation_error("gas pressure correction: " + cg_failure + "the LDLT answer has backward error " +
                               std::to_string(err) + " (the matrix is singular or not finite)");
      }
    }
    for_each(b, [&](const Index<Dim>& c) { x[c] = x_[row(c)]; });
  }

 private:
  int row(const Index<Dim>& c) const {
    int r = 0;
    int stride = 1;
    for (int a = 0; a < Dim; ++a) {
      r += (c[a] - cells_.lo[a]) * stride;
      stride *= cells_.extent(a);
    }
    return r;
  }

  IndexBox<Dim> cells_;
  std::array<bool, Dim> periodic_{};
  PressureSolverKind kind_;
  StencilMatrix a_;
  Eigen::SimplicialLDLT<StencilMatrix::Matrix> ldlt_;
  Eigen::ConjugateGradient<StencilMatrix::Matrix, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double>> cg_;
  Eigen::ConjugateGradient<StencilMatrix::Matrix, Eigen::Lower | Eigen::Upper, StaleLdltPreconditioner> pcg_;
  bool analysed_ = false;
  bool factorised_ = false;
  Eigen::VectorXd b_;
  Eigen::VectorXd x_;
};

}  // namespace

template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_eigen_structured_solver(const Grid<Dim>& grid, PressureSolverKind kind,
                                                                    double cg_tolerance) {
  return std::make_unique<EigenStructuredSolver<Dim>>(grid, kind, cg_tolerance);
}
template <int Dim>
void throw_non_finite_row(const Index<Dim>& cell, double imbalance) {
  std::string name = "(";
  for (int a = 0; a < Dim; ++a) name += (a > 0 ? ", " : "") + std::to_string(cell[a]);
  throw_simulation_error("gas pressure correction: the mass imbalance or a face coefficient of cell " + name +
                         ") is not finite (imbalance " + std::to_string(imbalance) + ")");
}

template void throw_non_finite_row<2>(const Index<2>&, double);
template void throw_non_finite_row<3>(const Index<3>&, double);
template std::unique_ptr<StructuredSolver<2>> make_eigen_structured_solver(const Grid<2>&, PressureSolverKind, double);
template std::unique_ptr<StructuredSolver<3>> make_eigen_structured_solver(const Grid<3>&, PressureSolverKind, double);

}  // namespace fluidbed
