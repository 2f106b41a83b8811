// Results do not depend on the OpenMP thread count, and a restart from state() continues bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "dem/dem_solver.hpp"
#include "dem/packing.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

/// 2000 of the paper's particles (Table 1) settling under gravity at the paper's dt in a 0.1 m wide box.
DemConfig settle_config() {
  return test::one_species_config(0.004, 2700.0, 800.0, 0.9, 0.3, 2e-4, {0.0, -9.81}, 0.1, 1.0, WallConfig{});
}

ParticleStore settle_bed() {
  const DemConfig c = settle_config();
  PackingConfig pc;
  pc.count = 2000;
  pc.x_max = 0.1;
  pc.y_max = 0.42;
  pc.seed = 3;
  ParticleStore p = place_random(c, pc);
  std::mt19937_64 rng(5);
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.vx[i] = 0.2 * uniform() - 0.1;
    p.vy[i] = 0.2 * uniform() - 0.1;
  }
  return p;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// Bit-for-bit equality of two solver states (particles in storage order, neighbour list, wall springs).
void expect_identical(const DemSolver::State& a, const DemSolver::State& b, const char* what) {
  const ParticleStore &p = a.particles, &q = b.particles;
  EXPECT_TRUE(same_bits(p.id, q.id)) << what;
  for (auto [u, v, name] : {std::tuple{&p.x, &q.x, "x"}, std::tuple{&p.y, &q.y, "y"}, std::tuple{&p.vx, &q.vx, "vx"},
                            std::tuple{&p.vy, &q.vy, "vy"}, std::tuple{&p.omega, &q.omega, "omega"},
                            std::tuple{&p.fx, &q.fx, "fx"}, std::tuple{&p.fy, &q.fy, "fy"},
                            std::tuple{&p.torque, &q.torque, "torque"}}) {
    EXPECT_TRUE(same_bits(*u, *v)) << what << ": " << name;
  }
  EXPECT_TRUE(same_bits(a.neighbors.offset, b.neighbors.offset)) << what;
  EXPECT_TRUE(same_bits(a.neighbors.partner, b.neighbors.partner)) << what;
  EXPECT_TRUE(same_bits(a.neighbors.history, b.neighbors.history)) << what;
  EXPECT_TRUE(same_bits(a.wall_xi, b.wall_xi)) << what;
  EXPECT_EQ(a.time, b.time) << what;
  EXPECT_EQ(a.steps, b.steps) << what;
}

DemSolver::State run(int threads, int steps) {
  const test::ScopedThreads t(threads);
  EXPECT_EQ(omp_get_max_threads(), threads);
  DemSolver s(settle_config(), settle_bed());
  for (int n = 0; n < steps; ++n) s.step();
  return s.state();
}

constexpr int kSteps = 2000;

// One and two threads (the machine's cores); more threads than cores would only make each step's barriers
// wait for time slices.
TEST(DemDeterminism, BitIdenticalOnOneAndTwoThreads) {
  const DemSolver::State one = run(1, kSteps);
  // A dense, settled bed with many contacts and sticking springs: the case where order matters most.
  std::size_t loaded = 0;
  for (const Vec2& xi : one.neighbors.history) loaded += norm2(xi) > 0.0 ? 1 : 0;
  fmt::print("after {} steps: {} neighbour entries, {} with a loaded tangential spring\n", kSteps,
             one.neighbors.partner.size(), loaded);
  EXPECT_GT(loaded, one.particles.size());
  expect_identical(one, run(2, kSteps), "2 threads vs 1");
}

// One thread: thread-count independence is the test above; this one isolates the restart.
TEST(DemDeterminism, RestartFromStateContinuesBitForBit) {
  const test::ScopedThreads one(1);
  DemSolver whole(settle_config(), settle_bed());
  for (int n = 0; n < kSteps; ++n) whole.step();

  DemSolver first(settle_config(), settle_bed());
  for (int n = 0; n < kSteps / 2; ++n) first.step();
  DemSolver second(settle_config(), ParticleStore{});
  second.restore(first.state());
  for (int n = 0; n < kSteps / 2; ++n) second.step();
  expect_identical(whole.state(), second.state(), "restarted vs uninterrupted");
  EXPECT_EQ(whole.rebuild_count(), second.rebuild_count());
}

}  // namespace
}  // namespace fluidbed
