// Verification of the TVD convection operator (paper section 2.2.1): profiles advected once around a
// periodic 1D domain keep their bounds and converge at better than first order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "core/field2.hpp"
#include "core/grid2.hpp"
#include "tfm/tvd_convection.hpp"

namespace fluidbed::tfm {
namespace {

// SSP-RK2 (Heun) is TVD for the same CFL limit as forward Euler, so the limiter alone decides boundedness,
// and its O(dt^2) error does not hide the spatial order.
Field2 advect_periodic(Limiter lim, int n, double velocity, double cfl, const std::function<double(double)>& f0) {
  const Grid2 g = Grid2::uniform(1.0, 1.0 / n, n, 1);
  Field2 phi(g.nx, g.ny);
  for (int i = 0; i < g.nx; ++i) phi(i, 0) = f0(g.xc(i));
  Field2 u(g.nx + 1, g.ny, velocity);
  Field2 v(g.nx, g.ny + 1, 0.0);
  const FaceVelocity vel{u, v, true};
  const double h = 1.0 / n;
  const int steps = static_cast<int>(std::lround(1.0 / (cfl * h / std::abs(velocity))));
  const double dt = 1.0 / (steps * std::abs(velocity));
  Field2 k1, k2, stage(g.nx, g.ny);
  for (int s = 0; s < steps; ++s) {
    convective_divergence(g, lim, phi, vel, k1);
    for (std::size_t c = 0; c < phi.size(); ++c) stage.v[c] = phi.v[c] - dt * k1.v[c];
    convective_divergence(g, lim, stage, vel, k2);
    for (std::size_t c = 0; c < phi.size(); ++c) phi.v[c] = 0.5 * (phi.v[c] + stage.v[c] - dt * k2.v[c]);
  }
  return phi;
}

double square_wave(double x) { return (x > 0.25 && x < 0.55) ? 1.0 : 0.0; }
double gaussian(double x) { return std::exp(-std::pow((x - 0.5) / 0.1, 2)); }

double l1_error(const Field2& phi, const std::function<double(double)>& exact) {
  const int n = phi.nx;
  double err = 0.0;
  for (int i = 0; i < n; ++i) {
    // Exact cell average by 8-point midpoint sampling: its error is far below the scheme's.
    double avg = 0.0;
    for (int k = 0; k < 8; ++k) avg += exact((i + (k + 0.5) / 8.0) / n) / 8.0;
    err += std::abs(phi(i, 0) - avg) / n;
  }
  return err;
}

// The cell update is a convex combination for CFL <= 0.5; rounding of that combination is the only
// way past the bounds, hence a few ulps of tolerance.
constexpr double kRounding = 1e-14;

TEST(TvdLimiter, SquareWaveKeepsBoundsForEveryLimiter) {
  for (Limiter lim : {Limiter::Superbee, Limiter::Minmod, Limiter::VanLeer, Limiter::Upwind}) {
    for (double vel : {1.0, -1.0}) {
      const Field2 phi = advect_periodic(lim, 100, vel, 0.45, square_wave);
      const auto [lo, hi] = std::minmax_element(phi.v.begin(), phi.v.end());
      EXPECT_GE(*lo, -kRounding) << "limiter " << static_cast<int>(lim) << " U=" << vel;
      EXPECT_LE(*hi, 1.0 + kRounding) << "limiter " << static_cast<int>(lim) << " U=" << vel;
    }
  }
}

TEST(TvdLimiter, SmoothProfileKeepsBounds) {
  const Field2 phi = advect_periodic(Limiter::Superbee, 100, 1.0, 0.45, gaussian);
  double init_max = 0.0, init_min = 1.0;
  for (int i = 0; i < 100; ++i) {
    init_max = std::max(init_max, gaussian((i + 0.5) / 100));
    init_min = std::min(init_min, gaussian((i + 0.5) / 100));
  }
  const auto [lo, hi] = std::minmax_element(phi.v.begin(), phi.v.end());
  EXPECT_GE(*lo, init_min - kRounding);
  EXPECT_LE(*hi, init_max + kRounding);
}

TEST(TvdLimiter, DirectionOfVelocityIsMirrorSymmetric) {
  // Advecting a profile left must give the mirror image of advecting its mirror image right.
  auto f = [](double x) { return square_wave(x) + 0.5 * gaussian(x + 0.2); };
  auto mirrored = [&](double x) { return f(1.0 - x); };
  const Field2 right = advect_periodic(Limiter::Superbee, 64, 1.0, 0.4, mirrored);
  const Field2 left = advect_periodic(Limiter::Superbee, 64, -1.0, 0.4, f);
  for (int i = 0; i < 64; ++i) EXPECT_NEAR(left(i, 0), right(63 - i, 0), 1e-12) << i;
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
  const Grid2 g = Grid2::uniform(1.0, 1.0 / n, n, 1);
  Field2 u(n + 1, 1, 1.0), v(n, 2, 0.0);
  const FaceVelocity vel{u, v, true};
  Field2 sb(n, 1), up(n, 1);
  for (int i = 0; i < n; ++i) sb(i, 0) = up(i, 0) = square_wave(g.xc(i));
  const double dt = 0.5 * g.dx;
  double mass0 = 0.0;
  for (double x : sb.v) mass0 += x;
  for (int s = 0; s < 100; ++s) {
    sb = advance_scalar_implicit(g, Limiter::Superbee, sb, vel, dt, 3);
    up = advance_scalar_implicit(g, Limiter::Upwind, up, vel, dt, 0);
  }
  double mass = 0.0;
  for (double x : sb.v) mass += x;
  // Conservative final flux evaluation: only rounding (about n * steps * 1e-16) can change the sum.
  EXPECT_NEAR(mass / mass0, 1.0, 1e-12);
  const double peak_sb = *std::max_element(sb.v.begin(), sb.v.end());
  const double peak_up = *std::max_element(up.v.begin(), up.v.end());
  std::printf("implicit after 100 steps: peak superbee %.4f, upwind %.4f, min superbee %.2e\n", peak_sb, peak_up,
              *std::min_element(sb.v.begin(), sb.v.end()));
  // Backward-Euler upwind smears the 30-cell plateau far more than the limited scheme.
  EXPECT_GT(peak_sb, peak_up + 0.05);
}

}  // namespace
}  // namespace fluidbed::tfm
