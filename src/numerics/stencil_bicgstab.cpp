#include "numerics/stencil_bicgstab.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "numerics/line_sum.hpp"
#include "parallel/periodic_halo.hpp"

namespace fluidbed {
namespace {

__attribute__((target_clones("avx2", "default"))) bool all_finite(std::span<const double> v) {
  // x - x is +0 for a finite x and NaN otherwise; four independent sums, so that the compiler can keep them in one
  // vector register (a single sum would be a chain of dependent additions).
  double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0;
  const double* p = v.data();
  const std::size_t n = v.size();
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    a0 += p[i] - p[i];
    a1 += p[i + 1] - p[i + 1];
    a2 += p[i + 2] - p[i + 2];
    a3 += p[i + 3] - p[i + 3];
  }
  for (; i < n; ++i) a0 += p[i] - p[i];
  return (a0 + a1) + (a2 + a3) == 0.0;
}

// One line of the product: each row the diagonal, then the neighbours in slot order (the same additions on every
// rank). Cloned for AVX2 without FMA (-ffp-contract=off): every clone rounds alike.
template <int Slots>
__attribute__((target_clones("avx2", "default"))) void stencil_line(int n, const double* d,
                                                                    const std::array<const double*, Slots>& o,
                                                                    const double* x,
                                                                    const std::array<std::ptrdiff_t, Slots>& shift,
                                                                    double* y) {
  for (int i = 0; i < n; ++i) {
    double s = d[i] * x[i];
    for (int k = 0; k < Slots; ++k) s += o[static_cast<std::size_t>(k)][i] * x[i + shift[static_cast<std::size_t>(k)]];
    y[i] = s;
  }
}

}  // namespace

template <int Dim>
StencilBicgstab<Dim>::StencilBicgstab(const Grid<Dim>& grid, const Comm& comm) : comm_(comm), grid_(grid) {
  const IndexBox<Dim>& own = grid.owned;
  if (own.extent(0) != grid.domain.extent(0)) {
    throw_input_error("BiCGSTAB of the two-fluid model: axis 0 (x) is cut across ranks; its inner products sum "
                      "whole lines along x in one order, so cut the other axes");
  }
  for (int a = 0; a < Dim; ++a) {
    if (!grid.periodic[static_cast<std::size_t>(a)]) continue;
    if (own.extent(a) != grid.domain.extent(a))
      throw_input_error("BiCGSTAB of the two-fluid model: periodic axis " + std::to_string(a) +
                        " is cut across ranks (its ghosts would need the opposite rank); cut the other axes");
    if (grid.domain.extent(a) < 3)
      throw_input_error("BiCGSTAB of the two-fluid model: periodic axis " + std::to_string(a) +
                        " has fewer than 3 cells (a row would meet one neighbour through both faces)");
  }
  if (comm.size() > 1) boxes_ = all_boxes<Dim>(comm, own);
  global_rows_ = static_cast<long>(grid.domain.count());
  line_length_ = own.extent(0);
  const auto n = static_cast<std::size_t>(own.count());
  diag_.assign(n, 0.0);
  for (std::vector<double>& o : off_) o.assign(n, 0.0);
  ghosted_ = Field<Dim>(own, 1);
  for (int a = 0; a < Dim; ++a) {
    const auto s = static_cast<std::ptrdiff_t>(ghosted_.stride(a));
    shift_[static_cast<std::size_t>(2 * a)] = -s;
    shift_[static_cast<std::size_t>(2 * a + 1)] = s;
  }
  IndexBox<Dim> starts = own;
  starts.hi[0] = starts.lo[0] + 1;
  for_each(starts, [&](const Index<Dim>& c) { line_start_.push_back(ghosted_.index(c)); });
}

template <int Dim>
int StencilBicgstab<Dim>::global_row(int row) const {
  return cell_row(grid_.domain, cell_at(grid_.owned, row));
}

template <int Dim>
void StencilBicgstab<Dim>::multiply(std::span<const double> in, std::vector<double>& out) {
  const int n0 = line_length_;
  double* g = ghosted_.data().data();
  for (std::size_t l = 0; l < line_start_.size(); ++l)
    std::copy_n(in.data() + l * static_cast<std::size_t>(n0), n0, g + line_start_[l]);
  if (comm_.size() > 1) comm_.exchange_halo_among(ghosted_, boxes_, HaloCells::Faces);
  fill_periodic_ghosts(grid_, ghosted_);
  out.resize(in.size());
  for (std::size_t l = 0; l < line_start_.size(); ++l) {
    const std::size_t r0 = l * static_cast<std::size_t>(n0);
    const double* x = g + line_start_[l];
    const double* d = diag_.data() + r0;
    std::array<const double*, kSlots> o{};
    for (int k = 0; k < kSlots; ++k) o[static_cast<std::size_t>(k)] = off_[static_cast<std::size_t>(k)].data() + r0;
    stencil_line<kSlots>(n0, d, o, x, shift_, out.data() + r0);
  }
}

template <int Dim>
void StencilBicgstab<Dim>::dots(int count, const std::array<const double*, 2>& u, const std::array<const double*, 2>& v,
                                std::array<double, 2>& out) const {
  std::array<ExactSum, 2> acc{};
  const int n0 = line_length_;
  for (std::size_t l = 0; l < line_start_.size(); ++l) {
    const std::size_t r0 = l * static_cast<std::size_t>(n0);
    for (int k = 0; k < count; ++k) acc[static_cast<std::size_t>(k)].add(line_dot(u[static_cast<std::size_t>(k)] + r0, v[static_cast<std::size_t>(k)] + r0, n0));
  }
  if (comm_.size() > 1) {
    // One collective for both: the limbs of the accumulators side by side, summed as integers (exact).
    std::vector<std::int64_t> words;
    for (int k = 0; k < count; ++k) {
      const auto w = acc[static_cast<std::size_t>(k)].words();
      words.insert(words.end(), w.begin(), w.end());
    }
    comm_.sum(std::span<std::int64_t>(words));
    for (int k = 0; k < count; ++k)
      acc[static_cast<std::size_t>(k)] = ExactSum::from_words(
          std::span<const std::int64_t, ExactSum::kWords>(words.data() + static_cast<std::size_t>(k) * ExactSum::kWords, ExactSum::kWords));
  }
  for (int k = 0; k < count; ++k) out[static_cast<std::size_t>(k)] = acc[static_cast<std::size_t>(k)].value();
}

template <int Dim>
LinearSolveOutcome StencilBicgstab<Dim>::solve(std::span<const double> b, std::vector<double>& x) {
  LinearSolveOutcome out;
  const auto n = static_cast<std::size_t>(rows());
  if (x.size() != n) x.assign(n, 0.0);
  // A non-finite coefficient makes every answer meaningless: the first such row over all ranks is named.
  bool finite = all_finite(b) && all_finite(diag_);
  for (const std::vector<double>& o : off_) finite = finite && all_finite(o);
  std::optional<std::string> bad;
  double key = 0.0;
  if (!finite) {
    for (std::size_t r = 0; r < n && !bad; ++r) {
      bool ok = std::isfinite(b[r]) && std::isfinite(diag_[r]);
      for (const std::vector<double>& o : off_) ok = ok && std::isfinite(o[r]);
      if (!ok) {
        key = global_row(static_cast<int>(r));
        bad = std::to_string(static_cast<long>(key));
      }
    }
  }
  if (const auto first = comm_.first_failure(bad, key)) {
    out.bad_row = std::stoi(*first);
    out.why = "non-finite coefficient or right-hand side in row " + *first;
    return out;
  }
  std::vector<double>& y = answer_;
  y = x;
  // The iterations are the same on every rank, so every rank agrees on whether they converged.
  if (bicgstab(b, y, out) && comm_.min(all_finite(y) ? 1.0 : 0.0) > 0.0) {
    out.ok = true;
    x.swap(y);
    return out;
  }
  out.fell_back = true;
  direct(b, x, out);
  return out;
}

template <int Dim>
bool StencilBicgstab<Dim>::bicgstab(std::span<const double> rhs, std::vector<double>& x, LinearSolveOutcome& out) {
  const std::size_t n = x.size();
  invdiag_.resize(n);
  for (std::size_t j = 0; j < n; ++j) invdiag_[j] = diag_[j] != 0.0 ? 1.0 / diag_[j] : 1.0;
  const long max_iters = max_iterations_ > 0 ? max_iterations_ : 2 * global_rows_;
  for (std::vector<double>* v : {&r_, &r0_, &v_, &p_, &y_, &z_, &s_, &t_}) v->resize(n);
  std::vector<double>&r = r_, &r0 = r0_, &v = v_, &p = p_, &y = y_, &z = z_, &s = s_, &t = t_;
  std::array<double, 2> d{};
  auto residual = [&] {
    multiply(x, t);
    for (std::size_t j = 0; j < n; ++j) r[j] = rhs[j] - t[j];
    r0 = r;
  };
  residual();
  dots(2, {r0.data(), rhs.data()}, {r0.data(), rhs.data()}, d);
  double r0_sqnorm = d[0];
  const double rhs_sqnorm = d[1];
  if (rhs_sqnorm == 0) {
    std::fill(x.begin(), x.end(), 0.0);
    out.iterations = 0;
    out.error = 0.0;
    return true;
  }
  double rho = 1, alpha = 1, w = 1;
  std::fill(v.begin(), v.end(), 0.0);
  std::fill(p.begin(), p.end(), 0.0);
  const double tol2 = tolerance_ * tolerance_ * rhs_sqnorm;
  const double eps2 = std::numeric_limits<double>::epsilon() * std::numeric_limits<double>::epsilon();
  long i = 0, restarts = 0;
  // |r|^2 and r0 . r of the current residual, from one collective (at the start r0 = r).
  double r_sqnorm = r0_sqnorm, r0_dot_r = r0_sqnorm;
  while (r_sqnorm > tol2 && i < max_iters) {
    const double rho_old = rho;
    rho = r0_dot_r;
    if (std::abs(rho) < eps2 * r0_sqnorm) {
      // The residual became too orthogonal to r0: restart with a new r0 (as Eigen).
      residual();
      dots(1, {r.data(), nullptr}, {r.data(), nullptr}, d);
      rho = r0_sqnorm = d[0];
      if (restarts++ == 0) i = 0;
    }
    const double beta = (rho / rho_old) * (alpha / w);
    for (std::size_t j = 0; j < n; ++j) {
      p[j] = r[j] + beta * (p[j] - w * v[j]);
      y[j] = invdiag_[j] * p[j];
    }
    multiply(y, v);
    dots(1, {r0.data(), nullptr}, {v.data(), nullptr}, d);
    alpha = rho / d[0];
    for (std::size_t j = 0; j < n; ++j) {
      s[j] = r[j] - alpha * v[j];
      z[j] = invdiag_[j] * s[j];
    }
    multiply(z, t);
    dots(2, {t.data(), t.data()}, {t.data(), s.data()}, d);
    w = d[0] > 0.0 ? d[1] / d[0] : 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      x[j] += alpha * y[j] + w * z[j];
      r[j] = s[j] - w * t[j];
    }
    ++i;
    dots(2, {r.data(), r0.data()}, {r.data(), r.data()}, d);
    r_sqnorm = d[0];
    r0_dot_r = d[1];
  }
  out.iterations = static_cast<int>(i);
  out.error = std::sqrt(r_sqnorm / rhs_sqnorm);
  return r_sqnorm <= tol2;
}

template <int Dim>
void StencilBicgstab<Dim>::direct(std::span<const double> b, std::vector<double>& x, LinearSolveOutcome& out) const {
  // Every rank's rows in global numbering, then the same matrix and the same LU on every rank.
  const std::size_t n = diag_.size();
  Bytes mine;
  for (std::size_t r = 0; r < n; ++r) {
    pack(mine, static_cast<std::int64_t>(global_row(static_cast<int>(r))));
    pack(mine, diag_[r]);
    for (const std::vector<double>& o : off_) pack(mine, o[r]);
    pack(mine, b[r]);
  }
  const Bytes all = comm_.allgather_concat(mine);
  const IndexBox<Dim>& dom = grid_.domain;
  const auto total = static_cast<Eigen::Index>(global_rows_);
  Eigen::VectorXd rhs(total);
  std::vector<Eigen::Triplet<double>> trip;
  Unpacker u(all);
  while (!u.done()) {
    const auto g = u.get<std::int64_t>();
    const Index<Dim> c = cell_at(dom, g);
    trip.emplace_back(g, g, u.get<double>());
    for (int k = 0; k < kSlots; ++k) {
      const double value = u.get<double>();
      const int a = k / 2;
      Index<Dim> nb = c;
      nb[a] += (k % 2 == 0) ? -1 : 1;
      nb[a] = grid_.wrap(a, nb[a]);
      if (value == 0.0 || nb[a] < dom.lo[a] || nb[a] >= dom.hi[a]) continue;  // a wall has no neighbour
      trip.emplace_back(g, cell_row(dom, nb), value);
    }
    rhs[g] = u.get<double>();
  }
  StencilMatrix::Matrix a(total, total);
  a.setFromTriplets(trip.begin(), trip.end());
  const Eigen::SparseMatrix<double, Eigen::ColMajor, int> a_col = a;
  Eigen::SparseLU<Eigen::SparseMatrix<double, Eigen::ColMajor, int>> lu;
  lu.compute(a_col);
  const std::string stopped = "BiCGSTAB stopped at relative residual " + std::to_string(out.error) + " after " +
                              std::to_string(out.iterations) + " iterations";
  if (lu.info() != Eigen::Success) {
    out.why = stopped + " and the sparse LU failed (" + lu.lastErrorMessage() + "): the matrix is singular";
    return;
  }
  const Eigen::VectorXd sol = lu.solve(rhs);
  out.backward_error = sol.allFinite() ? backward_error(a, sol, rhs) : INFINITY;
  if (!(out.backward_error <= kDirectBackwardError)) {
    out.why = stopped + " and the sparse LU answer has backward error " + std::to_string(out.backward_error) +
              ": the matrix is singular to working precision";
    return;
  }
  out.ok = true;
  x.resize(n);
  for (std::size_t r = 0; r < n; ++r) x[r] = sol[global_row(static_cast<int>(r))];
}

template class StencilBicgstab<2>;
template class StencilBicgstab<3>;

}  // namespace fluidbed
