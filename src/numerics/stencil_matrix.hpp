#pragma once
// A sparse matrix whose pattern (self and up to 2 Dim neighbours per row: five points in 2D, seven in 3D) is
// fixed once, so repeated assemblies write values in place and factorisations can reuse their symbolic analysis.
#include <array>
#include <string>
#include <vector>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

namespace fluidbed {

/// Loops over fewer cells than this run serially: thread start-up would cost more than the work.
inline constexpr int kParallelCells = 16384;

class StencilMatrix {
 public:
  using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

  /// neighbours[row] lists up to four (2D) or six (3D) column indices; -1 where there is none. The pattern of a
  /// row is its diagonal and these columns, in the order given (the slot order of set_row).
  void build(int n, const std::vector<std::array<int, 4>>& neighbours) { build_impl(n, neighbours); }
  void build(int n, const std::vector<std::array<int, 6>>& neighbours) { build_impl(n, neighbours); }
  /// The cell-centred five-point pattern of an nx x ny grid, rows numbered i fastest (row j nx + i), neighbours
  /// in the order W, E, S, N.
  void build_cells(int nx, int ny);

  int rows() const { return slots_ > 0 ? static_cast<int>(offset_.size()) / slots_ : 0; }
  /// Writes one row: diagonal and the neighbour coefficients (ignored where the neighbour is -1); the row's
  /// neighbour count must be the one the pattern was built with.
  void set_row(int row, double diag, const std::array<double, 4>& off) { set_row_impl(row, diag, off); }
  template <std::size_t N>
  void set_row(int row, double diag, const std::array<double, N>& off) { set_row_impl(row, diag, off); }
  const Matrix& matrix() const { return matrix_; }

 private:
  template <std::size_t N>
  void build_impl(int n, const std::vector<std::array<int, N>>& neighbours);
  template <std::size_t N>
  void set_row_impl(int row, double diag, const std::array<double, N>& off) {
    double* val = matrix_.valuePtr();
    const int* o = &offset_[static_cast<std::size_t>(row) * static_cast<std::size_t>(slots_)];
    val[o[0]] = diag;
    for (std::size_t k = 0; k < N; ++k)
      if (o[k + 1] >= 0) val[o[k + 1]] = off[k];
  }

  Matrix matrix_;
  std::vector<int> offset_;
  int slots_ = 0;  ///< 1 + neighbours per row
};

/// Normwise backward error of an answer, |A x - b|_inf / (|A|_inf |x|_inf + |b|_inf) (Rigal & Gaches 1967): a
/// backward-stable direct solve leaves it near the machine epsilon however ill-conditioned A is, so a large
/// value means the factorisation broke down, not that the matrix is hard.
double backward_error(const StencilMatrix::Matrix& a, const Eigen::VectorXd& x, const Eigen::VectorXd& b);
/// A direct answer is accepted below this backward error.
inline constexpr double kDirectBackwardError = 1e-10;

/// What a checked solve did: BiCGSTAB first, a sparse LU when BiCGSTAB did not reach its tolerance.
struct LinearSolveOutcome {
  bool ok = false;          ///< x holds a finite answer: BiCGSTAB converged, or the LU met kDirectBackwardError
  bool fell_back = false;   ///< BiCGSTAB failed (no convergence or breakdown) and the sparse LU answered
  int iterations = 0;       ///< BiCGSTAB iterations
  double error = 0.0;       ///< BiCGSTAB relative residual estimate when it stopped
  double backward_error = 0.0;  ///< backward_error() of the LU answer (fell_back only)
  int bad_row = -1;         ///< first row with a non-finite coefficient or right-hand side; -1 if none
  std::string why;          ///< when !ok: what failed, in words
};

/// A nonsymmetric sparse system solved by BiCGSTAB with a diagonal preconditioner, checked: when BiCGSTAB stops
/// short of its tolerance (iteration cap or breakdown) the system is solved again by a sparse LU, and an answer
/// is accepted only when it is finite and its relative residual is small. Nothing is accepted silently; the
/// caller turns !ok into a diagnosis with its own context (time, cell, likely cause).
class CheckedSparseSolver {
 public:
  using Matrix = StencilMatrix::Matrix;
  void set_tolerance(double tol) { tolerance_ = tol; }
  /// At most this many BiCGSTAB iterations; 0: Eigen's default (twice the size).
  void set_max_iterations(int n) {
    if (n > 0) max_iterations_ = n;
  }
  /// Solves a x = b; x is the initial guess on entry (zero for an empty vector) and the answer on exit.
  LinearSolveOutcome solve(const Matrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x);

 private:
  /// Eigen's BiCGSTAB (Eigen/src/IterativeLinearSolvers/BiCGSTAB.h, 3.4) step for step, with the same vector
  /// expressions, on vectors kept between calls, and the sparse products by multiply(): the same bits. Returns
  /// whether it converged; iterations and the relative residual estimate in `out`.
  bool bicgstab(const Matrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, LinearSolveOutcome& out);

  /// y = A x, the same bits as Eigen's sparse * dense product. Cloned for AVX-512 and AVX2 (no FMA: every clone
  /// rounds alike).
  __attribute__((target_clones("avx512f", "avx2", "default"))) void multiply(const Matrix& a, const Eigen::VectorXd& x,
                                                                  Eigen::VectorXd& y) const;
  /// Copies the values of a into the diagonal layout (rebuilt when the pattern differs from the last one).
  void take_diagonals(const Matrix& a);

  // The matrix by diagonals (a structured stencil has a few: offsets col - row, ascending), zero where a row
  // has no entry; slot_[k] is where stored value k goes. Used when the pattern has at most kMaxDiagonals.
  static constexpr int kMaxDiagonals = 8;
  std::vector<int> offsets_, slot_, pattern_;
  std::vector<double> diagonals_;
  bool by_diagonals_ = false;

  double tolerance_ = Eigen::NumTraits<double>::epsilon();  // Eigen's default
  int max_iterations_ = -1;                                 // -1: twice the size, as Eigen
  Eigen::VectorXd invdiag_;  // the Jacobi preconditioner: 1 / a_jj (1 where a_jj is absent or zero)
  Eigen::VectorXd r_, r0_, v_, p_, y_, z_, s_, t_;
  Eigen::VectorXd trial_;  // solve()'s iterate, swapped into the caller's x when accepted
};

}  // namespace fluidbed
