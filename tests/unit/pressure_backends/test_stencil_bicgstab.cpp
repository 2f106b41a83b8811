// StencilBicgstab (src/numerics/stencil_bicgstab.hpp) on one process: the answer of a nonsymmetric, diagonally
// dominant stencil system against a known solution (2D, 3D, a periodic axis), the answer of the checked Eigen
// solver it replaces in the two-fluid model, the LU fallback when the iterations are capped, a non-finite row named
// by its global row, and the refusals. Its bits on 1-4 ranks: tests/mpi/test_stencil_bicgstab_ranks.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "numerics/stencil_bicgstab.hpp"
#include "numerics/stencil_matrix.hpp"

namespace fluidbed {
namespace {

// A value in [e^-1, e^1] from the global cell and a salt (the same wherever it is asked).
template <int Dim>
double value(const Index<Dim>& c, int salt) {
  double phase = 0.41 * salt;
  for (int a = 0; a < Dim; ++a) phase += (0.33 + 0.17 * a) * c[a] + 0.011 * c[a] * c[a];
  return std::exp(std::sin(phase));
}

// The rows of an upwind-like transport operator: 1/dt on the diagonal plus the outflows, minus the inflows from the
// neighbours (nonsymmetric), with no neighbour beyond a wall. `global` numbers every cell of the domain.
template <int Dim>
struct Problem {
  std::vector<double> diag;
  std::vector<std::array<double, 2 * Dim>> off;
  std::vector<double> x_true;
};

template <int Dim>
Problem<Dim> problem(const Grid<Dim>& g) {
  Problem<Dim> p;
  for_each(g.owned, [&](const Index<Dim>& c) {
    std::array<double, 2 * Dim> off{};
    double diag = 4.0;
    for (int a = 0; a < Dim; ++a)
      for (int side = 0; side < 2; ++side) {
        Index<Dim> nb = c;
        nb[a] += side ? 1 : -1;
        const bool wall = !g.periodic[static_cast<std::size_t>(a)] && (nb[a] < g.domain.lo[a] || nb[a] >= g.domain.hi[a]);
        if (wall) continue;
        const double w = value<Dim>(c, 2 * a + side);
        off[static_cast<std::size_t>(2 * a + side)] = -w;
        diag += 1.1 * w * (side ? 0.7 : 1.3);  // outflow unlike inflow: nonsymmetric, still dominant
      }
    p.diag.push_back(diag);
    p.off.push_back(off);
    p.x_true.push_back(value<Dim>(c, 9) - 1.2);
  });
  return p;
}

// b = A x_true, from the global definition of every neighbour's value.
template <int Dim>
std::vector<double> rhs_of(const Grid<Dim>& g, const Problem<Dim>& p) {
  std::vector<double> b;
  std::size_t r = 0;
  for_each(g.owned, [&](const Index<Dim>& c) {
    double s = p.diag[r] * p.x_true[r];
    for (int k = 0; k < 2 * Dim; ++k) {
      if (p.off[r][static_cast<std::size_t>(k)] == 0.0) continue;
      Index<Dim> nb = c;
      nb[k / 2] = g.wrap(k / 2, nb[k / 2] + (k % 2 ? 1 : -1));
      s += p.off[r][static_cast<std::size_t>(k)] * (value<Dim>(nb, 9) - 1.2);
    }
    b.push_back(s);
    ++r;
  });
  return b;
}

template <int Dim>
double solve_error(const Index<Dim>& n, int periodic_axis, int* iterations = nullptr) {
  Vec<Dim> ext{};
  for (int a = 0; a < Dim; ++a) ext[a] = 0.1 * n[a];
  Grid<Dim> g = Grid<Dim>::uniform(ext, n, 1);
  if (periodic_axis >= 0) g.periodic[static_cast<std::size_t>(periodic_axis)] = true;
  const Problem<Dim> p = problem(g);
  StencilBicgstab<Dim> solver(g, serial_comm());
  for (int r = 0; r < solver.rows(); ++r) solver.set_row(r, p.diag[static_cast<std::size_t>(r)], p.off[static_cast<std::size_t>(r)]);
  solver.set_tolerance(1e-12);
  std::vector<double> x;
  const LinearSolveOutcome out = solver.solve(rhs_of(g, p), x);
  EXPECT_TRUE(out.ok) << out.why;
  EXPECT_FALSE(out.fell_back);
  EXPECT_LE(out.error, 1e-12);
  if (iterations) *iterations = out.iterations;
  double e = 0.0;
  for (std::size_t r = 0; r < x.size(); ++r) e = std::max(e, std::abs(x[r] - p.x_true[r]));
  return e;
}

// The rows are diagonally dominant by at least 4 against values of order 1-3, so the condition number is of order
// ten: an answer to relative residual 1e-12 is within ~1e-11 of x_true.
TEST(StencilBicgstab, KnownSolution2d) {
  int its = 0;
  EXPECT_LT(solve_error<2>({17, 23}, -1, &its), 1e-11);
  EXPECT_LT(its, 40);
}
TEST(StencilBicgstab, KnownSolution3d) { EXPECT_LT(solve_error<3>({9, 11, 7}, -1), 1e-11); }
TEST(StencilBicgstab, KnownSolutionPeriodic) {
  EXPECT_LT(solve_error<2>({13, 10}, 0), 1e-11);
  EXPECT_LT(solve_error<3>({6, 9, 5}, 2), 1e-11);
}

TEST(StencilBicgstab, AgreesWithTheCheckedEigenSolver) {
  const Grid<2> g = Grid<2>::uniform({1.2, 1.6}, {12, 16}, 1);
  const Problem<2> p = problem(g);
  StencilBicgstab<2> mine(g, serial_comm());
  std::vector<std::array<int, 4>> nb;
  StencilMatrix m;
  for_each(g.owned, [&](const Index<2>& c) {
    std::array<int, 4> r{};
    for (int k = 0; k < 4; ++k) {
      Index<2> q = c;
      q[k / 2] += k % 2 ? 1 : -1;
      r[static_cast<std::size_t>(k)] = (q[k / 2] < 0 || q[k / 2] >= g.domain.hi[k / 2]) ? -1 : q[0] + 12 * q[1];
    }
    nb.push_back(r);
  });
  m.build(static_cast<int>(nb.size()), nb);
  for (int r = 0; r < mine.rows(); ++r) {
    mine.set_row(r, p.diag[static_cast<std::size_t>(r)], p.off[static_cast<std::size_t>(r)]);
    m.set_row(r, p.diag[static_cast<std::size_t>(r)], p.off[static_cast<std::size_t>(r)]);
  }
  const std::vector<double> b = rhs_of(g, p);
  std::vector<double> x;
  mine.set_tolerance(1e-13);
  ASSERT_TRUE(mine.solve(b, x).ok);
  CheckedSparseSolver eigen;
  eigen.set_tolerance(1e-13);
  Eigen::VectorXd y;
  ASSERT_TRUE(eigen.solve(m.matrix(), Eigen::Map<const Eigen::VectorXd>(b.data(), static_cast<Eigen::Index>(b.size())), y).ok);
  double d = 0.0;
  for (std::size_t r = 0; r < x.size(); ++r) d = std::max(d, std::abs(x[r] - y[static_cast<Eigen::Index>(r)]));
  EXPECT_LT(d, 1e-12);
}

TEST(StencilBicgstab, CappedIterationsFallBackToTheLu) {
  const Grid<3> g = Grid<3>::uniform({0.5, 0.6, 0.4}, {5, 6, 4}, 1);
  const Problem<3> p = problem(g);
  StencilBicgstab<3> solver(g, serial_comm());
  for (int r = 0; r < solver.rows(); ++r) solver.set_row(r, p.diag[static_cast<std::size_t>(r)], p.off[static_cast<std::size_t>(r)]);
  solver.set_tolerance(1e-14);
  solver.set_max_iterations(1);
  std::vector<double> x;
  const LinearSolveOutcome out = solver.solve(rhs_of(g, p), x);
  EXPECT_TRUE(out.ok) << out.why;
  EXPECT_TRUE(out.fell_back);
  EXPECT_LE(out.backward_error, kDirectBackwardError);
  double e = 0.0;
  for (std::size_t r = 0; r < x.size(); ++r) e = std::max(e, std::abs(x[r] - p.x_true[r]));
  EXPECT_LT(e, 1e-12);
}

TEST(StencilBicgstab, NonFiniteRowIsNamed) {
  const Grid<2> g = Grid<2>::uniform({0.4, 0.3}, {4, 3}, 1);
  StencilBicgstab<2> solver(g, serial_comm());
  for (int r = 0; r < solver.rows(); ++r) solver.set_row(r, 4.0, {0.0, -1.0, 0.0, 0.0});
  solver.set_row(6, NAN, {0.0, 0.0, 0.0, 0.0});
  std::vector<double> x, b(12, 1.0);
  const LinearSolveOutcome out = solver.solve(b, x);
  EXPECT_FALSE(out.ok);
  EXPECT_EQ(out.bad_row, 6);
  EXPECT_NE(out.why.find("row 6"), std::string::npos) << out.why;
}

TEST(StencilBicgstab, RefusesWhatItCannotSolveByName) {
  Grid<2> g = Grid<2>::uniform({0.2, 0.3}, {2, 3}, 1);
  g.periodic = {true, false};
  try {
    StencilBicgstab<2> s(g, serial_comm());
    FAIL() << "a periodic axis of 2 cells was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fewer than 3 cells"), std::string::npos) << e.what();
  }
  Grid<2> cut = Grid<2>::uniform({1.0, 1.0}, {10, 10}, 1);
  cut.owned.hi[0] = 5;  // a block that does not span axis 0
  try {
    StencilBicgstab<2> s(cut, serial_comm());
    FAIL() << "a block cut along axis 0 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("axis 0 (x) is cut"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fluidbed
