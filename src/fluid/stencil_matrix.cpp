#include "fluid/stencil_matrix.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace fluidbed {
namespace {

// x - x is +0 for every finite x and NaN for inf and NaN: the OR of the bits is zero exactly when all are finite
// (a loop that vectorises, unlike one that tests each value).
bool all_finite(const double* v, Eigen::Index n) {
  std::uint64_t bits = 0;
  for (Eigen::Index k = 0; k < n; ++k) bits |= std::bit_cast<std::uint64_t>(v[k] - v[k]);
  return bits == 0;
}

}  // namespace

template <std::size_t N>
void StencilMatrix::build_impl(int n, const std::vector<std::array<int, N>>& neighbours) {
  constexpr int kSlots = static_cast<int>(N) + 1;
  slots_ = kSlots;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(n) * kSlots);
  for (int r = 0; r < n; ++r) {
    triplets.emplace_back(r, r, 1.0);
    for (int c : neighbours[static_cast<std::size_t>(r)])
      if (c >= 0) triplets.emplace_back(r, c, 0.0);
  }
  matrix_ = Matrix(n, n);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();
  offset_.assign(static_cast<std::size_t>(n) * kSlots, -1);
  const int* outer = matrix_.outerIndexPtr();
  const int* inner = matrix_.innerIndexPtr();
  const auto find = [&](int r, int c) {
    for (int k = outer[r]; k < outer[r + 1]; ++k)
      if (inner[k] == c) return k;
    return -1;
  };
  for (int r = 0; r < n; ++r) {
    offset_[static_cast<std::size_t>(r) * kSlots] = find(r, r);
    for (int k = 0; k < static_cast<int>(N); ++k) {
      const int c = neighbours[static_cast<std::size_t>(r)][static_cast<std::size_t>(k)];
      offset_[static_cast<std::size_t>(r) * kSlots + 1 + k] = c >= 0 ? find(r, c) : -1;
    }
  }
}

template void StencilMatrix::build_impl(int, const std::vector<std::array<int, 4>>&);
template void StencilMatrix::build_impl(int, const std::vector<std::array<int, 6>>&);

void StencilMatrix::build_cells(int nx, int ny) {
  std::vector<std::array<int, 4>> nb(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      nb[static_cast<std::size_t>(r)] = {i > 0 ? r - 1 : -1, i < nx - 1 ? r + 1 : -1, j > 0 ? r - nx : -1,
                                         j < ny - 1 ? r + nx : -1};
    }
  build(nx * ny, nb);
}

double backward_error(const StencilMatrix::Matrix& a, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  double a_norm = 0.0;
  for (Eigen::Index r = 0; r < a.outerSize(); ++r) {
    double row = 0.0;
    for (StencilMatrix::Matrix::InnerIterator it(a, r); it; ++it) row += std::abs(it.value());
    a_norm = std::max(a_norm, row);
  }
  const double denom = a_norm * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>();
  const double r = (a * x - b).lpNorm<Eigen::Infinity>();
  if (!std::isfinite(r) || !std::isfinite(denom)) return INFINITY;
  return denom > 0.0 ? r / denom : r;
}

LinearSolveOutcome CheckedSparseSolver::solve(const Matrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  LinearSolveOutcome out;
  const Eigen::Index n = a.rows();
  if (x.size() != n) x = Eigen::VectorXd::Zero(n);
  // A non-finite coefficient makes every solver's answer meaningless: name the row instead of iterating. The
  // common all-finite case is one branch-free scan of the stored values; rows are looked at only after a hit.
  const bool scanned = a.isCompressed() && all_finite(a.valuePtr(), a.nonZeros()) && all_finite(b.data(), n);
  for (Eigen::Index r = 0; !scanned && r < n && out.bad_row < 0; ++r) {
    bool finite = std::isfinite(b[r]);
    for (Matrix::InnerIterator it(a, r); it && finite; ++it) finite = std::isfinite(it.value());
    if (!finite) out.bad_row = static_cast<int>(r);
  }
  if (out.bad_row >= 0) {
    out.why = "non-finite coefficient or right-hand side in row " + std::to_string(out.bad_row);
    return out;
  }
  bicgstab_.compute(a);
  Eigen::VectorXd& y = y_;  // kept between calls: no allocation per solve
  y = bicgstab_.solveWithGuess(b, x);
  out.iterations = static_cast<int>(bicgstab_.iterations());
  out.error = bicgstab_.error();
  if (bicgstab_.info() == Eigen::Success && y.allFinite()) {
    out.ok = true;
    x.swap(y);
    return out;
  }
  // BiCGSTAB ran out of iterations or broke down: a direct factorisation does not depend on convergence.
  out.fell_back = true;
  const Eigen::SparseMatrix<double, Eigen::ColMajor, int> a_col = a;
  Eigen::SparseLU<Eigen::SparseMatrix<double, Eigen::ColMajor, int>> lu;
  lu.compute(a_col);
  if (lu.info() != Eigen::Success) {
    out.why = "BiCGSTAB stopped at relative residual " + std::to_string(out.error) + " after " +
              std::to_string(out.iterations) + " iterations and the sparse LU failed (" + lu.lastErrorMessage() +
              "): the matrix is singular";
    return out;
  }
  y = lu.solve(b);
  out.backward_error = y.allFinite() ? backward_error(a, y, b) : INFINITY;
  if (!(out.backward_error <= kDirectBackwardError)) {
    out.why = "BiCGSTAB stopped at relative residual " + std::to_string(out.error) + " after " +
              std::to_string(out.iterations) + " iterations and the sparse LU answer has backward error " +
              std::to_string(out.backward_error) + ": the matrix is singular to working precision";
    return out;
  }
  out.ok = true;
  x.swap(y);
  return out;
}

}  // namespace fluidbed
