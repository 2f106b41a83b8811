// The band LDL^T pressure backend (src/numerics/band_pressure_solver.hpp) on problems with a known discrete
// answer: x* given, rhs = A x* with A the StructuredSolver form (varying coefficients 0.7-1.3, fixed-pressure
// faces at twice the coefficient on the high side of the last axis, as the TFM's open top, or none: all-Neumann,
// first cell pinned). A backward-stable direct solve leaves a relative error of at most about kappa(A) times the
// machine epsilon; kappa of these Laplacians is below 8 n_max^2 / pi^2 times the coefficient ratio (about 4,000
// for n_max = 50), so 4e3 x 2.2e-16 ~ 1e-12, taken with a factor 100 for the growth of rounding with n:
// 1e-10 relative. Eigen's sparse Cholesky answers the same problems within the same bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "numerics/band_pressure_solver.hpp"

namespace fluidbed::tfm {
namespace {

template <int Dim>
struct Problem {
  Grid<Dim> grid;
  FaceFields<Dim> coeff;
  Field<Dim> exact, rhs;
};

template <int Dim>
Problem<Dim> make_problem(const Index<Dim>& n, bool open_top, double phase = 0.0, double contrast = 0.0) {
  Vec<Dim> ext{};
  for (int a = 0; a < Dim; ++a) ext[a] = 1.0;
  Problem<Dim> pr{Grid<Dim>::uniform(ext, n, 0), {}, {}, {}};
  const IndexBox<Dim>& cells = pr.grid.owned;
  pr.coeff = FaceFields<Dim>(cells, 0, 0.0);
  for (int a = 0; a < Dim; ++a)
    for_each(cells.faces(a), [&](const Index<Dim>& f) {
      const bool boundary = f[a] == cells.lo[a] || f[a] == cells.hi[a];
      double c = 1.0 + 0.3 * std::sin(0.7 * f[0] + 1.3 * f[1] + 0.3 * a + phase);
      c *= std::exp(contrast * std::sin(1.9 * f[0] + 0.7 * f[Dim - 1]));
      if (boundary) c = open_top && a == Dim - 1 && f[a] == cells.hi[a] ? 2.0 * c : 0.0;
      pr.coeff[a][f] = c;
    });
  pr.exact = Field<Dim>(cells, 0);
  for_each(cells, [&](const Index<Dim>& c) {
    double v = 1.0;
    for (int a = 0; a < Dim; ++a) v *= std::cos(std::numbers::pi * (c[a] + 0.5) / n[a]) + 0.2 * (a + 1);
    pr.exact[c] = v;
  });
  if (!open_top) pr.exact[cells.lo] = 0.0;  // the pinned cell
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
double rel_error(const Field<Dim>& x, const Field<Dim>& exact) {
  double d = 0.0, m = 0.0;
  for (std::size_t k = 0; k < x.data().size(); ++k) {
    d = std::max(d, std::abs(x.data()[k] - exact.data()[k]));
    m = std::max(m, std::abs(exact.data()[k]));
  }
  return d / m;
}

constexpr double kTol = 1e-10;

// The relative error of a solve of `pr` from a zero start that asks to reuse the last factorisation.
template <int Dim>
double reuse_error(StructuredSolver<Dim>& solver, const Problem<Dim>& pr) {
  Field<Dim> x(pr.grid.owned, 0);
  solver.solve(pr.coeff, pr.rhs, x, true);
  return rel_error(x, pr.exact);
}

template <int Dim>
void check(const Index<Dim>& n, bool open_top) {
  Problem<Dim> pr = make_problem<Dim>(n, open_top);
  auto band = make_band_structured_solver<Dim>(pr.grid);
  ASSERT_NE(band, nullptr);
  auto eigen = make_eigen_structured_solver<Dim>(pr.grid);
  Field<Dim> xb(pr.grid.owned, 0), xe(pr.grid.owned, 0);
  band->solve(pr.coeff, pr.rhs, xb, false);
  eigen->solve(pr.coeff, pr.rhs, xe, false);
  const double eb = rel_error(xb, pr.exact), ee = rel_error(xe, pr.exact);
  std::printf("%dD %s: band error %.2e, Eigen LDLT error %.2e (bound %.0e)\n", Dim, open_top ? "open top" : "pinned",
              eb, ee, kTol);
  EXPECT_LT(eb, kTol);
  EXPECT_LT(ee, kTol);

  // The same matrix again with the kept factorisation, then new coefficients with reuse asked: the backend must
  // notice the change (backward error) and factorise them.
  EXPECT_LT(reuse_error(*band, pr), kTol);
  const double em = reuse_error(*band, make_problem<Dim>(n, open_top, 0.9));
  std::printf("  reuse asked after the coefficients moved: error %.2e\n", em);
  EXPECT_LT(em, kTol);
}

TEST(BandPressureSolver, PaperBedIn2dOpenTop) { check<2>({30, 50}, true); }
TEST(BandPressureSolver, AllNeumannPinned2d) { check<2>({17, 9}, false); }
TEST(BandPressureSolver, Thin3dBox) { check<3>({4, 3, 6}, true); }

// Grids whose band with axis 0 fastest is too wide, numbered with the longest axis slowest: a thin slab (band
// 12 x 2 instead of 12 x 20; pinned: 9 x 3 instead of 9 x 14) and a 2D bed wider than tall (band 10, not 80),
// whose open top is then the high face of the fastest axis.
TEST(BandPressureSolver, ThinSlab3dLongestAxisSlowest) { check<3>({12, 20, 2}, true); }
TEST(BandPressureSolver, ThinSlab3dPinnedLongestAxisSlowest) { check<3>({9, 14, 3}, false); }
TEST(BandPressureSolver, Wide2dLongestAxisSlowest) { check<2>({80, 10}, true); }

// The CFD-DEM gas's reuse (BandReuse::Preconditioner): within a SIMPLE step the coefficients move a little, and
// conjugate gradients preconditioned by the step's first factorisation answer them. Its answer meets the relative
// residual asked, so its error is at most kappa(A) times that (kappa < 4,000 here, see above); taken loose
// (tolerance 1e-3) it must not be the exact answer, which shows the factorisation was reused, not redone.
// Coefficients moved by factors of e^-3 to e^3 face by face exceed kBandReuseIterations and are factorised anew:
// exact.
template <int Dim>
void check_preconditioned_reuse(const Index<Dim>& n, bool open_top) {
  Problem<Dim> pr = make_problem<Dim>(n, open_top);
  auto band = make_band_structured_solver<Dim>(pr.grid, BandReuse::Preconditioner, 1e-12);
  ASSERT_NE(band, nullptr);
  Field<Dim> x(pr.grid.owned, 0);
  band->solve(pr.coeff, pr.rhs, x, false);
  EXPECT_LT(rel_error(x, pr.exact), kTol);
  constexpr double kKappa = 4e3;
  Problem<Dim> near = make_problem<Dim>(n, open_top, 0.01);  // faces moved by up to 0.4%
  for (const double tolerance : {1e-12, 1e-3}) {
    band->set_tolerance(tolerance);
    const double e = reuse_error(*band, near);
    std::printf("%dD %s, nearby coefficients, tolerance %.0e: error %.2e\n", Dim, open_top ? "open top" : "pinned",
                tolerance, e);
    EXPECT_LT(e, kKappa * tolerance);
    if (tolerance > 1e-6) {
      EXPECT_GT(e, 1e3 * kTol);
    }
  }
  band->set_tolerance(1e-3);
  const double ef = reuse_error(*band, make_problem<Dim>(n, open_top, 0.0, 3.0));
  std::printf("  far moved coefficients, tolerance 1e-3: error %.2e\n", ef);
  EXPECT_LT(ef, kTol);
}

TEST(BandPressureSolver, PreconditionedReusePaperBed) { check_preconditioned_reuse<2>({30, 50}, true); }
TEST(BandPressureSolver, PreconditionedReusePinned) { check_preconditioned_reuse<2>({17, 9}, false); }
TEST(BandPressureSolver, PreconditionedReuseThinSlab) { check_preconditioned_reuse<3>({12, 20, 2}, true); }

TEST(BandPressureSolver, WideBandIsLeftToTheOtherBackends) {
  Vec<3> e3{};
  for (int a = 0; a < 3; ++a) e3[a] = 1.0;
  // The 3D slab of cases/tfm3d: band 30 x 2 = 60 with the height slowest; the column: 16 x 16 = 256 at best.
  EXPECT_NE(make_band_structured_solver<3>(Grid<3>::uniform(e3, Index<3>{30, 50, 2}, 0)), nullptr);
  EXPECT_EQ(make_band_structured_solver<3>(Grid<3>::uniform(e3, Index<3>{16, 50, 16}, 0)), nullptr);
  Vec<2> e2{};
  for (int a = 0; a < 2; ++a) e2[a] = 1.0;
  EXPECT_EQ(make_band_structured_solver<2>(Grid<2>::uniform(e2, Index<2>{kMaxPressureBand + 1, 70}, 0)), nullptr);
  EXPECT_NE(make_band_structured_solver<2>(Grid<2>::uniform(e2, Index<2>{kMaxPressureBand + 1, 10}, 0)), nullptr);
  EXPECT_NE(make_band_structured_solver<2>(Grid<2>::uniform(e2, Index<2>{kMaxPressureBand, 10}, 0)), nullptr);
}

TEST(BandPressureSolver, ANonFiniteRowNamesItsCellInEveryBackend) {
  // The band and the Eigen backends share one message (fluid/pressure_correction.hpp, throw_non_finite_row).
  Problem<2> pr = make_problem<2>({6, 5}, true);
  pr.rhs[Index<2>{3, 2}] = std::nan("");
  Field<2> x(pr.grid.owned, 0);
  std::unique_ptr<StructuredSolver<2>> solvers[] = {make_band_structured_solver<2>(pr.grid),
                                                    make_eigen_structured_solver<2>(pr.grid)};
  for (const auto& solver : solvers) {
    ASSERT_NE(solver, nullptr);
    try {
      solver->solve(pr.coeff, pr.rhs, x, false);
      ADD_FAILURE() << "a NaN imbalance was solved";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("cell (3, 2) is not finite (imbalance nan)"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace fluidbed::tfm
