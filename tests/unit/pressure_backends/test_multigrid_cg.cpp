// The multigrid-preconditioned CG backend (src/numerics/multigrid_cg.hpp) on one process: problems with a known
// discrete answer x*, rhs = A x* with A the backends' own face form, coefficients varying by a factor e^3 ~ 20 across
// the domain as a voidage-weighted pressure correction has them. A relative residual tol bounds the relative error
// by kappa(A) tol, and kappa <= (c_max / c_min) 8 n_max^2 / pi^2 (the unit Laplacian's bound times the coefficients'
// spread), so that times tol times |x*| bounds the error. Also: the iteration count stays nearly flat as the grid is
// refined (what a multigrid preconditioner is for), the answer is the same bits on 1 and 2 threads, and what the
// backend refuses.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>

#include "core/error.hpp"
#include "numerics/multigrid_cg.hpp"
#include "field_error.hpp"

namespace fluidbed {
namespace {

using test::max_abs;
using test::max_diff;

constexpr double kSpread = 20.1;  // e^3: the coefficients lie in [e^-1.5, e^1.5]

template <int Dim>
struct Problem {
  Grid<Dim> grid;
  FaceFields<Dim> coeff;
  Field<Dim> exact, rhs;
};

enum class Sides { FixedTop, Neumann, PeriodicX };

template <int Dim>
Problem<Dim> make_problem(const Index<Dim>& n, Sides sides) {
  Vec<Dim> ext{};
  for (int a = 0; a < Dim; ++a) ext[a] = 1.0;
  Problem<Dim> pr{Grid<Dim>::uniform(ext, n, 0), {}, {}, {}};
  if (sides == Sides::PeriodicX) pr.grid.periodic[0] = true;
  const IndexBox<Dim>& cells = pr.grid.owned;
  pr.coeff = FaceFields<Dim>(cells, 0, 0.0);
  for (int a = 0; a < Dim; ++a) {
    for_each(cells.faces(a), [&](const Index<Dim>& f) {
      double phase = 0.0;
      for (int b = 0; b < Dim; ++b) phase += (0.37 + 0.21 * b) * f[b];
      double c = std::exp(1.5 * std::sin(phase + a));
      const bool boundary = f[a] == cells.lo[a] || f[a] == cells.hi[a];
      if (boundary) {
        if (a == 0 && sides == Sides::PeriodicX) {
          Index<Dim> first = f;
          first[0] = cells.lo[0];  // the last face is the first one
          phase = 0.0;
          for (int b = 0; b < Dim; ++b) phase += (0.37 + 0.21 * b) * first[b];
          c = std::exp(1.5 * std::sin(phase + a));
        } else {
          c = sides != Sides::Neumann && a == Dim - 1 && f[a] == cells.hi[a] ? 2.0 : 0.0;
        }
      }
      pr.coeff[a][f] = c;
    });
  }
  pr.exact = Field<Dim>(cells, 0);
  for_each(cells, [&](const Index<Dim>& c) {
    double v = 1.0;
    for (int a = 0; a < Dim; ++a) v *= std::cos(2.0 * std::numbers::pi * (c[a] + 0.5) / n[a]) + 1.5 + 0.1 * a;
    pr.exact[c] = v;
  });
  if (sides == Sides::Neumann) pr.exact[cells.lo] = 0.0;  // the pinned cell
  pr.rhs = Field<Dim>(cells, 0);
  for_each(cells, [&](const Index<Dim>& c) {
    double s = 0.0;
    for (int a = 0; a < Dim; ++a) {
      const bool per = pr.grid.periodic[static_cast<std::size_t>(a)];
      Index<Dim> lo = shifted<Dim>(c, a, -1), hi = shifted<Dim>(c, a, 1);
      const bool has_lo = c[a] > cells.lo[a] || per, has_hi = c[a] < cells.hi[a] - 1 || per;
      lo[a] = pr.grid.wrap(a, lo[a]);
      hi[a] = pr.grid.wrap(a, hi[a]);
      Index<Dim> hi_face = shifted<Dim>(c, a, 1);
      if (per && c[a] == cells.hi[a] - 1) hi_face[a] = cells.lo[a];
      s += pr.coeff[a][c] * (pr.exact[c] - (has_lo ? pr.exact[lo] : 0.0));
      s += pr.coeff[a][hi_face] * (pr.exact[c] - (has_hi ? pr.exact[hi] : 0.0));
    }
    pr.rhs[c] = s;
  });
  if (sides == Sides::Neumann) {
    // The pinned cell's own row is dropped, and its neighbours see it as zero: rhs as A x* with that x*.
    pr.rhs[cells.lo] = 0.0;
  }
  return pr;
}

template <int Dim>
MultigridCgStats check(const Index<Dim>& n, Sides sides, bool line_sums = false) {
  const double tol = 1e-10;
  Problem<Dim> pr = make_problem<Dim>(n, sides);
  int nmax = 0;
  for (int a = 0; a < Dim; ++a) nmax = std::max(nmax, n[a]);
  const double kappa = kSpread * 8.0 * nmax * nmax / (std::numbers::pi * std::numbers::pi);
  const double bound = (sides == Sides::Neumann ? 10.0 : 1.0) * kappa * tol * max_abs(pr.exact);
  auto mg = make_multigrid_cg_solver<Dim>(pr.grid, serial_comm(), {.tolerance = tol, .line_sums = line_sums});
  Field<Dim> xm(pr.grid.owned, 0), xe(pr.grid.owned, 0);
  mg->solve(pr.coeff, pr.rhs, xm, false);
  const MultigridCgStats st = multigrid_cg_stats<Dim>(*mg);
  // Eigen's Cholesky as a second reference where its fill-in stays small.
  const bool small = pr.grid.owned.count() <= 10000;
  if (small) make_eigen_structured_solver<Dim>(pr.grid)->solve(pr.coeff, pr.rhs, xe, false);
  const double err_m = max_diff(xm, pr.exact), err_me = small ? max_diff(xm, xe) : 0.0;
  std::printf("%dD %zu cells, %d levels: %d iterations to %.2g; bound %.3g; |mg - exact| %.3g, |mg - eigen| %.3g\n",
              Dim, pr.grid.owned.count(), st.levels, st.iterations, st.relative_residual, bound, err_m, err_me);
  EXPECT_LE(st.relative_residual, tol);
  EXPECT_LT(err_m, bound);
  EXPECT_LT(err_me, bound);
  // Warm start from the answer with the hierarchy reused: no iteration is needed.
  mg->solve(pr.coeff, pr.rhs, xm, true);
  EXPECT_EQ(multigrid_cg_stats<Dim>(*mg).iterations, 0);
  return st;
}

TEST(MultigridCg, Poisson2dFixedTop) { check<2>({30, 50}, Sides::FixedTop); }
TEST(MultigridCg, Poisson2dNeumannPinned) { check<2>({17, 23}, Sides::Neumann); }
TEST(MultigridCg, Poisson2dPeriodic) { check<2>({21, 40}, Sides::PeriodicX); }
TEST(MultigridCg, Poisson3dFixedTop) { check<3>({20, 24, 16}, Sides::FixedTop); }
TEST(MultigridCg, Poisson3dNeumannPinned) { check<3>({9, 11, 7}, Sides::Neumann); }
TEST(MultigridCg, Poisson3dPeriodic) { check<3>({12, 20, 9}, Sides::PeriodicX); }
// Inner products as line sums (the two-fluid model's mode): the same bound, and about the same iterations.
TEST(MultigridCg, LineSums) {
  const int exact = check<2>({30, 50}, Sides::FixedTop).iterations;
  EXPECT_NEAR(check<2>({30, 50}, Sides::FixedTop, true).iterations, exact, 1);
  check<3>({20, 24, 16}, Sides::FixedTop, true);
  check<3>({12, 20, 9}, Sides::PeriodicX, true);
  check<3>({9, 11, 7}, Sides::Neumann, true);
}

// A multigrid preconditioner keeps CG's iteration count nearly independent of the grid (plain or diagonally
// preconditioned CG needs ~n times more); 16 times the cells may cost a few more iterations, not four times as many.
TEST(MultigridCg, IterationsNearlyFlatUnderRefinement) {
  const int coarse = check<2>({32, 48}, Sides::FixedTop).iterations;
  const int fine = check<2>({128, 192}, Sides::FixedTop).iterations;
  EXPECT_LE(fine, coarse + 8);
  const int coarse3 = check<3>({12, 16, 12}, Sides::FixedTop).iterations;
  const int fine3 = check<3>({48, 64, 48}, Sides::FixedTop).iterations;
  EXPECT_LE(fine3, coarse3 + 8);
}

TEST(MultigridCg, SameBitsOnOneAndTwoThreads) {
  Problem<3> pr = make_problem<3>({40, 48, 32}, Sides::PeriodicX);
  for (bool line_sums : {false, true}) {
    Field<3> x1(pr.grid.owned, 0), x2(pr.grid.owned, 0);
    const int before = omp_get_max_threads();
    omp_set_num_threads(1);
    make_multigrid_cg_solver<3>(pr.grid, serial_comm(), {.line_sums = line_sums})->solve(pr.coeff, pr.rhs, x1, false);
    omp_set_num_threads(2);
    make_multigrid_cg_solver<3>(pr.grid, serial_comm(), {.line_sums = line_sums})->solve(pr.coeff, pr.rhs, x2, false);
    omp_set_num_threads(before);
    for (std::size_t k = 0; k < x1.data().size(); ++k)
      ASSERT_EQ(std::bit_cast<std::uint64_t>(x1.data()[k]), std::bit_cast<std::uint64_t>(x2.data()[k]))
          << k << (line_sums ? " (line sums)" : "");
  }
}

TEST(MultigridCg, RefusesAPeriodicAxisCutAcrossRanks) {
  Grid<2> g = Grid<2>::uniform({1.0, 1.0}, {8, 8}, 1);
  g.periodic[0] = true;
  g.owned.hi[0] = 4;  // a block of the domain, as on one of two ranks
  try {
    make_multigrid_cg_solver<2>(g, serial_comm());
    FAIL() << "a periodic axis cut across ranks was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("periodic axis 0 is cut across ranks"), std::string::npos) << e.what();
  }
}

TEST(MultigridCg, LineSumsRefuseACutAlongX) {
  Grid<2> g = Grid<2>::uniform({1.0, 1.0}, {8, 8}, 1);
  g.owned.hi[0] = 4;
  try {
    make_multigrid_cg_solver<2>(g, serial_comm(), {.line_sums = true});
    FAIL() << "line sums over a block cut along x were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("axis 0 (x) is cut"), std::string::npos) << e.what();
  }
}

TEST(MultigridCg, NamesTheCellOfANonFiniteRow) {
  Problem<2> pr = make_problem<2>({8, 8}, Sides::FixedTop);
  pr.rhs[{3, 5}] = std::nan("");
  Field<2> x(pr.grid.owned, 0);
  try {
    make_multigrid_cg_solver<2>(pr.grid, serial_comm())->solve(pr.coeff, pr.rhs, x, false);
    FAIL() << "a non-finite right-hand side was solved";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cell (3, 5)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fluidbed
