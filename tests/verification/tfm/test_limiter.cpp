// Verification of the TVD convection operator (paper section 2.2.1): profiles advected once around a
// periodic 1D domain keep their bounds and converge at better than first order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "tfm/tvd_convection.hpp"

namespace fluidbed::tfm {
namespace {

// SSP-RK2 (Heun) is TVD for the same CFL limit as forward Euler, so the limiter alone decides boundedness,
// and its O(dt^2) error does not hide the spatial order.
// One SSP-RK2 step of d(phi)/dt + div(U phi) = 0 on a grid periodic along every axis.
template <int Dim>
void rk2_step(const Grid<Dim>& g, Limiter lim, const FaceVelocity<Dim>& vel, double dt, Field<Dim>& phi,
              Field<Dim>& stage, Field<Dim>& k1, Field<Dim>& k2) {
  fill_cell_ghosts(phi, vel.periodic);
  convective_divergence(g, lim, phi, vel, k1);
  for_each(g.domain, [&](const Index<Dim>& c) { stage[c] = phi[c] - dt * k1[c]; });
  fill_cell_ghosts(stage, vel.periodic);
  convective_divergence(g, lim, stage, vel, k2);
  for_each(g.domain, [&](const Index<Dim>& c) { phi[c] = 0.5 * (phi[c] + stage[c] - dt * k2[c]); });
}

// The profile once around a periodic 1D domain of n cells (a row of a 2D grid), returned as the n cell values.
std::vector<double> advect_periodic(Limiter lim, int n, double velocity, double cfl,
                                    const std::function<double(double)>& f0) {
  const Grid<2> g = Grid<2>::uniform({1.0, 1.0 / n}, {n, 1}, kGhost);
  Field<2> phi(g.domain, kGhost), stage(g.domain, kGhost), k1, k2;
  for (int i = 0; i < n; ++i) phi(i, 0) = f0(g.centre(0, i));
  FaceFields<2> u(g.domain, kGhost);
  u[0].fill(velocity);
  const FaceVelocity<2> vel{u, {true, true}};
  const double h = 1.0 / n;
  const int steps = static_cast<int>(std::lround(1.0 / (cfl * h / std::abs(velocity))));
  const double dt = 1.0 / (steps * std::abs(velocity));
  for (int s = 0; s < steps; ++s) rk2_step(g, lim, vel, dt, phi, stage, k1, k2);
  return phi.interior();
}

double square_wave(double x) { return (x > 0.25 && x < 0.55) ? 1.0 : 0.0; }
double gaussian(double x) { return std::exp(-std::pow((x - 0.5) / 0.1, 2)); }

double l1_error(const std::vector<double>& phi, const std::function<double(double)>& exact) {
  const int n = static_cast<int>(phi.size());
  double err = 0.0;
  for (int i = 0; i < n; ++i) {
    // Exact cell average by 8-point midpoint sampling: its error is far below the scheme's.
    double avg = 0.0;
    for (int k = 0; k < 8; ++k) avg += exact((i + (k + 0.5) / 8.0) / n) / 8.0;
    err += std::abs(phi[static_cast<std::size_t>(i)] - avg) / n;
  }
  return err;
}

// The cell update is a convex combination for CFL <= 0.5; rounding of that combination is the only
// way past the bounds, hence a few ulps of tolerance.
constexpr double kRounding = 1e-14;

TEST(TvdLimiter, SquareWaveKeepsBoundsForEveryLimiter) {
  for (Limiter lim : {Limiter::Superbee, Limiter::Minmod, Limiter::VanLeer, Limiter::Upwind}) {
    for (double vel : {1.0, -1.0}) {
      const std::vector<double> phi = advect_periodic(lim, 100, vel, 0.45, square_wave);
      const auto [lo, hi] = std::minmax_element(phi.begin(), phi.end());
      EXPECT_GE(*lo, -kRounding) << "limiter " << static_cast<int>(lim) << " U=" << vel;
      EXPECT_LE(*hi, 1.0 + kRounding) << "limiter " << static_cast<int>(lim) << " U=" << vel;
    }
  }
}

TEST(TvdLimiter, SmoothProfileKeepsBounds) {
  const std::vector<double> phi = advect_periodic(Limiter::Superbee, 100, 1.0, 0.45, gaussian);
  double init_max = 0.0, init_min = 1.0;
  for (int i = 0; i < 100; ++i) {
    init_max = std::max(init_max, gaussian((i + 0.5) / 100));
    init_min = std::min(init_min, gaussian((i + 0.5) / 100));
  }
  const auto [lo, hi] = std::minmax_element(phi.begin(), phi.end());
  EXPECT_GE(*lo, init_min - kRounding);
  EXPECT_LE(*hi, init_max + kRounding);
}

TEST(TvdLimiter, DirectionOfVelocityIsMirrorSymmetric) {
  // Advecting a profile left must give the mirror image of advecting its mirror image right.
  auto f = [](double x) { return square_wave(x) + 0.5 * gaussian(x + 0.2); };
  auto mirrored = [&](double x) { return f(1.0 - x); };
  const std::vector<double> right = advect_periodic(Limiter::Superbee, 64, 1.0, 0.4, mirrored);
  const std::vector<double> left = advect_periodic(Limiter::Superbee, 64, -1.0, 0.4, f);
  for (std::size_t i = 0; i < 64; ++i) EXPECT_NEAR(left[i], right[63 - i], 1e-12) << i;
}

// Grids of 100, 200 and 400 cells (10-40 cells per Gaussian width): on coarser grids superbee's
// compression squares the profile off and the error is not yet in its asymptotic range.
constexpr int N1 = 100;
double observed_order(Limiter lim) {
  const double e1 = l1_error(advect_periodic(lim, N1, 1.0, 0.4, gaussian), gaussian);
  const double e2 = l1_error(advect_periodic(lim, 2 * N1, 1.0, 0.4, gaussian), gaussian);
  const double e3 = l1_error(advect_periodic(lim, 4 * N1, 1.0, 0.4, gaussian), gaussian);
  const double order = std::log2(e2 / e3);
  std::printf("limiter %d: L1 errors %.3e %.3e %.3e, orders %.2f %.2f\n", static_cast<int>(lim), e1, e2, e3,
              std::log2(e1 / e2), order);
  return order;
}

TEST(TvdLimiter, SmoothProfileConvergesBetterThanFirstOrder) {
  // TVD limiters fall to first order only at the extremum (a few cells), so the L1 order sits between
  // 1 and 2 (measured 1.6-1.9); 1.3 separates them from upwind, which this same measurement puts below 1
  // (0.76: still approaching its asymptotic order 1 from below), so the check can fail.
  EXPECT_GT(observed_order(Limiter::Superbee), 1.3);
  EXPECT_GT(observed_order(Limiter::VanLeer), 1.3);
  EXPECT_GT(observed_order(Limiter::Minmod), 1.3);
  EXPECT_LT(observed_order(Limiter::Upwind), 1.15);
}

TEST(TvdLimiter, ImplicitStepConservesAndSharpens) {
  const int n = 100;
  const Grid<2> g = Grid<2>::uniform({1.0, 1.0 / n}, {n, 1}, kGhost);
  FaceFields<2> u(g.domain, kGhost);
  u[0].fill(1.0);
  const FaceVelocity<2> vel{u, {true, false}};
  Field<2> sb(g.domain, kGhost), up(g.domain, kGhost);
  for (int i = 0; i < n; ++i) sb(i, 0) = up(i, 0) = square_wave(g.centre(0, i));
  const double dt = 0.5 * g.h[0];
  double mass0 = 0.0;
  for (double x : sb.interior()) mass0 += x;
  for (int s = 0; s < 100; ++s) {
    sb = advance_scalar_implicit(g, Limiter::Superbee, sb, vel, dt, 3);
    up = advance_scalar_implicit(g, Limiter::Upwind, up, vel, dt, 0);
  }
  double mass = 0.0;
  const std::vector<double> sb_cells = sb.interior(), up_cells = up.interior();
  for (double x : sb_cells) mass += x;
  // Conservative final flux evaluation: only rounding (about n * steps * 1e-16) can change the sum.
  EXPECT_NEAR(mass / mass0, 1.0, 1e-12);
  const double peak_sb = *std::max_element(sb_cells.begin(), sb_cells.end());
  const double peak_up = *std::max_element(up_cells.begin(), up_cells.end());
  std::printf("implicit after 100 steps: peak superbee %.4f, upwind %.4f, min superbee %.2e\n", peak_sb, peak_up,
              *std::min_element(sb_cells.begin(), sb_cells.end()));
  // Backward-Euler upwind smears the 30-cell plateau far more than the limited scheme.
  EXPECT_GT(peak_sb, peak_up + 0.05);
}


// ---- 3D (issue 13, acceptance 2): a cube periodic along every axis, a profile carried along the body diagonal
// U = (1, 1, 1) once around (t = 1, the exact answer is the initial profile). The unsplit update is a convex
// combination when the sum of the three Courant numbers is at most 0.5 (the 1D bound of the limited upwind
// scheme, psi <= 2), so 0.45 summed (0.15 per axis) keeps every limiter within the bounds up to rounding.
using Profile3 = std::function<double(double, double, double)>;

std::vector<double> advect_diagonal_3d(Limiter lim, int n, const Profile3& f0) {
  const Grid<3> g = Grid<3>::uniform({1.0, 1.0, 1.0}, {n, n, n}, kGhost);
  Field<3> phi(g.domain, kGhost), stage(g.domain, kGhost), k1, k2;
  for_each(g.domain, [&](const Index<3>& c) { phi[c] = f0(g.centre(0, c[0]), g.centre(1, c[1]), g.centre(2, c[2])); });
  FaceFields<3> u(g.domain, kGhost, 1.0);
  const FaceVelocity<3> vel{u, {true, true, true}};
  const double courant_sum = 0.45;
  const int steps = static_cast<int>(std::lround(3.0 * n / courant_sum));
  const double dt = 1.0 / steps;
  for (int s = 0; s < steps; ++s) rk2_step(g, lim, vel, dt, phi, stage, k1, k2);
  return phi.interior();
}

double box3(double x, double y, double z) { return square_wave(x) * square_wave(y) * square_wave(z); }
double gaussian3(double x, double y, double z) { return gaussian(x) * gaussian(y) * gaussian(z); }

// L1 error against the exact cell averages: the profile is a product, so its cell average is the product of the
// 1D averages (8-point midpoint sampling each, far below the scheme's error).
double l1_error_3d(const std::vector<double>& phi, int n) {
  std::vector<double> avg(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 8; ++k) avg[static_cast<std::size_t>(i)] += gaussian((i + (k + 0.5) / 8.0) / n) / 8.0;
  }
  double err = 0.0;
  std::size_t c = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i, ++c) {
        const double exact = avg[static_cast<std::size_t>(i)] * avg[static_cast<std::size_t>(j)] * avg[static_cast<std::size_t>(k)];
        err += std::abs(phi[c] - exact) / (static_cast<double>(n) * n * n);
      }
  return err;
}

TEST(TvdLimiter3d, BoxKeepsBoundsForEveryLimiter) {
  for (Limiter lim : {Limiter::Superbee, Limiter::Minmod, Limiter::VanLeer, Limiter::Upwind}) {
    const std::vector<double> phi = advect_diagonal_3d(lim, 16, box3);
    const auto [lo, hi] = std::minmax_element(phi.begin(), phi.end());
    std::printf("3D box, limiter %d: exact bounds [0, 1], computed [%.3e, %.15f]\n", static_cast<int>(lim), *lo, *hi);
    EXPECT_GE(*lo, -kRounding) << "limiter " << static_cast<int>(lim);
    EXPECT_LE(*hi, 1.0 + kRounding) << "limiter " << static_cast<int>(lim);
  }
}

double observed_order_3d(Limiter lim) {
  const double e1 = l1_error_3d(advect_diagonal_3d(lim, 16, gaussian3), 16);
  const double e2 = l1_error_3d(advect_diagonal_3d(lim, 32, gaussian3), 32);
  const double order = std::log2(e1 / e2);
  std::printf("3D limiter %d: L1 errors %.3e (16^3) %.3e (32^3), order %.2f\n", static_cast<int>(lim), e1, e2, order);
  return order;
}

TEST(TvdLimiter3d, SmoothProfileConvergesBetterThanFirstOrder) {
  // 1.6 to 3.2 cells per Gaussian width: far from the asymptotic range, where upwind's order lies well below 1
  // (its error is still growing towards the O(h) regime; measured 0.20) and superbee gains far more (1.47, as the
  // 1D test at its coarsest pair of grids); 1.2 and 1.0 separate the two with margin, so the check can fail.
  const double sb = observed_order_3d(Limiter::Superbee);
  const double up = observed_order_3d(Limiter::Upwind);
  EXPECT_GT(sb, 1.2);
  EXPECT_LT(up, 1.0);
  EXPECT_GT(sb, up + 0.3);
}

}  // namespace
}  // namespace fluidbed::tfm
