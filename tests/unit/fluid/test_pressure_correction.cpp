// The reusable pressure-correction solver: manufactured solutions, direct and iterative paths.
#include <gtest/gtest.h>

#include <cmath>

#include "numerics/pressure_correction.hpp"

namespace fluidbed {
namespace {

// rhs = A x for the five-point operator aP x_P - sum a_nb x_nb, with p' = 0 beyond boundary faces.
Field2 apply(const Field2& ax, const Field2& ay, const Field2& x) {
  const int nx = x.nx;
  const int ny = x.ny;
  Field2 r(nx, ny);
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
  Grid2 grid;
  Field2 ax, ay, exact;
};

// Spatially varying positive coefficients (as rho eps A d would be), walls at the sides and bottom.
Problem make_problem(bool open_top) {
  Problem p{Grid2::uniform(1.0, 1.0, 7, 9), Field2(8, 9), Field2(7, 10), Field2(7, 9)};
  for (int j = 0; j < 9; ++j)
    for (int i = 1; i < 7; ++i) p.ax(i, j) = 1.0 + 0.1 * i + 0.05 * j;
  for (int j = 1; j < 9; ++j)
    for (int i = 0; i < 7; ++i) p.ay(i, j) = 2.0 + 0.03 * i * j;
  if (open_top)
    for (int i = 0; i < 7; ++i) p.ay(i, 9) = 3.0;
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 7; ++i) p.exact(i, j) = std::sin(0.7 * i + 0.3) * std::cos(0.4 * j);
  return p;
}

// Direct LDLT: round-off only, relative 1e-12 of the O(1) solution. CG to 1e-12 relative residual:
// error bounded by the condition number (about 1e2 here) times that, so 1e-9.
TEST(PressureCorrection, ManufacturedSolutionWithOutlet) {
  const Problem p = make_problem(true);
  const Field2 rhs = apply(p.ax, p.ay, p.exact);
  for (auto kind : {PressureSolverKind::Direct, PressureSolverKind::ConjugateGradient}) {
    PressureCorrectionSolver solver(p.grid, kind);
    Field2 x(7, 9, 0.0);
    solver.solve(p.ax, p.ay, rhs, x);
    const double tol = kind == PressureSolverKind::Direct ? 1e-12 : 1e-9;
    for (std::size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(x.v[k], p.exact.v[k], tol);
    // A second solve with new coefficients reuses the symbolic analysis and must still be right.
    Problem q = p;
    for (double& a : q.ay.v) a *= 1.5;
    const Field2 rhs_q = apply(q.ax, q.ay, q.exact);
    solver.solve(q.ax, q.ay, rhs_q, x);
    for (std::size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(x.v[k], q.exact.v[k], tol);
  }
}

TEST(PressureCorrection, ClosedDomainPinsFirstCell) {
  Problem p = make_problem(false);
  const double shift = p.exact(0, 0);
  for (double& v : p.exact.v) v -= shift;  // the pinned cell holds zero
  const Field2 rhs = apply(p.ax, p.ay, p.exact);
  PressureCorrectionSolver solver(p.grid);
  Field2 x(7, 9, 0.0);
  solver.solve(p.ax, p.ay, rhs, x);
  for (std::size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(x.v[k], p.exact.v[k], 1e-11);
}

}  // namespace
}  // namespace fluidbed
