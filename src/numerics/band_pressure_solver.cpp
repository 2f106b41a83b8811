#include "numerics/band_pressure_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "numerics/stencil_matrix.hpp"

namespace fluidbed {
namespace {

template <int Dim>
class BandStructuredSolver final : public StructuredSolver<Dim> {
 public:
  // Rows numbered with the axes in `order`, the first fastest; the band is the stride of the last.
  BandStructuredSolver(const IndexBox<Dim>& cells, const std::array<int, Dim>& order, BandReuse reuse, double tolerance)
      : cells_(cells), n_(static_cast<int>(cells.count())), reuse_(reuse), tolerance_(tolerance) {
    for (int i = 0, s = 1; i < Dim; ++i) {
      const int a = order[static_cast<std::size_t>(i)];
      stride_[static_cast<std::size_t>(a)] = s;
      kd_ = s;
      s *= cells.extent(a);
    }
    const auto n = static_cast<std::size_t>(n_);
    diag_.resize(n);
    for (auto& l : low_) l.resize(n);
    band_.resize(n * static_cast<std::size_t>(kd_ + 1) + kLanes);  // + the last block's whole-vector overrun
    b_.resize(n);
    x_.resize(n);
    if (reuse_ == BandReuse::Preconditioner)
      for (auto* v : {&r_, &z_, &p_, &q_}) v->resize(n);
  }

  const char* name() const override { return "band"; }
  // Only the preconditioned reuse stops early; a factorisation's answer is exact.
  void set_tolerance(double relative) override { tolerance_ = relative; }

  void solve(const FaceFields<Dim>& coeff, const Field<Dim>& rhs, Field<Dim>& x, bool reuse_factorisation) override {
    assemble(coeff, rhs);
    bool solved = false;
    if (reuse_factorisation && factorised_) {
      if (reuse_ == BandReuse::Preconditioner) {
        solved = preconditioned_cg(x);
      } else {
        substitute(b_, x_);
        solved = backward_error() <= kDirectBackwardError;  // the same matrix, unless the caller's coefficients moved
      }
    }
    if (!solved) {
      factorise();
      substitute(b_, x_);
      const double err = backward_error();
      // Finite and backward stable, or not accepted.
      if (!(err <= kDirectBackwardError)) {
        throw_simulation_error("gas pressure correction: the band LDLT answer has backward error " +
                               std::to_string(err) + " (the matrix is singular or not finite)");
      }
    }
    for_each(cells_, [&](const Index<Dim>& c) { x[c] = x_[row(c)]; });
  }

 private:
  std::size_t row(const Index<Dim>& c) const {
    std::size_t r = 0;
    for (int a = 0; a < Dim; ++a)
      r += static_cast<std::size_t>(c[a] - cells_.lo[a]) * static_cast<std::size_t>(stride_[static_cast<std::size_t>(a)]);
    return r;
  }

  // The matrix of the problem (rows in the solver's order): diagonal and the coupling to the lower neighbour along
  // each axis (the upper ones follow by symmetry), built as fluid/pressure_correction.cpp's Eigen backend builds it.
  void assemble(const FaceFields<Dim>& coeff, const Field<Dim>& rhs) {
    const IndexBox<Dim>& b = cells_;
    // An all-Neumann problem pins the first cell (row 0 in every order): its couplings are dropped from its row
    // and its neighbours'.
    const bool pin = !couples_to_boundary<Dim>(b, coeff);
    for_each(b, [&](const Index<Dim>& c) {
      const std::size_t r = row(c);
      bool finite = std::isfinite(rhs[c]);
      double diag = 0.0;
      for (int a = 0; a < Dim; ++a) {
        const double lo = coeff[a][c], hi = coeff[a][shifted<Dim>(c, a, 1)];
        finite = finite && std::isfinite(lo) && std::isfinite(hi);
        diag = a == 0 ? lo + hi : diag + lo + hi;
        low_[static_cast<std::size_t>(a)][r] = c[a] > b.lo[a] && !(pin && c == shifted<Dim>(b.lo, a, 1)) ? -lo : 0.0;
      }
      if (!finite) {
        throw_non_finite_row<Dim>(c, rhs[c]);
      }
      double rb = rhs[c];
      if (pin && r == 0) {
        diag = 1.0;
        rb = 0.0;
      }
      if (!(diag > 0.0)) diag = 1.0;  // a cell with no open face: p' is free, keep it at zero
      diag_[r] = diag;
      b_[r] = rb;
    });
  }

  // Band LDL^T in place, column k holding L(k + i, k) at offset i and d_k at offset 0 (right-looking: the update
  // of each later column is one contiguous pass). Pivots go kPivots at a time (a rank-kPivots update, loaded and
  // stored once); every entry still takes the updates of the pivots in their order, as one pivot at a time.
  // Cloned for AVX-512 and AVX2; -ffp-contract=off (CMakeLists.txt) keeps FMA out, so every clone rounds alike.
  __attribute__((target_clones("avx512f", "avx2", "default"))) void factorise() {
    const int w = kd_ + 1;
    std::fill(band_.begin(), band_.end(), 0.0);
    for (int r = 0; r < n_; ++r) {
      band_[static_cast<std::size_t>(r) * w] = diag_[static_cast<std::size_t>(r)];
      for (int a = 0; a < Dim; ++a) {
        const int s = stride_[static_cast<std::size_t>(a)];
        const double v = low_[static_cast<std::size_t>(a)][static_cast<std::size_t>(r)];
        if (v != 0.0) band_[static_cast<std::size_t>(r - s) * w + s] = v;
      }
    }
    int k = 0;
    for (; k + kPivots <= n_; k += kPivots) pivot_block<kPivots>(k);
    for (; k < n_; ++k) pivot_block<1>(k);  // the last rows
    factorised_ = true;
  }

  static constexpr int kPivots = 4;
  static constexpr int kLanes = 8;  // the widest clone's doubles per vector

  // Pivots k .. k + P - 1. t_[p][r] holds column k + p before its scaling, A(k + r, k + p), at rows r relative to
  // k and zero outside that column's band, so a later column's pass subtracts f * 0 = 0 where a pivot does not
  // reach: the entry is unchanged bit for bit (no entry of the factorisation is ever -0: it starts at +0 or a
  // non-zero, and x - y rounds an exact cancellation to +0).
  template <int P>
  [[gnu::always_inline]] inline void pivot_block(int k) {
    const int w = kd_ + 1;
    std::array<int, P> m{};  // column k + p reaches rows up to k + p + m[p]
    const int rows = std::min(P - 1 + kd_, n_ - 1 - k);  // the block's last row, relative to k
    for (int p = 0; p < P; ++p) {
      double* cp = &band_[static_cast<std::size_t>(k + p) * w];
      m[p] = std::min(kd_, n_ - 1 - k - p);
      const double dk = cp[0];
      if (!(dk > 0.0) || !std::isfinite(dk)) {
        throw_simulation_error("gas pressure correction: the band LDLT factorisation failed at row " +
                               std::to_string(k + p) + " (pivot " + std::to_string(dk) +
                               ": the matrix is not positive definite, a face coefficient is negative or not finite)");
      }
      double* t = t_[static_cast<std::size_t>(p)].data();
      for (int r = 0; r < rows + kLanes; ++r) t[r] = 0.0;
      for (int i = 1; i <= m[p]; ++i) {
        t[p + i] = cp[i];
        cp[i] /= dk;
      }
      // Pivot p's update of the block's later columns q (rows k + q .. k + p + m[p]).
      for (int q = p + 1; q < P && q - p <= m[p]; ++q) {
        const double f = cp[q - p];
        double* cq = &band_[static_cast<std::size_t>(k + q) * w] - q;  // cq[r] = A(k + r, k + q)
        for (int r = q; r <= p + m[p]; ++r) cq[r] -= f * t[r];
      }
    }
    // Columns k + P .. k + rows: the block's pivots, in order, on rows k + j .. k + rows. The rows are taken in
    // whole vectors of kLanes: the rows past `rows` (the next column's first entries, or the tail's padding) see
    // t = 0 and stay as they are, and the loop has no scalar remainder.
    for (int j = P; j <= rows; ++j) {
      std::array<double, P> f{};
      for (int p = 0; p < P; ++p)
        f[p] = j - p <= m[p] ? band_[static_cast<std::size_t>(k + p) * w + static_cast<std::size_t>(j - p)] : 0.0;
      double* cj = &band_[static_cast<std::size_t>(k + j) * w] - j;  // cj[r] = A(k + r, k + j)
      if constexpr (P == kPivots) {
        const double *t0 = t_[0].data(), *t1 = t_[1].data(), *t2 = t_[2].data(), *t3 = t_[3].data();
        const int end = j + ((rows - j + kLanes) / kLanes) * kLanes;
        for (int r = j; r < end; ++r) cj[r] = (((cj[r] - f[0] * t0[r]) - f[1] * t1[r]) - f[2] * t2[r]) - f[3] * t3[r];
      } else {
        for (int p = 0; p < P; ++p) {
          const double* t = t_[static_cast<std::size_t>(p)].data();
          for (int r = j; r <= rows; ++r) cj[r] -= f[p] * t[r];
        }
      }
    }
  }

  // out = L^-T D^-1 L^-1 in.
  __attribute__((target_clones("avx512f", "avx2", "default"))) void substitute(const std::vector<double>& in,
                                                                               std::vector<double>& out) const {
    const int w = kd_ + 1;
    out = in;
    // A zero right-hand side (the second P' solve of a TFM step has one) has the answer zero.
    if (std::all_of(in.begin(), in.end(), [](double v) { return v == 0.0; })) return;
    // L y = b by columns, four at a time: the four's own rows first (the triangle, in column order), then each
    // column's update of the rows below the four, column after column. Every entry takes the same updates in the
    // same order as one column at a time; the four column passes start on the same row, so each reads what the
    // one before stored at the same place (a stored vector is read back whole, not from a shifted place).
    double* y = out.data();
    int k = 0;
    for (; k + 4 <= n_; k += 4) {
      std::array<const double*, 4> c{};
      std::array<int, 4> m{};
      for (int p = 0; p < 4; ++p) {
        c[static_cast<std::size_t>(p)] = &band_[static_cast<std::size_t>(k + p) * w];
        m[static_cast<std::size_t>(p)] = std::min(kd_, n_ - 1 - k - p);
      }
      std::array<double, 4> yp{y[k], y[k + 1], y[k + 2], y[k + 3]};
      for (int p = 0; p < 3; ++p)
        for (int q = p + 1; q < 4 && q - p <= m[static_cast<std::size_t>(p)]; ++q)
          yp[static_cast<std::size_t>(q)] -= c[static_cast<std::size_t>(p)][q - p] * yp[static_cast<std::size_t>(p)];
      for (int q = 1; q < 4; ++q) y[k + q] = yp[static_cast<std::size_t>(q)];
      for (int p = 0; p < 4; ++p) {
        const double* cp = c[static_cast<std::size_t>(p)] - p;  // cp[r] = L(k + r, k + p)
        const double v = yp[static_cast<std::size_t>(p)];
        double* yk = y + k;
        for (int r = 4; r <= p + m[static_cast<std::size_t>(p)]; ++r) yk[r] -= cp[r] * v;
      }
    }
    for (; k < n_; ++k) {
      const double* ck = &band_[static_cast<std::size_t>(k) * w];
      const int m = std::min(kd_, n_ - 1 - k);
      const double yk = y[k];
      for (int i = 1; i <= m; ++i) y[k + i] -= ck[i] * yk;
    }
    // x = D^-1 y - L^T x by rows from the last. Each row's sum takes the terms of the four answers just found
    // last, nearest last, from registers: the row waits on the one before it for a multiply, an add and a
    // subtract only, and reads from memory only answers stored four rows earlier. The farther terms go into four
    // partial sums in a fixed order (vectorised); the sum rounds the same on every run.
    double x1 = 0.0, x2 = 0.0, x3 = 0.0, x4 = 0.0;  // x[k + 1] .. x[k + 4]
    for (int k = n_ - 1; k >= 0; --k) {
      const double* ck = &band_[static_cast<std::size_t>(k) * w];
      const int m = std::min(kd_, n_ - 1 - k);
      const double* z = &y[k];
      double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
      int i = 5;
      for (; i + 3 <= m; i += 4) {
        s0 += ck[i] * z[i];
        s1 += ck[i + 1] * z[i + 1];
        s2 += ck[i + 2] * z[i + 2];
        s3 += ck[i + 3] * z[i + 3];
      }
      if (i <= m) s0 += ck[i] * z[i];
      if (i + 1 <= m) s1 += ck[i + 1] * z[i + 1];
      if (i + 2 <= m) s2 += ck[i + 2] * z[i + 2];
      const double c4 = m >= 4 ? ck[4] : 0.0, c3 = m >= 3 ? ck[3] : 0.0, c2 = m >= 2 ? ck[2] : 0.0,
                   c1 = m >= 1 ? ck[1] : 0.0;
      const double far = ((s0 + s1) + (s2 + s3)) + ((c4 * x4 + c3 * x3) + c2 * x2);
      const double xk = z[0] / ck[0] - (far + c1 * x1);
      y[k] = xk;
      x4 = x3;
      x3 = x2;
      x2 = x1;
      x1 = xk;
    }
  }

  // Conjugate gradients on the new matrix, preconditioned by the last factorisation (Golub & Van Loan, 4th ed.,
  // Alg. 11.5.1), from the caller's guess; converged when |r|_2 <= tolerance |b|_2, as Eigen's
  // ConjugateGradient. Serial, every sum in row order: the same bits on every run. False when it has not
  // converged within kBandReuseIterations or a curvature is not positive (the caller factorises then).
  bool preconditioned_cg(const Field<Dim>& guess) {
    for_each(cells_, [&](const Index<Dim>& c) { x_[row(c)] = guess[c]; });
    const double bb = dot(b_, b_);
    if (bb == 0.0) {
      std::fill(x_.begin(), x_.end(), 0.0);
      return true;
    }
    const double threshold = tolerance_ * tolerance_ * bb;
    apply(x_, q_);
    for (std::size_t i = 0; i < r_.size(); ++i) r_[i] = b_[i] - q_[i];
    if (dot(r_, r_) <= threshold) return true;
    substitute(r_, z_);
    p_ = z_;
    double rz = dot(r_, z_);
    for (int k = 0; k < kBandReuseIterations; ++k) {
      apply(p_, q_);
      const double pq = dot(p_, q_);
      if (!(pq > 0.0) || !std::isfinite(pq)) return false;
      const double alpha = rz / pq;
      for (std::size_t i = 0; i < x_.size(); ++i) {
        x_[i] += alpha * p_[i];
        r_[i] -= alpha * q_[i];
      }
      const double rr = dot(r_, r_);
      if (!std::isfinite(rr)) return false;
      if (rr <= threshold) return true;
      substitute(r_, z_);
      const double rz_next = dot(r_, z_);
      const double beta = rz_next / rz;
      rz = rz_next;
      for (std::size_t i = 0; i < p_.size(); ++i) p_[i] = z_[i] + beta * p_[i];
    }
    return false;
  }

  // out = A v, with the assembled diagonal and lower couplings (the upper ones by symmetry).
  void apply(const std::vector<double>& v, std::vector<double>& out) const {
    for (int r = 0; r < n_; ++r) {
      const auto ur = static_cast<std::size_t>(r);
      double s = diag_[ur] * v[ur];
      for (int a = 0; a < Dim; ++a) {
        const int st = stride_[static_cast<std::size_t>(a)];
        const auto& low = low_[static_cast<std::size_t>(a)];
        if (r - st >= 0) s += low[ur] * v[ur - static_cast<std::size_t>(st)];
        if (r + st < n_) s += low[ur + static_cast<std::size_t>(st)] * v[ur + static_cast<std::size_t>(st)];
      }
      out[ur] = s;
    }
  }

  static double dot(const std::vector<double>& a, const std::vector<double>& b) {
    double s = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
    return s;
  }

  // |A x - b|_inf / (|A|_inf |x|_inf + |b|_inf), as fluid/stencil_matrix.hpp's backward_error.
  double backward_error() const {
    double r_max = 0.0, a_max = 0.0, x_max = 0.0, b_max = 0.0;
    for (int r = 0; r < n_; ++r) {
      const auto ur = static_cast<std::size_t>(r);
      double ax = diag_[ur] * x_[ur], a_row = std::abs(diag_[ur]);
      for (int a = 0; a < Dim; ++a) {
        const int s = stride_[static_cast<std::size_t>(a)];
        const auto& low = low_[static_cast<std::size_t>(a)];
        if (r - s >= 0 && low[ur] != 0.0) {
          ax += low[ur] * x_[ur - static_cast<std::size_t>(s)];
          a_row += std::abs(low[ur]);
        }
        if (r + s < n_ && low[ur + static_cast<std::size_t>(s)] != 0.0) {
          ax += low[ur + static_cast<std::size_t>(s)] * x_[ur + static_cast<std::size_t>(s)];
          a_row += std::abs(low[ur + static_cast<std::size_t>(s)]);
        }
      }
      r_max = std::max(r_max, std::abs(ax - b_[ur]));
      a_max = std::max(a_max, a_row);
      x_max = std::max(x_max, std::abs(x_[ur]));
      b_max = std::max(b_max, std::abs(b_[ur]));
    }
    const double denom = a_max * x_max + b_max;
    if (!std::isfinite(r_max) || !std::isfinite(denom)) return INFINITY;
    return denom > 0.0 ? r_max / denom : r_max;
  }

  IndexBox<Dim> cells_;
  int n_ = 0;
  int kd_ = 0;
  std::array<int, Dim> stride_{};
  std::vector<double> diag_;
  std::array<std::vector<double>, Dim> low_;
  std::vector<double> band_;
  std::vector<double> b_, x_;
  BandReuse reuse_;
  double tolerance_;
  std::vector<double> r_, z_, p_, q_;  // the preconditioned reuse's residual, preconditioned residual, direction, A p
  std::array<std::array<double, kMaxPressureBand + kPivots + kLanes>, kPivots> t_{};  // the block's unscaled columns
  bool factorised_ = false;
};

}  // namespace

template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_band_structured_solver(const Grid<Dim>& grid, BandReuse reuse,
                                                                   double tolerance) {
  if (!(grid.owned == grid.domain)) return nullptr;
  for (int a = 0; a < Dim; ++a)
    if (grid.periodic[static_cast<std::size_t>(a)]) return nullptr;
  // The band is the product of every axis but the slowest: the axes in their order (axis 0 fastest) where that
  // band is narrow enough, else the longest axis slowest (a thin 3D slab: its depth and width within the band).
  std::array<int, Dim> order{};
  for (int a = 0; a < Dim; ++a) order[static_cast<std::size_t>(a)] = a;
  const long count = static_cast<long>(grid.domain.count());
  if (count / grid.domain.extent(Dim - 1) > kMaxPressureBand) {
    int longest = Dim - 1;
    for (int a = 0; a < Dim; ++a)
      if (grid.domain.extent(a) > grid.domain.extent(longest)) longest = a;
    std::stable_partition(order.begin(), order.end(), [&](int a) { return a != longest; });
  }
  if (count / grid.domain.extent(order[Dim - 1]) > kMaxPressureBand) return nullptr;
  return std::make_unique<BandStructuredSolver<Dim>>(grid.domain, order, reuse, tolerance);
}

template std::unique_ptr<StructuredSolver<2>> make_band_structured_solver(const Grid<2>&, BandReuse, double);
template std::unique_ptr<StructuredSolver<3>> make_band_structured_solver(const Grid<3>&, BandReuse, double);

}  // namespace fluidbed
