#include "tfm/band_pressure_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "fluid/stencil_matrix.hpp"

namespace fluidbed::tfm {
namespace {

template <int Dim>
class BandStructuredSolver final : public StructuredSolver<Dim> {
 public:
  BandStructuredSolver(const IndexBox<Dim>& cells, int band) : cells_(cells), n_(static_cast<int>(cells.count())), kd_(band) {
    for (int a = 0, s = 1; a < Dim; ++a) {
      stride_[static_cast<std::size_t>(a)] = s;
      s *= cells.extent(a);
    }
    const auto n = static_cast<std::size_t>(n_);
    diag_.resize(n);
    for (auto& l : low_) l.resize(n);
    band_.resize(n * static_cast<std::size_t>(kd_ + 1));
    b_.resize(n);
    x_.resize(n);
  }

  const char* name() const override { return "band"; }

  void solve(const FaceFields<Dim>& coeff, const Field<Dim>& rhs, Field<Dim>& x, bool reuse_factorisation) override {
    assemble(coeff, rhs);
    bool solved = false;
    if (reuse_factorisation && factorised_) {
      substitute();
      solved = backward_error() <= kDirectBackwardError;  // the same matrix, unless the caller's coefficients moved
    }
    if (!solved) {
      factorise();
      substitute();
      const double err = backward_error();
      // Finite and backward stable, or not accepted.
      if (!(err <= kDirectBackwardError)) {
        throw_simulation_error("gas pressure correction: the band LDLT answer has backward error " +
                               std::to_string(err) + " (the matrix is singular or not finite)");
      }
    }
    int r = 0;
    for_each(cells_, [&](const Index<Dim>& c) { x[c] = x_[static_cast<std::size_t>(r++)]; });
  }

 private:
  // The matrix of the problem (rows axis 0 fastest): diagonal and the coupling to the lower neighbour along each
  // axis (the upper ones follow by symmetry), built as fluid/pressure_correction.cpp's Eigen backend builds it.
  void assemble(const FaceFields<Dim>& coeff, const Field<Dim>& rhs) {
    const IndexBox<Dim>& b = cells_;
    // An all-Neumann problem pins the first cell: its couplings are dropped from its row and its neighbours'.
    const bool pin = !couples_to_boundary<Dim>(b, coeff);
    int r = 0;
    for_each(b, [&](const Index<Dim>& c) {
      bool finite = std::isfinite(rhs[c]);
      double diag = 0.0;
      for (int a = 0; a < Dim; ++a) {
        const double lo = coeff[a][c], hi = coeff[a][shifted<Dim>(c, a, 1)];
        finite = finite && std::isfinite(lo) && std::isfinite(hi);
        diag = a == 0 ? lo + hi : diag + lo + hi;
        low_[static_cast<std::size_t>(a)][static_cast<std::size_t>(r)] =
            c[a] > b.lo[a] && !(pin && c == shifted<Dim>(b.lo, a, 1)) ? -lo : 0.0;
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
      diag_[static_cast<std::size_t>(r)] = diag;
      b_[static_cast<std::size_t>(r)] = rb;
      ++r;
    });
  }

  // Band LDL^T in place, column k holding L(k + i, k) at offset i and d_k at offset 0 (right-looking: the update
  // of each later column is one contiguous axpy).
  // Cloned for AVX2 (four lanes instead of SSE2's two; no FMA, so both clones round alike).
  __attribute__((target_clones("avx2", "default"))) void factorise() {
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
    // Two pivots at a time: column k + 1 is finished first (k's update on it, then its own scaling), then the
    // updates of both reach each later column in one pass, k's before k + 1's, so every entry sees the same
    // operations in the same order as one pivot at a time, with half the memory traffic.
    std::array<double, kMaxPressureBand + 2> t0{}, t1{};
    auto pivot = [&](int k, double* ck, std::array<double, kMaxPressureBand + 2>& t, int m) {
      const double dk = ck[0];
      if (!(dk > 0.0) || !std::isfinite(dk)) {
        throw_simulation_error("gas pressure correction: the band LDLT factorisation failed at row " +
                               std::to_string(k) + " (pivot " + std::to_string(dk) +
                               ": the matrix is not positive definite, a face coefficient is negative or not finite)");
      }
      for (int i = 1; i <= m; ++i) {
        t[static_cast<std::size_t>(i)] = ck[i];
        ck[i] /= dk;
      }
    };
    int k = 0;
    for (; k + 1 < n_; k += 2) {
      double* ck = &band_[static_cast<std::size_t>(k) * w];
      double* c1 = ck + w;
      const int m = std::min(kd_, n_ - 1 - k);  // column k reaches rows up to k + m
      pivot(k, ck, t0, m);
      {
        const double f = ck[1];  // k's update of column k + 1 (rows k + 1 .. k + m)
        if (f != 0.0)
          for (int i = 1; i <= m; ++i) c1[i - 1] -= f * t0[static_cast<std::size_t>(i)];
      }
      const int m1 = std::min(kd_, n_ - 2 - k);  // column k + 1 reaches rows up to k + 1 + m1
      pivot(k + 1, c1, t1, m1);
      // Columns k + 2 .. k + 1 + m1: k's update reaches rows up to k + m, k + 1's up to k + 1 + m1.
      for (int j = 2; j <= 1 + m1; ++j) {
        const double f0 = j <= m ? ck[j] : 0.0, f1 = c1[j - 1];
        double* cj = &band_[static_cast<std::size_t>(k + j) * w] - j;  // cj[i] = A(k + i, k + j)
        const int top0 = m, top1 = 1 + m1;
        if (f0 != 0.0 && f1 != 0.0 && top0 == top1 - 1) {
          for (int i = j; i <= top0; ++i)
            cj[i] = (cj[i] - f0 * t0[static_cast<std::size_t>(i)]) - f1 * t1[static_cast<std::size_t>(i - 1)];
          cj[top1] -= f1 * t1[static_cast<std::size_t>(top1 - 1)];
        } else {
          if (f0 != 0.0)
            for (int i = j; i <= top0; ++i) cj[i] -= f0 * t0[static_cast<std::size_t>(i)];
          if (f1 != 0.0)
            for (int i = j; i <= top1; ++i) cj[i] -= f1 * t1[static_cast<std::size_t>(i - 1)];
        }
      }
    }
    if (k < n_) pivot(k, &band_[static_cast<std::size_t>(k) * w], t0, 0);  // the last row, when n is odd
    factorised_ = true;
  }

  // x = L^-T D^-1 L^-1 b.
  __attribute__((target_clones("avx2", "default"))) void substitute() {
    const int w = kd_ + 1;
    x_ = b_;
    // A zero right-hand side (the second P' solve of a TFM step has one) has the answer zero.
    if (std::all_of(b_.begin(), b_.end(), [](double v) { return v == 0.0; })) return;
    for (int k = 0; k < n_; ++k) {
      const double* ck = &band_[static_cast<std::size_t>(k) * w];
      const int m = std::min(kd_, n_ - 1 - k);
      const double yk = x_[static_cast<std::size_t>(k)];
      double* y = &x_[static_cast<std::size_t>(k)];
      for (int i = 1; i <= m; ++i) y[i] -= ck[i] * yk;
    }
    for (int k = n_ - 1; k >= 0; --k) {
      const double* ck = &band_[static_cast<std::size_t>(k) * w];
      const int m = std::min(kd_, n_ - 1 - k);
      const double* z = &x_[static_cast<std::size_t>(k)];
      // Four partial sums in a fixed order: the dot product vectorises and rounds the same on every run.
      double s[4] = {0.0, 0.0, 0.0, 0.0};
      int i = 1;
      for (; i + 3 <= m; i += 4)
        for (int l = 0; l < 4; ++l) s[l] += ck[i + l] * z[i + l];
      for (int l = 0; i <= m; ++i, ++l) s[l] += ck[i] * z[i];
      x_[static_cast<std::size_t>(k)] = z[0] / ck[0] - ((s[0] + s[1]) + (s[2] + s[3]));
    }
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
  bool factorised_ = false;
};

}  // namespace

template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_band_structured_solver(const Grid<Dim>& grid) {
  if (!(grid.owned == grid.domain)) return nullptr;
  for (int a = 0; a < Dim; ++a)
    if (grid.periodic[static_cast<std::size_t>(a)]) return nullptr;
  const long band = static_cast<long>(grid.domain.count()) / grid.domain.extent(Dim - 1);
  if (band > kMaxPressureBand) return nullptr;
  return std::make_unique<BandStructuredSolver<Dim>>(grid.domain, static_cast<int>(band));
}

template std::unique_ptr<StructuredSolver<2>> make_band_structured_solver(const Grid<2>&);
template std::unique_ptr<StructuredSolver<3>> make_band_structured_solver(const Grid<3>&);

}  // namespace fluidbed::tfm
