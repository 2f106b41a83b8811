// Results do not depend on the OpenMP thread count, and a restart from state() continues bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "core/error.hpp"

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

// The same particles handed over in another storage order (as a particle CSV in any row order, or a settled
// bed still in the settler's order) give the same run bit for bit: the solver starts from the canonical order.
TEST(DemDeterminism, StorageOrderAtTheStartDoesNotMatter) {
  const test::ScopedThreads one(1);
  const ParticleStore bed = settle_bed();
  std::vector<std::size_t> order(bed.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::shuffle(order.begin(), order.end(), std::mt19937_64(17));
  ParticleStore shuffled = bed;
  shuffled.permute(order);
  ASSERT_NE(shuffled.id, bed.id);
  constexpr int kShort = 500;
  DemSolver a(settle_config(), bed), b(settle_config(), shuffled);
  for (int n = 0; n < kShort; ++n) {
    a.step();
    b.step();
  }
  expect_identical(a.state(), b.state(), "shuffled vs id order at the start");
}

TEST(DemDeterminism, DuplicateIdsAreBadInput) {
  ParticleStore p;
  const Species s{};
  p.add(3, 0, s, {0.05, 0.01});
  p.add(3, 0, s, {0.02, 0.01});
  EXPECT_THROW(DemSolver(settle_config(), p), Error);
}

// The clock counts whole steps: after n steps it reads n dt with one rounding, not a sum of n roundings.
TEST(DemDeterminism, ClockDoesNotDrift) {
  DemSolver s(settle_config(), ParticleStore{});
  double sum = 0.0;
  for (int n = 0; n < 950; ++n) {
    s.step();
    sum += settle_config().dt;
  }
  EXPECT_EQ(s.time(), 950 * settle_config().dt);
  fmt::print("after 950 steps of 2e-4 s: clock {:.17g}, a running sum would read {:.17g}\n", s.time(), sum);
  // A shortened step lands where it is told, and the clock continues in whole steps from there.
  s.step(1e-4);
  EXPECT_EQ(s.time(), 950 * settle_config().dt + 1e-4);
  const double t0 = s.time();
  for (int n = 0; n < 10; ++n) s.step();
  EXPECT_EQ(s.time(), t0 + 10 * settle_config().dt);
}

}  // namespace
}  // namespace fluidbed
