#include "numerics/stencil_matrix.hpp"

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

void CheckedSparseSolver::take_diagonals(const Matrix& a) {
  const Eigen::Index n = a.rows(), nnz = a.nonZeros();
  by_diagonals_ = false;
  if (!a.isCompressed() || a.cols() != n) return;
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const bool same = pattern_.size() == static_cast<std::size_t>(n + 1 + nnz) &&
                    std::equal(outer, outer + n + 1, pattern_.begin()) &&
                    std::equal(inner, inner + nnz, pattern_.begin() + n + 1);
  if (!same) {
    pattern_.assign(outer, outer + n + 1);
    pattern_.insert(pattern_.end(), inner, inner + nnz);
    offsets_.clear();
    bool sorted = true;
    for (Eigen::Index r = 0; r < n && sorted; ++r)
      for (int k = outer[r]; k < outer[r + 1]; ++k) {
        sorted = sorted && (k == outer[r] || inner[k] > inner[k - 1]);
        const int off = inner[k] - static_cast<int>(r);
        if (std::find(offsets_.begin(), offsets_.end(), off) == offsets_.end()) offsets_.push_back(off);
      }
    // Rows summed in column order, as Eigen does, only if the diagonals in ascending order meet each row so.
    if (!sorted || offsets_.size() > static_cast<std::size_t>(kMaxDiagonals)) {
      offsets_.clear();
      return;
    }
    std::sort(offsets_.begin(), offsets_.end());
    slot_.resize(static_cast<std::size_t>(nnz));
    for (Eigen::Index r = 0; r < n; ++r)
      for (int k = outer[r]; k < outer[r + 1]; ++k) {
        const auto d = std::find(offsets_.begin(), offsets_.end(), inner[k] - static_cast<int>(r)) - offsets_.begin();
        slot_[static_cast<std::size_t>(k)] = static_cast<int>(d * n + r);
      }
    diagonals_.assign(offsets_.size() * static_cast<std::size_t>(n), 0.0);  // the entries no row has stay zero
  }
  if (offsets_.empty()) return;
  const double* val = a.valuePtr();
  for (Eigen::Index k = 0; k < nnz; ++k) diagonals_[static_cast<std::size_t>(slot_[static_cast<std::size_t>(k)])] = val[k];
  by_diagonals_ = true;
}

// Eigen's sparse * dense product (SparseDenseProduct.h) adds each row's products in column order to a sum that
// starts at zero. By diagonals, in ascending offset order, every row sees the same additions in the same order:
// the same bits, since a zero entry adds +-0 to a sum that is never -0 (x finite; a non-finite x fails the solve
// either way). The diagonal loops vectorise; the row loop of a compressed matrix waits on one chain per row.
void CheckedSparseSolver::multiply(const Matrix& a, const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  if (!by_diagonals_) {
    y.noalias() = a * x;
    return;
  }
  const int n = static_cast<int>(a.rows());
  const int nd = static_cast<int>(offsets_.size());
  const double* px = x.data();
  double* py = y.data();
  std::array<const double*, kMaxDiagonals> pa{};
  for (int d = 0; d < nd; ++d) pa[static_cast<std::size_t>(d)] = diagonals_.data() + static_cast<std::size_t>(d) * n;
  // Rows where every diagonal has its column inside the matrix: all terms of a row in one expression, in the
  // same ascending order (five or seven diagonals: the 2D and 3D stencils); the other rows term by term.
  const int first = std::clamp(-offsets_.front(), 0, n), last = std::clamp(n - offsets_.back(), first, n);
  auto row = [&](int r) {
    double sum = 0.0;
    for (int d = 0; d < nd; ++d) {
      const int c = r + offsets_[static_cast<std::size_t>(d)];
      if (c >= 0 && c < n) sum += pa[static_cast<std::size_t>(d)][r] * px[c];
    }
    py[r] = sum;
  };
  for (int r = 0; r < first; ++r) row(r);
  const int* o = offsets_.data();
  if (nd == 5) {
    const double *a0 = pa[0], *a1 = pa[1], *a2 = pa[2], *a3 = pa[3], *a4 = pa[4];
    const double *x0 = px + o[0], *x1 = px + o[1], *x2 = px + o[2], *x3 = px + o[3], *x4 = px + o[4];
    for (int r = first; r < last; ++r)
      py[r] = ((((0.0 + a0[r] * x0[r]) + a1[r] * x1[r]) + a2[r] * x2[r]) + a3[r] * x3[r]) + a4[r] * x4[r];
  } else if (nd == 7) {
    const double *a0 = pa[0], *a1 = pa[1], *a2 = pa[2], *a3 = pa[3], *a4 = pa[4], *a5 = pa[5], *a6 = pa[6];
    const double *x0 = px + o[0], *x1 = px + o[1], *x2 = px + o[2], *x3 = px + o[3], *x4 = px + o[4],
                 *x5 = px + o[5], *x6 = px + o[6];
    for (int r = first; r < last; ++r)
      py[r] = ((((((0.0 + a0[r] * x0[r]) + a1[r] * x1[r]) + a2[r] * x2[r]) + a3[r] * x3[r]) + a4[r] * x4[r]) +
               a5[r] * x5[r]) +
              a6[r] * x6[r];
  } else {
    for (int r = first; r < last; ++r) row(r);
  }
  for (int r = last; r < n; ++r) row(r);
}

bool CheckedSparseSolver::bicgstab(const Matrix& a, const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
                                   LinearSolveOutcome& out) {
  using std::abs;
  using std::sqrt;
  take_diagonals(a);
  // Jacobi: 1 / a_jj, or 1 where the diagonal is absent or zero (Eigen's DiagonalPreconditioner, whose search
  // for each row's diagonal entry the diagonal layout makes unnecessary).
  const Eigen::Index n_rows = a.rows();
  invdiag_.resize(n_rows);
  const auto d0 = std::find(offsets_.begin(), offsets_.end(), 0);
  if (by_diagonals_ && d0 != offsets_.end()) {
    const double* diag = diagonals_.data() + static_cast<std::size_t>(d0 - offsets_.begin()) * static_cast<std::size_t>(n_rows);
    for (Eigen::Index j = 0; j < n_rows; ++j) invdiag_[j] = diag[j] != 0.0 ? 1.0 / diag[j] : 1.0;
  } else if (by_diagonals_) {
    invdiag_.setOnes();
  } else {
    Eigen::DiagonalPreconditioner<double> jacobi;
    jacobi.compute(a);
    invdiag_ = jacobi.solve(Eigen::VectorXd::Ones(n_rows));
  }
  const Eigen::Index n = a.cols();
  const Eigen::Index max_iters = max_iterations_ < 0 ? 2 * n : max_iterations_;
  const double tol = tolerance_;
  for (Eigen::VectorXd* v : {&r_, &r0_, &v_, &p_, &y_, &z_, &s_, &t_}) v->resize(n);
  Eigen::VectorXd &r = r_, &r0 = r0_, &v = v_, &p = p_, &y = y_, &z = z_, &s = s_, &t = t_;
  multiply(a, x, t);
  r = rhs - t;
  r0 = r;
  double r0_sqnorm = r0.squaredNorm();
  const double rhs_sqnorm = rhs.squaredNorm();
  if (rhs_sqnorm == 0) {  // Eigen leaves its iteration count and error estimate at their limits here
    x.setZero();
    out.iterations = static_cast<int>(max_iters);
    out.error = tol;
    return true;
  }
  double rho = 1, alpha = 1, w = 1;
  v.setZero();
  p.setZero();
  const double tol2 = tol * tol * rhs_sqnorm;
  const double eps2 = Eigen::NumTraits<double>::epsilon() * Eigen::NumTraits<double>::epsilon();
  Eigen::Index i = 0, restarts = 0;
  while (r.squaredNorm() > tol2 && i < max_iters) {
    const double rho_old = rho;
    rho = r0.dot(r);
    if (abs(rho) < eps2 * r0_sqnorm) {
      // The residual became too orthogonal to r0: restart with a new r0.
      multiply(a, x, t);
      r = rhs - t;
      r0 = r;
      rho = r0_sqnorm = r.squaredNorm();
      if (restarts++ == 0) i = 0;
    }
    const double beta = (rho / rho_old) * (alpha / w);
    p = r + beta * (p - w * v);
    y = invdiag_.array() * p.array();
    multiply(a, y, v);
    alpha = rho / r0.dot(v);
    s = r - alpha * v;
    z = invdiag_.array() * s.array();
    multiply(a, z, t);
    const double tmp = t.squaredNorm();
    w = tmp > 0.0 ? t.dot(s) / tmp : 0.0;
    x += alpha * y + w * z;
    r = s - w * t;
    ++i;
  }
  out.error = sqrt(r.squaredNorm() / rhs_sqnorm);
  out.iterations = static_cast<int>(i);
  return out.error <= tol;
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
  Eigen::VectorXd& y = trial_;  // kept between solves: the swap below trades two buffers of the same size
  y = x;
  if (bicgstab(a, b, y, out) && y.allFinite()) {
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
