// Rolling resistance (Ai, Chen, Rotter & Ooi 2011, Powder Technol. 206, 269).
// 1. A sphere rolling without slip on a floor, v0 = 0.2 m/s, stops at the distance the model predicts: the
//    rolling torque mu_r R F_n (model A always, model C once its spring has reached the cap, after turning
//    M_m / k_r, here 4e-4 rad) decelerates it about the contact point, I_c = 1.4 m R^2, so a = mu_r g / 1.4 and
//    s = 0.7 v0^2 / (mu_r g). Ai et al.'s Fig. 3 is this test. Tolerance 2%: the tangential spring lets the
//    contact creep by mu_r-sized fractions of its (tiny) elastic range, and the normal spring breathes by
//    O(delta / R) = 1e-4.
// 2. A 2D heap of 325 discs (two sizes, 4 and 5 mm, so that they do not crystallise), built as a 60-degree
//    triangle that is steeper than any repose angle here: its flanks fail and relax, in 1 s, to rest at the angle
//    of repose, which rises with the rolling coefficient (Zhou, Wright, Yang, Xu & Yu 1999, Physica A 269, 536:
//    the angle grows with mu_r). Model C, mu_r = 0, 0.05, 0.2, measured 1.2, 7.6, 18.8 degrees; each angle must
//    exceed the previous by 3 degrees, well above the resolution of the flank fit (columns of 1.25 d).
//    Discs that roll freely (mu_r = 0) spread into a near-flat layer: rolling resistance is what holds a 2D heap.
#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "contact_cases.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.004, kRho = 2700.0, kK = 1e4, kG = 9.81;

template <int Dim>
DemConfig rolling_config(RollingModel model, double mu_r, double dt) {
  DemConfig c = Dim == 3 ? test::one_species_config_3d(kD, kRho, kK, 0.5, 0.5, dt, {0.0, -kG, 0.0}, {0.5, 0.1, 0.1},
                                                       test::closed_box())
                         : test::one_species_config(kD, kRho, kK, 0.5, 0.5, dt, {0.0, -kG}, 0.5, 0.1,
                                                    WallConfig{true, true, true, true});
  c.contact.rolling = model;
  c.pair[0].rolling_friction = mu_r;
  c.wall[0].rolling_friction = mu_r;
  c.skin = 0.0;
  return c;
}

template <int Dim>
double stop_distance(RollingModel model, double mu_r, double v0, double* drift_after) {
  const Species sp{kD, kRho};
  const double m = sp.mass(), r = sp.radius();
  const double dt = contact_duration(m, kK, damping_from_restitution(m, kK, 0.5)) / 50.0;
  const DemConfig c = rolling_config<Dim>(model, mu_r, dt);
  ParticleStore<Dim> p;
  Vec<Dim> x{};
  x[0] = 0.02;
  x[1] = r - m * kG / kK;  // resting on its static overlap
  if constexpr (Dim == 3) x[2] = 0.05;
  Vec<Dim> v{};
  v[0] = v0;
  Spin<Dim> w{};
  if constexpr (Dim == 2) {
    w = -v0 / r;
  } else {
    w.z = -v0 / r;
  }
  p.add(0, 0, sp, x, v, w);
  DemSolver<Dim> s(c, std::move(p));
  const auto& q = s.particles();
  for (long k = 0; k < 10000000; ++k) {
    s.step();
    if (q.vx[0] <= 0.0) break;
  }
  const double dist = q.x[0] - x[0];
  const double x_stop = q.x[0];
  for (int k = 0; k < static_cast<int>(0.2 / dt); ++k) s.step();
  *drift_after = std::abs(q.x[0] - x_stop);
  return dist;
}

template <int Dim>
void rolling_stops() {
  const double v0 = 0.2;
  test::Table t(fmt::format("Sphere rolling on a floor, {}D, v0 = {} m/s: stop distance exact vs computed", Dim, v0),
                {"model", "mu_r", "s exact m", "s comp. m", "err", "drift 0.2 s"});
  for (RollingModel model : {RollingModel::Constant, RollingModel::Epsd}) {
    for (double mu_r : {0.05, 0.1}) {
      double drift = 0.0;
      const double s = stop_distance<Dim>(model, mu_r, v0, &drift);
      const double exact = 0.7 * v0 * v0 / (mu_r * kG);
      t.row({model == RollingModel::Epsd ? 3.0 : 1.0, mu_r, exact, s, test::rel_err(s, exact), drift});
      EXPECT_LE(test::rel_err(s, exact), 0.02) << to_string(model) << " " << mu_r;
      // Model C holds the sphere still (its spring); model A leaves it rocking by tiny amounts about rest.
      if (model == RollingModel::Epsd) {
        EXPECT_LE(drift, 1e-4 * exact) << mu_r;
      }
    }
  }
}

TEST(RollingResistance, SphereRollingOnAPlaneStopsAtThePredictedDistance) {
  const test::ScopedThreads one_thread(1);
  rolling_stops<3>();
  rolling_stops<2>();
}

/// Angle of repose (degrees) of a 2D heap: the mean slope of a line fitted to the top of each flank, between
/// 25% and 75% of the heap's height, the top found per column of width d.
double repose_angle(const ParticleStore<2>& p, double x_c) {
  const double d = kD * 1.25;
  std::vector<double> top(400, 0.0);
  double h = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto b = static_cast<std::size_t>(p.x[i] / d);
    top[b] = std::max(top[b], p.y[i] + p.radius[i]);
    h = std::max(h, p.y[i] + p.radius[i]);
  }
  double slope_sum = 0.0;
  for (int side : {-1, 1}) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (std::size_t b = 0; b < top.size(); ++b) {
      const double xb = (static_cast<double>(b) + 0.5) * d;
      if ((xb - x_c) * side <= 0.0 || top[b] < 0.25 * h || top[b] > 0.75 * h) continue;
      sx += xb;
      sy += top[b];
      sxx += xb * xb;
      sxy += xb * top[b];
      ++n;
    }
    if (n < 2) return std::nan("");
    slope_sum += std::abs((n * sxy - sx * sy) / (n * sxx - sx * sx));
  }
  return std::atan(0.5 * slope_sum) * 180.0 / std::numbers::pi;
}

double heap_angle(double mu_r) {
  const double width = 0.3, height = 0.2;
  DemConfig c = test::one_species_config(kD, kRho, 1000.0, 0.3, 0.5, 3e-5, {0.0, -kG}, width, height,
                                         WallConfig{true, true, true, true});
  c.species = {Species{kD, kRho}, Species{1.25 * kD, kRho}};
  c.pair.assign(4, InteractionParams{0.3, 0.5, mu_r});
  c.wall.assign(2, InteractionParams{0.3, 0.5, mu_r});
  c.contact.rolling = RollingModel::Epsd;
  c.skin = 0.25 * kD;
  // A 60-degree triangle (steeper than any repose angle here) on a lattice of pitch 1.15 d_max, jittered, sizes
  // drawn at random: its flanks fail and relax to the angle of repose.
  ParticleStore<2> p;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double pitch = 1.15 * 1.25 * kD, base = 0.15;
  const double slope = std::tan(std::numbers::pi / 3.0);
  int id = 0;
  for (int row = 0;; ++row) {
    const double y = 0.5 * pitch + row * pitch * 0.8660254;
    const double half = 0.5 * base - y / slope;
    if (half < 0.5 * pitch) break;
    for (double x = 0.5 * width - half + 0.5 * pitch + (row % 2) * 0.5 * pitch; x <= 0.5 * width + half - 0.5 * pitch;
         x += pitch) {
      const int sp = static_cast<int>(rng() % 2);
      p.add(id++, sp, c.species[static_cast<std::size_t>(sp)], {x + 0.05 * kD * u(rng), y}, {});
    }
  }
  DemSolver<2> s(c, std::move(p));
  for (int k = 0; k < static_cast<int>(1.0 / c.dt); ++k) s.step();
  fmt::print("  heap of {} discs, mu_r = {}: kinetic energy at the end {:.3g} J\n", s.particles().size(), mu_r,
             s.kinetic_energy());
  return repose_angle(s.particles(), 0.5 * width);
}

TEST(RollingResistance, HeapAngleOfReposeRisesWithTheRollingCoefficient) {
  const test::ScopedThreads one_thread(1);
  test::Table t("2D heap of 300 discs after the collapse of a column (elastic-plastic rolling, Ai et al. 2011)",
                {"mu_r", "angle deg"});
  double prev = -1e9;
  for (double mu_r : {0.0, 0.05, 0.2}) {
    const double a = heap_angle(mu_r);
    t.row({mu_r, a});
    EXPECT_GT(a, prev + 3.0) << mu_r;
    prev = a;
  }
}

}  // namespace
}  // namespace fluidbed
