// The hypre PFMG-CG pressure backend (src/fluid/structured_solver_hypre.hpp) on Poisson problems with a known
// discrete solution, in 2D and 3D: x* = sin-shaped, rhs = A x* with A the backend's own (2 Dim + 1)-point form
// (unit-spaced coefficients, fixed-pressure faces on the low and high sides of axis Dim - 1 at twice the interior
// coefficient, the half cell to the boundary). A relative residual tol bounds the relative error by kappa(A) tol;
// kappa of this Laplacian is below 4 n_max^2 / pi^2 * 2 (n_max the longest side), so the error bound is that times
// the tolerance. The same problems through Eigen's Cholesky give the reference within the same bound, and an
// all-Neumann problem (pinned first cell) must agree with Eigen's pinned answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "numerics/structured_solver_hypre.hpp"
#include "field_error.hpp"

namespace fluidbed {
namespace {

using test::max_abs;
using test::max_diff;

template <int Dim>
struct Problem {
  Grid<Dim> grid;
  FaceFields<Dim> coeff;
  Field<Dim> exact, rhs;
};

template <int Dim>
Problem<Dim> make_problem(const Index<Dim>& n, bool dirichlet) {
  Vec<Dim> ext{};
  for (int a = 0; a < Dim; ++a) ext[a] = 1.0;
  Problem<Dim> pr{Grid<Dim>::uniform(ext, n, 0), {}, {}, {}};
  const IndexBox<Dim>& cells = pr.grid.owned;
  pr.coeff = FaceFields<Dim>(cells, 0, 0.0);
  for (int a = 0; a < Dim; ++a) {
    for_each(cells.faces(a), [&](const Index<Dim>& f) {
      const bool boundary = f[a] == cells.lo[a] || f[a] == cells.hi[a];
      // Slightly varying interior coefficients, as a voidage-weighted pressure correction has them.
      double c = 1.0 + 0.3 * std::sin(0.7 * f[0] + 0.3 * a);
      if (boundary) c = dirichlet && a == Dim - 1 ? 2.0 : 0.0;
      pr.coeff[a][f] = c;
    });
  }
  pr.exact = Field<Dim>(cells, 0);
  for_each(cells, [&](const Index<Dim>& c) {
    double v = 1.0;
    for (int a = 0; a < Dim; ++a) v *= std::sin(std::numbers::pi * (c[a] + 0.5) / n[a]) + 0.1 * a;
    pr.exact[c] = v;
  });
  if (!dirichlet) pr.exact[cells.lo] = 0.0;  // the pinned cell
  // rhs_P = sum over faces a_f (x_P - x_nb), x = 0 beyond a boundary face.
  pr.rhs = Field<Dim>(cells, 0);
  for_each(cells, [&](const Index<Dim>& c) {
    double s = 0.0;
    for (int a = 0; a < Dim; ++a) {
      const Index<Dim> lo = shifted<Dim>(c, a, -1), hi = shifted<Dim>(c, a, 1);
      s += pr.coeff[a][c] * (pr.exact[c] - (c[a] > cells.lo[a] ? pr.exact[lo] : 0.0));
      s += pr.coeff[a][hi] * (pr.exact[c] - (c[a] < cells.hi[a] - 1 ? pr.exact[hi] : 0.0));
    }
    pr.rhs[c] = s;
  });
  return pr;
}

template <int Dim>
void check(const Index<Dim>& n, bool dirichlet) {
  if (!hypre_available()) GTEST_SKIP() << "built without hypre";
  const double tol = 1e-10;
  Problem<Dim> pr = make_problem<Dim>(n, dirichlet);
  int nmax = 0;
  for (int a = 0; a < Dim; ++a) nmax = std::max(nmax, n[a]);
  const double kappa = 8.0 * nmax * nmax / (std::numbers::pi * std::numbers::pi);
  const double bound = (dirichlet ? 1.0 : 10.0) * kappa * tol * max_abs(pr.exact);

  auto hypre = make_hypre_structured_solver<Dim>(pr.grid, tol);
  auto eigen = make_eigen_structured_solver<Dim>(pr.grid);
  Field<Dim> xh(pr.grid.owned, 0), xe(pr.grid.owned, 0);
  const auto t0 = std::chrono::steady_clock::now();
  hypre->solve(pr.coeff, pr.rhs, xh, false);
  const auto t1 = std::chrono::steady_clock::now();
  eigen->solve(pr.coeff, pr.rhs, xe, false);
  const auto t2 = std::chrono::steady_clock::now();
  // Warm start from the answer: a reused hierarchy must return at once and stay within the bound.
  hypre->solve(pr.coeff, pr.rhs, xh, true);
  const double err_h = max_diff(xh, pr.exact), err_e = max_diff(xe, pr.exact), err_he = max_diff(xh, xe);
  std::printf("%dD %zu cells %s: bound %.3g; |hypre - exact| %.3g, |eigen - exact| %.3g, |hypre - eigen| %.3g; "
              "first solve hypre %.3g ms, eigen (factorise + solve) %.3g ms\n",
              Dim, pr.grid.owned.count(), dirichlet ? "fixed-pressure top/bottom" : "all-Neumann, pinned", bound,
              err_h, err_e, err_he, std::chrono::duration<double, std::milli>(t1 - t0).count(),
              std::chrono::duration<double, std::milli>(t2 - t1).count());
  EXPECT_LT(err_h, bound);
  EXPECT_LT(err_he, bound);
}

TEST(HyprePfmg, Poisson2dFixedPressure) { check<2>({30, 50}, true); }
TEST(HyprePfmg, Poisson2dNeumannPinned) { check<2>({17, 23}, false); }
TEST(HyprePfmg, Poisson3dFixedPressure) { check<3>({20, 24, 16}, true); }
TEST(HyprePfmg, Poisson3dNeumannPinned) { check<3>({9, 11, 7}, false); }

}  // namespace
}  // namespace fluidbed
