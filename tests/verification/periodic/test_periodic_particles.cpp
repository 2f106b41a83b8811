// Periodic axes for particles: the neighbour search through periodic images equals the brute-force minimum-image
// search; a pair colliding across the periodic side exchanges its velocities as a pair inside the box does; a
// periodic box of elastic, frictionless particles conserves its momentum along the periodic axes to round-off and
// its energy to the integrator's error. Tolerances: momentum is a sum of pair forces that cancel bit for bit (the
// force loop writes -f to the partner), so only the summation of the final momentum rounds, ~1e-15 of the sum of
// |m v|; energy as tests/verification/dem/test_energy_box.cpp (0.5%, from the symplectic Euler's O(omega dt)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "dem/dem_solver.hpp"
#include "dem/neighbor_list.hpp"
#include "dem/packing.hpp"
#include "../dem/dem_closed_form.hpp"

namespace fluidbed {
namespace {

template <int Dim>
ParticleStore<Dim> random_cloud(std::size_t n, Vec<Dim> box, const std::vector<double>& d, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  ParticleStore<Dim> p;
  for (std::size_t i = 0; i < n; ++i) {
    const auto s = static_cast<std::size_t>(uniform() * static_cast<double>(d.size())) % d.size();
    Vec<Dim> x;
    for (int a = 0; a < Dim; ++a) x[a] = box[a] * uniform();
    // A few exactly on the low side and just below the period: the edges of the image shells.
    if (i % 97 == 0) x[0] = 0.0;
    if (i % 89 == 0) x[0] = std::nextafter(box[0], 0.0);
    p.add(static_cast<std::int64_t>(i) * 7 + 3, static_cast<std::int32_t>(s), Species{d[s], 2700.0}, x);
  }
  return p;
}

template <int Dim>
std::vector<std::pair<std::int64_t, std::int64_t>> list_pairs(const ParticleStore<Dim>& p, const NeighborList<Dim>& l) {
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t k = l.offset[i]; k < l.offset[i + 1]; ++k) {
      const std::int64_t a = p.id[i], b = p.id[l.partner[k]];
      if (a < b) pairs.emplace_back(a, b);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

template <int Dim>
void expect_images_equal_brute_force(const char* name, const ParticleStore<Dim>& p, const PeriodicBox<Dim>& box,
                                     double cell, double skin) {
  NeighborList<Dim> l;
  NeighborScratch scratch;
  build_neighbor_list(p, cell, skin, l, scratch, box);
  const auto got = list_pairs(p, l);
  const auto want = brute_force_contacts(p, skin, box);
  const auto closed = brute_force_contacts(p, skin);
  // Every pair in both partners' lists exactly once (each pair counted from its lower id above).
  EXPECT_EQ(l.entries(), 2 * got.size()) << name;
  fmt::print("{:<28} {:>6} particles: brute force {:>6} pairs ({:>5} across a periodic side), list {:>6}\n", name,
             p.size(), want.size(), want.size() - closed.size(), got.size());
  EXPECT_EQ(got, want) << name;
  EXPECT_GT(want.size(), closed.size()) << name << ": the cloud should have pairs across the periodic side";
}

TEST(PeriodicNeighbors, ImageSearchEqualsBruteForce2D) {
  const std::vector<double> mono{0.004}, poly{0.002, 0.0035, 0.006};
  PeriodicBox<2> box;
  box.on = {true, false};
  box.length = {0.05, 0.08};
  expect_images_equal_brute_force("2D dense mono, x periodic", random_cloud<2>(600, box.length, mono, 1), box,
                                  0.0044, 4e-4);
  expect_images_equal_brute_force("2D dense poly, x periodic", random_cloud<2>(800, box.length, poly, 2), box,
                                  0.0065, 5e-4);
  PeriodicBox<2> wide = box;
  wide.length = {0.02, 0.3};  // a period of three cells: the images of one side reach the other's neighbours
  expect_images_equal_brute_force("2D narrow period", random_cloud<2>(500, wide.length, mono, 3), wide, 0.0044, 4e-4);
}

TEST(PeriodicNeighbors, ImageSearchEqualsBruteForce3D) {
  const std::vector<double> poly{0.002, 0.0035, 0.006};
  PeriodicBox<3> box;
  box.on = {true, false, true};
  box.length = {0.04, 0.05, 0.03};
  expect_images_equal_brute_force("3D poly, x and z periodic", random_cloud<3>(1500, box.length, poly, 4), box,
                                  0.0065, 5e-4);
  box.on = {false, false, true};
  expect_images_equal_brute_force("3D poly, z periodic", random_cloud<3>(1500, box.length, poly, 5), box, 0.0065, 5e-4);
}

DemConfig periodic_x_config(double W, double H, double e, double mu, double dt) {
  DemConfig c = test::one_species_config(0.004, 2700.0, 800.0, e, mu, dt, {0.0, 0.0}, W, H,
                                         WallConfig{true, true, true, true});
  c.domain.periodic = {true, false, false};
  c.skin = 4e-4;
  return c;
}

// A sphere moving left crosses x = 0, re-enters at x = W and hits a resting equal sphere there from its right,
// head-on. Elastic and frictionless, they exchange their velocities (the closed form of a central elastic impact
// of equal masses): the mover stops, the other leaves at -v0. The linear spring integrated at 50 steps per contact
// keeps the restitution to ~(pi/50)^2 / 2 ~ 2e-3 of 1 (test_restitution measures 2e-5), the bound used here.
TEST(PeriodicParticles, PairCollidingAcrossTheBoundaryExchangesVelocities) {
  const test::ScopedThreads one(1);
  const double W = 0.05, H = 0.05, v0 = 0.3;
  const Species sp{0.004, 2700.0};
  const double dt = contact_duration(reduced_mass(sp.mass(), sp.mass()), 800.0, 0.0) / 50.0;
  DemConfig c = periodic_x_config(W, H, 1.0, 0.0, dt);
  ParticleStore<2> p;
  p.add(1, 0, sp, {0.01, 0.02}, {-v0, 0.0});  // out through x = 0, touching particle 2 at x = -0.002 = W - 0.002
  p.add(2, 0, sp, {W - 0.006, 0.02}, {0.0, 0.0});
  DemSolver<2> s(c, std::move(p));
  const double m = sp.mass();
  double worst_p = 0.0, max_ov = 0.0;
  bool wrapped = false;
  const int steps = static_cast<int>(std::ceil(0.06 / dt));
  for (int n = 0; n < steps; ++n) {
    s.step();
    const ParticleStore<2>& q = s.particles();
    worst_p = std::max(worst_p, std::abs(m * (q.vx[0] + q.vx[1]) - m * -v0) + std::abs(m * (q.vy[0] + q.vy[1])));
    max_ov = std::max(max_ov, s.max_overlap());
    for (std::size_t i = 0; i < 2; ++i) {
      ASSERT_GE(q.x[i], 0.0);
      ASSERT_LT(q.x[i], W);
      if (q.id[i] == 1 && q.x[i] > 0.5 * W) wrapped = true;
    }
  }
  const ParticleStore<2>& q = s.particles();
  const std::size_t i1 = q.id[0] == 1 ? 0 : 1, i2 = 1 - i1;
  test::Table t("Elastic impact across the periodic side x = 0 = W (velocities over v0)",
                {"exact", "computed", "error"});
  t.row({0.0, q.vx[i1] / v0, q.vx[i1] / v0});
  t.row({-1.0, q.vx[i2] / v0, q.vx[i2] / v0 + 1.0});
  fmt::print("largest |total momentum - m (-v0)| over the run: {:.3g} kg m/s (|m v0| = {:.3g}); largest overlap "
             "{:.3g} m; particle 1 at x = {:.6g} m\n", worst_p, m * v0, max_ov, q.x[i1]);
  EXPECT_TRUE(wrapped) << "particle 1 should have crossed x = 0 and come back at x near W";
  EXPECT_GT(max_ov, 1e-5) << "the pair should have touched across the boundary";
  EXPECT_LE(std::abs(q.vx[i1] / v0), 2e-3);
  EXPECT_LE(std::abs(q.vx[i2] / v0 + 1.0), 2e-3);
  EXPECT_LE(worst_p, 4e-16 * m * v0);
}

/// Spring energy with minimum-image pair separations and the walls of the non-periodic axis y.
template <int Dim>
double spring_energy(const ParticleStore<Dim>& p, double k, const PeriodicBox<Dim>& box, double height) {
  double e = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double d = norm(box.min_image(p.pos(j) - p.pos(i)));
      const double ov = p.radius[i] + p.radius[j] - d;
      if (ov > 0.0) e += 0.5 * k * ov * ov;
    }
    for (double ov : {p.radius[i] - p.y[i], p.radius[i] - (height - p.y[i])}) {
      if (ov > 0.0) e += 0.5 * k * ov * ov;
    }
  }
  return e;
}

template <int Dim>
void run_elastic_periodic_box(Vec<Dim> L, std::size_t count, int steps) {
  const test::ScopedThreads two(2);
  const double k = 800.0;
  const Species sp{0.004, 2700.0};
  const double dt = contact_duration(reduced_mass(sp.mass(), sp.mass()), k, 0.0) / 50.0;
  DemConfig c = periodic_x_config(L[0], L[1], 1.0, 0.0, dt);
  if constexpr (Dim == 3) {
    c.domain.dimension = 3;
    c.domain.depth = L[2];
    c.domain.periodic = {true, false, true};
  }
  PackingConfig pc;
  pc.count = static_cast<std::int64_t>(count);
  pc.x_max = L[0];
  pc.y_max = L[1];
  if constexpr (Dim == 3) pc.z_max = L[2];
  pc.min_gap = 0.001;
  pc.seed = 17;
  ParticleStore<Dim> p = place_random<Dim>(c, pc);
  std::mt19937_64 rng(23);
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  for (std::size_t i = 0; i < p.size(); ++i) {
    // A drift along x (and z) on top of the random motion: the momentum the periodic axes must keep.
    for (int a = 0; a < Dim; ++a) p.velocity(a)[i] = 2.0 * uniform() - 1.0 + (a != 1 ? 0.3 : 0.0);
  }
  DemSolver<Dim> s(c, std::move(p));
  const PeriodicBox<Dim> box = s.periodic();
  auto momentum = [&](int a) {
    double m = 0.0;
    for (std::size_t i = 0; i < s.particles().size(); ++i) m += s.particles().mass[i] * s.particles().velocity(a)[i];
    return m;
  };
  auto abs_momentum = [&]() {
    double m = 0.0;
    for (std::size_t i = 0; i < s.particles().size(); ++i) m += s.particles().mass[i] * norm(s.particles().vel(i));
    return m;
  };
  const double e0 = s.kinetic_energy() + spring_energy(s.particles(), k, box, L[1]);
  std::vector<double> p0;
  for (int a = 0; a < Dim; ++a) p0.push_back(momentum(a));
  const double scale = abs_momentum();
  test::Table t(fmt::format("Elastic frictionless particles, {}D, periodic x{}, walls at y = 0 and H", Dim,
                            Dim == 3 ? " and z" : ""),
                {"step", "E rel change", "P_x exact", "P_x computed", "P_x error"});
  double worst_e = 0.0, worst_p = 0.0;
  std::uint64_t crossings = 0;
  std::vector<double> last_x = s.particles().x;
  for (int n = 1; n <= steps; ++n) {
    s.step();
    for (std::size_t i = 0; i < last_x.size(); ++i) {
      if (std::abs(s.particles().x[i] - last_x[i]) > 0.5 * L[0]) ++crossings;  // same storage order between steps
    }
    last_x = s.particles().x;
    if (n % 100 == 0) {
      const double e = s.kinetic_energy() + spring_energy(s.particles(), k, box, L[1]);
      worst_e = std::max(worst_e, std::abs(e - e0) / e0);
      for (int a = 0; a < Dim; ++a) {
        if (a == 1) continue;
        worst_p = std::max(worst_p, std::abs(momentum(a) - p0[static_cast<std::size_t>(a)]));
      }
      if (n % (steps / 5) == 0) t.row({double(n), (e - e0) / e0, p0[0], momentum(0), momentum(0) - p0[0]});
    }
  }
  fmt::print("{} crossings of x = 0 = W; max |E - E0| / E0 {:.3g}; max |P - P0| along periodic axes {:.3g} "
             "(sum |m v| = {:.3g})\n", crossings, worst_e, worst_p, scale);
  EXPECT_GT(crossings, 10u);
  EXPECT_LE(worst_e, 0.005);
  // Pair forces cancel exactly; the momentum sum itself rounds at ~N eps of sum |m v|.
  EXPECT_LE(worst_p, 1e-13 * scale);
}

TEST(PeriodicParticles, ElasticPeriodicBoxConservesMomentumAndEnergy2D) {
  run_elastic_periodic_box<2>({0.1, 0.1}, 200, 4000);
}

TEST(PeriodicParticles, ElasticPeriodicBoxConservesMomentumAndEnergy3D) {
  run_elastic_periodic_box<3>({0.04, 0.04, 0.04}, 180, 2000);
}

// A periodic run does not depend on the thread count (the image search and the force loops keep their order).
TEST(PeriodicParticles, ThreadCountIndependent) {
  auto run = [](int threads) {
    const test::ScopedThreads t(threads);
    DemConfig c = periodic_x_config(0.06, 0.1, 0.9, 0.3, 1e-4);
    c.domain.gravity = {0.0, -9.81, 0.0};
    PackingConfig pc;
    pc.count = 200;
    pc.x_max = 0.06;
    pc.y_max = 0.1;
    pc.min_gap = 0.0005;
    pc.seed = 5;
    ParticleStore<2> p = place_random<2>(c, pc);
    for (std::size_t i = 0; i < p.size(); ++i) p.vx[i] = 0.5;
    DemSolver<2> s(c, std::move(p));
    for (int n = 0; n < 1500; ++n) s.step();
    return s.state();
  };
  const auto a = run(1), b = run(3);
  ASSERT_EQ(a.particles.size(), b.particles.size());
  EXPECT_EQ(a.particles.x, b.particles.x);
  EXPECT_EQ(a.particles.vx, b.particles.vx);
  EXPECT_EQ(a.particles.omega, b.particles.omega);
}

}  // namespace
}  // namespace fluidbed
