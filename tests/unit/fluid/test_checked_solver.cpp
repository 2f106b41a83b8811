// CheckedSparseSolver: a linear solve is never accepted unless it converged. BiCGSTAB capped below what it needs
// must hand over to the sparse LU (same answer to the direct solve's round-off), a singular or non-finite system
// must be reported, not returned; and the gas momentum with a one-iteration cap gives the converged step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "fluid/gas_solver.hpp"
#include "numerics/stencil_matrix.hpp"

namespace fluidbed {
namespace {

// Convection-diffusion on an n x n grid (upwind, Peclet 5 per cell): nonsymmetric, diagonally dominant, so
// BiCGSTAB converges in some tens of iterations and one iteration is far from enough.
StencilMatrix convection_diffusion(int n) {
  StencilMatrix m;
  m.build_cells(n, n);
  for (int r = 0; r < n * n; ++r) m.set_row(r, 4.0 + 5.0 + 0.1, {-1.0 - 5.0, -1.0, -1.0, -1.0});
  return m;
}

Eigen::VectorXd rhs(int size) {
  Eigen::VectorXd b(size);
  for (int k = 0; k < size; ++k) b[k] = std::sin(0.37 * k) + 0.5;
  return b;
}

TEST(CheckedSparseSolver, ConvergedBicgstabIsAcceptedWithoutFallback) {
  const StencilMatrix m = convection_diffusion(20);
  const Eigen::VectorXd b = rhs(400);
  CheckedSparseSolver s;
  s.set_tolerance(1e-12);
  Eigen::VectorXd x;
  const LinearSolveOutcome out = s.solve(m.matrix(), b, x);
  EXPECT_TRUE(out.ok);
  EXPECT_FALSE(out.fell_back);
  EXPECT_GT(out.iterations, 1);
  EXPECT_LT((m.matrix() * x - b).norm() / b.norm(), 1e-11);
}

// The solver runs Eigen's BiCGSTAB algorithm itself (kept vectors, products by diagonals): it must give Eigen's
// answer bit for bit, with Eigen's iteration count, from a zero and from a non-zero guess, on a five-point matrix
// with varying coefficients, boundary rows with fewer entries and explicit zeros, and on a pattern with more
// diagonals than the diagonal layout takes (the row-loop product).
TEST(CheckedSparseSolver, BicgstabGivesEigensAnswerBitForBit) {
  // One solver for every system, so that its cached diagonal layout must follow each change of pattern.
  CheckedSparseSolver s;
  s.set_tolerance(1e-12);
  auto check = [&s](const StencilMatrix::Matrix& a, const Eigen::VectorXd& b, const Eigen::VectorXd& guess) {
    Eigen::BiCGSTAB<StencilMatrix::Matrix, Eigen::DiagonalPreconditioner<double>> eigen;
    eigen.setTolerance(1e-12);
    eigen.compute(a);
    const Eigen::VectorXd x_ref = eigen.solveWithGuess(b, guess);
    Eigen::VectorXd x = guess;
    const LinearSolveOutcome out = s.solve(a, b, x);
    ASSERT_TRUE(out.ok);
    EXPECT_FALSE(out.fell_back);
    EXPECT_EQ(out.iterations, eigen.iterations());
    EXPECT_EQ(out.error, eigen.error());
    ASSERT_EQ(x.size(), x_ref.size());
    int differ = 0;
    for (Eigen::Index k = 0; k < x.size(); ++k) differ += std::memcmp(&x[k], &x_ref[k], sizeof(double)) != 0;
    EXPECT_EQ(differ, 0);
  };
  const int nx = 13, ny = 9, n = nx * ny;
  StencilMatrix m;
  m.build_cells(nx, ny);
  for (int r = 0; r < n; ++r) {
    const double w = 1.0 + 0.3 * std::sin(0.7 * r), e = r % 5 == 0 ? 0.0 : 0.5 + 0.2 * std::cos(1.3 * r);
    m.set_row(r, 3.5 + w + e, {-w, -e, -0.8 - 0.1 * std::sin(0.2 * r), -1.1});
  }
  const Eigen::VectorXd b = rhs(n);
  check(m.matrix(), b, Eigen::VectorXd::Zero(n));
  Eigen::VectorXd guess(n);
  for (int k = 0; k < n; ++k) guess[k] = 0.1 * std::cos(0.5 * k);
  check(m.matrix(), b, guess);
  // Ten diagonals: more than the diagonal layout takes.
  std::vector<Eigen::Triplet<double>> t;
  for (int r = 0; r < n; ++r) {
    t.emplace_back(r, r, 12.0 + std::sin(r));
    for (int off : {-40, -20, -9, -3, -1, 2, 7, 21, 33})
      if (r + off >= 0 && r + off < n) t.emplace_back(r, r + off, -1.0 + 0.1 * std::cos(r + off));
  }
  StencilMatrix::Matrix wide(n, n);
  wide.setFromTriplets(t.begin(), t.end());
  check(wide, b, guess);
  // Back to the five-point pattern with other values: the layout is rebuilt and the old values are gone.
  for (int r = 0; r < n; ++r) m.set_row(r, 5.0 + 0.01 * r, {-1.0, -0.5, -1.2, r % 3 == 0 ? 0.0 : -0.9});
  check(m.matrix(), b, guess);
  check(m.matrix(), b, Eigen::VectorXd::Zero(n));
}

TEST(CheckedSparseSolver, IterationCapFallsBackToLuWithTheSameAnswer) {
  const StencilMatrix m = convection_diffusion(20);
  const Eigen::VectorXd b = rhs(400);
  CheckedSparseSolver converged, capped;
  converged.set_tolerance(1e-12);
  capped.set_tolerance(1e-12);
  capped.set_max_iterations(1);
  Eigen::VectorXd x_ref, x;
  ASSERT_TRUE(converged.solve(m.matrix(), b, x_ref).ok);
  const LinearSolveOutcome out = capped.solve(m.matrix(), b, x);
  std::printf("capped BiCGSTAB: %d iteration, error %.3e; LU backward error %.3e, |x - x_ref| %.3e\n", out.iterations,
              out.error, out.backward_error, (x - x_ref).lpNorm<Eigen::Infinity>());
  EXPECT_TRUE(out.ok);
  EXPECT_TRUE(out.fell_back);
  EXPECT_GT(out.error, 1e-12);  // the cap really stopped BiCGSTAB short
  EXPECT_LT(out.backward_error, kDirectBackwardError);
  // Both answers have relative residuals of 1e-12 or less; the matrix is well conditioned (diagonal dominance 0.1
  // over the off-diagonal sum), so they agree to a few hundred times that.
  EXPECT_LT((x - x_ref).lpNorm<Eigen::Infinity>(), 1e-9 * x_ref.lpNorm<Eigen::Infinity>());
}

TEST(CheckedSparseSolver, SingularSystemIsReportedNotReturned) {
  StencilMatrix m = convection_diffusion(10);
  m.set_row(37, 0.0, {0.0, 0.0, 0.0, 0.0});  // a row of zeros: no answer exists for b[37] != 0
  CheckedSparseSolver s;
  s.set_tolerance(1e-12);
  Eigen::VectorXd x;
  const LinearSolveOutcome out = s.solve(m.matrix(), rhs(100), x);
  EXPECT_FALSE(out.ok);
  EXPECT_TRUE(out.fell_back);
  EXPECT_NE(out.why.find("singular"), std::string::npos) << out.why;
}

TEST(CheckedSparseSolver, NonFiniteCoefficientNamesItsRow) {
  StencilMatrix m = convection_diffusion(10);
  m.set_row(42, NAN, {-1.0, -1.0, -1.0, -1.0});
  CheckedSparseSolver s;
  Eigen::VectorXd x;
  const LinearSolveOutcome out = s.solve(m.matrix(), rhs(100), x);
  EXPECT_FALSE(out.ok);
  EXPECT_EQ(out.bad_row, 42);
}

// The gas momentum of a drag-loaded bed (a CFD-DEM step): with the BiCGSTAB capped at one iteration every
// momentum solve must go to the LU, and the step must come out as the converged one (SIMPLE to 1e-8).
TEST(GasSolverLinearSolves, OneIterationCapFallsBackAndGivesTheConvergedStep) {
  const int nx = 12, ny = 20;
  const Grid<2> grid = Grid<2>::uniform({0.24, 0.4}, {nx, ny});
  GasConfig cfg;
  cfg.boundary.jets = {InletJet{0.12, 0.02, 20.0, 0.0, 1.0}};
  cfg.boundary.inlet_velocity = 1.8;
  Field<2> eps(cell_field(grid, 1.0)), beta(cell_field(grid, 0.0));
  for (int j = 0; j < ny / 2; ++j)
    for (int i = 0; i < nx; ++i) {
      eps(i, j) = 0.45 + 0.01 * ((i * 7 + j * 3) % 5);
      beta(i, j) = 2.0e4;
    }
  const Field<2> zero(cell_field(grid, 0.0));
  auto run = [&](int cap, int& fallbacks) {
    GasConfig c = cfg;
    c.momentum_solver_max_iterations = cap;
    GasSolver<2> gas(grid, c);
    fallbacks = 0;
    for (int step = 1; step <= 5; ++step) {
      fallbacks += gas.advance(step * 1e-3, 1e-3, eps, eps, beta, {zero, zero}).linear_fallbacks;
    }
    return gas.fields();
  };
  int fb_ref = 0, fb_capped = 0;
  const GasFields<2> ref = run(500, fb_ref);
  const GasFields<2> capped = run(1, fb_capped);
  EXPECT_EQ(fb_ref, 0);
  EXPECT_GT(fb_capped, 0);
  double du = 0.0, vmax = 0.0;
  for (std::size_t k = 0; k < ref.u[1].data().size(); ++k) {
    du = std::max(du, std::abs(ref.u[1].data()[k] - capped.u[1].data()[k]));
    vmax = std::max(vmax, std::abs(ref.u[1].data()[k]));
  }
  std::printf("gas step with capped momentum solves: %d LU fallbacks, max |dv| %.3e of %.3g m/s\n", fb_capped, du, vmax);
  // Both runs meet the SIMPLE mass tolerance 1e-8 (normalised by the inflow); the velocities agree to that order.
  EXPECT_LT(du, 1e-6 * vmax);
}

}  // namespace
}  // namespace fluidbed
