// 3D: a frictional bed settling in a box gives the same bits on one and two threads, a restart from state()
// continues bit for bit, and the bed settled by settle_bed rests on its walls with its weight (static
// equilibrium: pair forces cancel, so the walls carry N m g).
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "dem/dem_solver.hpp"
#include "dem/packing.hpp"
#include "dem/settle.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

constexpr Vec3 kBox{0.04, 0.2, 0.04};

DemConfig bed_config() {
  return test::one_species_config_3d(0.004, 2700.0, 800.0, 0.9, 0.3, 1e-4, {0.0, -9.81, 0.0}, kBox,
                                     WallConfig{true, true, true, false, false, true, true});
}

ParticleStore<3> falling_bed() {
  ParticleStore<3> p = place_random<3>(bed_config(), test::box_packing(kBox, 1200, 9));
  std::mt19937_64 rng(4);
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < 3; ++a) p.velocity(a)[i] = 0.2 * uniform() - 0.1;
    p.set_spin(i, Vec3{50.0 * uniform() - 25.0, 50.0 * uniform() - 25.0, 50.0 * uniform() - 25.0});
  }
  return p;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expect_identical(const DemSolver<3>::State& a, const DemSolver<3>::State& b, const char* what) {
  std::vector<const void*> dummy;
  std::size_t k = 0;
  a.particles.for_each_array([&](const std::string& name, const auto& u, ArrayRole) {
    std::size_t m = 0;
    b.particles.for_each_array([&](const std::string&, const auto& v, ArrayRole) {
      if constexpr (std::is_same_v<decltype(u), decltype(v)>) {
        if (m == k) {
          EXPECT_TRUE(same_bits(u, v)) << what << ": " << name;
        }
      }
      ++m;
    });
    ++k;
  });
  EXPECT_TRUE(same_bits(a.neighbors.partner, b.neighbors.partner)) << what;
  EXPECT_TRUE(same_bits(a.neighbors.history, b.neighbors.history)) << what;
  EXPECT_EQ(a.steps, b.steps) << what;
}

DemSolver<3>::State run(int threads, int steps) {
  const test::ScopedThreads t(threads);
  DemSolver<3> s(bed_config(), falling_bed());
  for (int n = 0; n < steps; ++n) s.step();
  return s.state();
}

TEST(DemDeterminismIn3D, ThreadsAndRestartAreBitIdentical) {
  constexpr int kSteps = 1500;
  const DemSolver<3>::State one = run(1, kSteps);
  std::size_t loaded = 0;
  for (const Vec3& xi : one.neighbors.history) loaded += norm2(xi) > 0.0 ? 1 : 0;
  fmt::print("3D bed, {} spheres after {} steps: {} list entries, {} loaded springs\n", one.particles.size(), kSteps,
             one.neighbors.entries(), loaded);
  EXPECT_GT(loaded, one.particles.size());
  expect_identical(one, run(2, kSteps), "2 threads vs 1");

  const test::ScopedThreads t(1);
  DemSolver<3> first(bed_config(), falling_bed());
  for (int n = 0; n < kSteps / 2; ++n) first.step();
  DemSolver<3> second(bed_config(), ParticleStore<3>{});
  second.restore(first.state());
  for (int n = 0; n < kSteps - kSteps / 2; ++n) second.step();
  expect_identical(one, second.state(), "restarted vs uninterrupted");
}

// Settled (kinetic energy below 1e-11 J per particle), the bed is in static equilibrium: the contact forces sum
// to minus its weight, all of it carried by the walls. Residual accelerations of a bed at that energy are tiny
// against g; 1% is far above them and far below what a wall or a force term missing from the sum would give.
TEST(DemDeterminismIn3D, SettledBedRestsWithItsWeightOnTheWalls) {
  const test::ScopedThreads t(2);
  DemSolver<3> s(bed_config(), falling_bed());
  const SettleResult r = settle_bed(s, 1e-11, 3.0);
  s.compute_forces();
  const ParticleStore<3>& p = s.particles();
  Vec3 f{};
  double weight = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    f += Vec3{p.fx[i], p.fy[i], p.fz[i]};
    weight += p.mass[i] * 9.81;
  }
  const double h = bed_height<3>(p, kBox.x, 5);
  const double solid_fraction = static_cast<double>(p.size()) * Species{}.volume() / (kBox.x * kBox.z * h);
  fmt::print("settled in {:.3g} s ({} steps, converged {}): contact force ({:.6g}, {:.6g}, {:.6g}) N, weight "
             "{:.6g} N; bed height {:.4g} m, solid fraction {:.3f}\n",
             r.time, r.steps, r.converged, f.x, f.y, f.z, weight, h, solid_fraction);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(std::abs(f.y - weight) / weight, 0.01);
  EXPECT_LE(std::abs(f.x) / weight, 0.01);
  EXPECT_LE(std::abs(f.z) / weight, 0.01);
  // A random packing of monosized spheres against flat walls: between random loose and random close packing.
  EXPECT_GT(solid_fraction, 0.5);
  EXPECT_LT(solid_fraction, 0.66);
}

}  // namespace
}  // namespace fluidbed
