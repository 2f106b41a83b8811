// The Eigen pressure-correction backend: manufactured solutions, direct and iterative paths.
#include <gtest/gtest.h>

#include <cmath>

#include "numerics/pressure_correction.hpp"

namespace fluidbed {
namespace {

// rhs = A x for the five-point operator aP x_P - sum a_nb x_nb, with p' = 0 beyond boundary faces.
Field<2> apply(const FaceFields<2>& a, const Field<2>& x) {
  const int nx = x.box().extent(0);
  const int ny = x.box().extent(1);
  Field<2> r(x.box(), 0);
  const Field<2>& ax = a[0];
  const Field<2>& ay = a[1];
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      double s = (ax(i, j) + ax(i + 1, j) + ay(i, j) + ay(i, j + 1)) * x(i, j);
      if (i > 0) s -= ax(i, j) * x(i - 1, j);
      if (i < nx - 1) s -= ax(i + 1, j) * x(i + 1, j);
      if (j > 0) s -= ay(i, j) * x(i, j - 1);
      if (j < ny - 1) s -= ay(i, j + 1) * x(i, j + 1);
      r(i, j) = s;
    }
  return r;
}

struct Problem {
  Grid<2> grid;
  FaceFields<2> coeff;
  Field<2> exact;
};

// Spatially varying positive coefficients (as rho eps A d would be), walls at the sides and bottom.
Problem make_problem(bool open_top) {
  const Grid<2> g = Grid<2>::uniform({1.0, 1.0}, {7, 9});
  Problem p{g, FaceFields<2>(g.owned, 0), cell_field(g)};
  for (int j = 0; j < 9; ++j)
    for (int i = 1; i < 7; ++i) p.coeff[0](i, j) = 1.0 + 0.1 * i + 0.05 * j;
  for (int j = 1; j < 9; ++j)
    for (int i = 0; i < 7; ++i) p.coeff[1](i, j) = 2.0 + 0.03 * i * j;
  if (open_top)
    for (int i = 0; i < 7; ++i) p.coeff[1](i, 9) = 3.0;
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 7; ++i) p.exact(i, j) = std::sin(0.7 * i + 0.3) * std::cos(0.4 * j);
  return p;
}

// Direct LDLT: round-off only, relative 1e-12 of the O(1) solution. CG to 1e-12 relative residual:
// error bounded by the condition number (about 1e2 here) times that, so 1e-9.
TEST(PressureCorrection, ManufacturedSolutionWithOutlet) {
  const Problem p = make_problem(true);
  const Field<2> rhs = apply(p.coeff, p.exact);
  for (auto kind : {PressureSolverKind::Direct, PressureSolverKind::ConjugateGradient}) {
    const auto solver = make_eigen_structured_solver<2>(p.grid, kind);
    Field<2> x = cell_field(p.grid);
    solver->solve(p.coeff, rhs, x, false);
    const double tol = kind == PressureSolverKind::Direct ? 1e-12 : 1e-9;
    for (std::size_t k = 0; k < x.data().size(); ++k) EXPECT_NEAR(x.data()[k], p.exact.data()[k], tol);
    // A second solve with new coefficients reuses the symbolic analysis and must still be right.
    Problem q = p;
    for (double& a : q.coeff[1].data()) a *= 1.5;
    const Field<2> rhs_q = apply(q.coeff, q.exact);
    solver->solve(q.coeff, rhs_q, x, false);
    for (std::size_t k = 0; k < x.data().size(); ++k) EXPECT_NEAR(x.data()[k], q.exact.data()[k], tol);
  }
}

TEST(PressureCorrection, ClosedDomainPinsFirstCell) {
  Problem p = make_problem(false);
  const double shift = p.exact(0, 0);
  for (double& v : p.exact.data()) v -= shift;  // the pinned cell holds zero
  const Field<2> rhs = apply(p.coeff, p.exact);
  const auto solver = make_eigen_structured_solver<2>(p.grid);
  Field<2> x = cell_field(p.grid);
  solver->solve(p.coeff, rhs, x, false);
  for (std::size_t k = 0; k < x.data().size(); ++k) EXPECT_NEAR(x.data()[k], p.exact.data()[k], 1e-11);
}

}  // namespace
}  // namespace fluidbed
