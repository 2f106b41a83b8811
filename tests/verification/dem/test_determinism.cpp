// Results do not depend on the OpenMP thread count, and a restart from state() continues bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <type_traits>
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

ParticleStore<2> settle_bed() {
  const DemConfig c = settle_config();
  PackingConfig pc;
  pc.count = 2000;
  pc.x_max = 0.1;
  pc.y_max = 0.42;
  pc.seed = 3;
  ParticleStore<2> p = place_random<2>(c, pc);
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

/// Bit-for-bit equality of two solver states (every particle attribute in storage order, the neighbour list and
/// the wall springs).
void expect_identical(const DemSolver<2>::State& a, const DemSolver<2>::State& b, const char* what) {
  std::vector<std::string> names;
  a.particles.for_each_array([&](const std::string& name, const auto&, ArrayRole) { names.push_back(name); });
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
  EXPECT_EQ(names.size(), k);
  EXPECT_TRUE(same_bits(a.neighbors.offset, b.neighbors.offset)) << what;
  EXPECT_TRUE(same_bits(a.neighbors.partner, b.neighbors.partner)) << what;
  EXPECT_TRUE(same_bits(a.neighbors.history, b.neighbors.history)) << what;
  ASSERT_EQ(a.walls.size(), b.walls.size()) << what;
  std::size_t wall_diffs = 0;
  for (std::size_t i = 0; i < a.walls.size(); ++i)
    for (int w = 0; w < 4; ++w) wall_diffs += same_bits(std::vector<Vec2>{a.walls.get(i, w)}, std::vector<Vec2>{b.walls.get(i, w)}) ? 0 : 1;
  EXPECT_EQ(wall_diffs, 0u) << what << ": wall springs";
  EXPECT_EQ(a.time, b.time) << what;
  EXPECT_EQ(a.steps, b.steps) << what;
}

DemSolver<2>::State run(int threads, int steps) {
  const test::ScopedThreads t(threads);
  EXPECT_EQ(omp_get_max_threads(), threads);
  DemSolver<2> s(settle_config(), settle_bed());
  for (int n = 0; n < steps; ++n) s.step();
  return s.state();
}

constexpr int kSteps = 2000;

// One and two threads (the machine's cores); more threads than cores would only make each step's barriers
// wait for time slices.
TEST(DemDeterminism, BitIdenticalOnOneAndTwoThreads) {
  const DemSolver<2>::State one = run(1, kSteps);
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
  DemSolver<2> whole(settle_config(), settle_bed());
  for (int n = 0; n < kSteps; ++n) whole.step();

  DemSolver<2> first(settle_config(), settle_bed());
  for (int n = 0; n < kSteps / 2; ++n) first.step();
  DemSolver<2> second(settle_config(), ParticleStore<2>{});
  second.restore(first.state());
  for (int n = 0; n < kSteps / 2; ++n) second.step();
  expect_identical(whole.state(), second.state(), "restarted vs uninterrupted");
  EXPECT_EQ(whole.rebuild_count(), second.rebuild_count());
}

// The same particles handed over in another storage order (as a particle CSV in any row order, or a settled
// bed still in the settler's order) give the same run bit for bit: the solver starts from the canonical order.
TEST(DemDeterminism, StorageOrderAtTheStartDoesNotMatter) {
  const test::ScopedThreads one(1);
  const ParticleStore<2> bed = settle_bed();
  std::vector<std::size_t> order(bed.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::shuffle(order.begin(), order.end(), std::mt19937_64(17));
  ParticleStore<2> shuffled = bed;
  shuffled.permute(order);
  ASSERT_NE(shuffled.id, bed.id);
  constexpr int kShort = 500;
  DemSolver<2> a(settle_config(), bed), b(settle_config(), shuffled);
  for (int n = 0; n < kShort; ++n) {
    a.step();
    b.step();
  }
  expect_identical(a.state(), b.state(), "shuffled vs id order at the start");
}

/// The state with its particles stored in another order: every attribute and the build positions permuted, the
/// list rows moved with their particles and each entry's partner slot found again by the partner's id (what a
/// particle migrating between ranks will carry: its entries keyed by ids).
DemSolver<2>::State permuted(const DemSolver<2>::State& s, const std::vector<std::size_t>& order) {
  DemSolver<2>::State out = s;
  out.particles.permute(order);
  out.walls.permute(order);
  for (std::size_t a = 0; a < 2; ++a) {
    for (std::size_t k = 0; k < order.size(); ++k) out.build[a][k] = s.build[a][order[k]];
  }
  std::vector<std::size_t> slot_of_id(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) slot_of_id[static_cast<std::size_t>(out.particles.id[k])] = k;
  const NeighborList<2>& in = s.neighbors;
  NeighborList<2>& nl = out.neighbors;
  nl.offset.assign(1, 0);
  nl.partner.clear();
  nl.history.clear();
  for (std::size_t k = 0; k < order.size(); ++k) {
    for (std::size_t q = in.offset[order[k]]; q < in.offset[order[k] + 1]; ++q) {
      const auto partner_id = static_cast<std::size_t>(s.particles.id[in.partner[q]]);
      nl.partner.push_back(static_cast<std::uint32_t>(slot_of_id[partner_id]));
      nl.history.push_back(in.history[q]);
    }
    nl.offset.push_back(nl.partner.size());
  }
  return out;
}

/// Springs by (particle id, partner id), and the wall springs by particle id: what must not depend on storage.
std::map<std::pair<std::int64_t, std::int64_t>, Vec2> springs_by_id(const DemSolver<2>::State& s) {
  std::map<std::pair<std::int64_t, std::int64_t>, Vec2> m;
  const ParticleStore<2>& p = s.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t k = s.neighbors.offset[i]; k < s.neighbors.offset[i + 1]; ++k) {
      if (norm2(s.neighbors.history[k]) > 0.0) m[{p.id[i], p.id[s.neighbors.partner[k]]}] = s.neighbors.history[k];
    }
    for (int w = 0; w < 4; ++w) {
      if (norm2(s.walls.get(i, w)) > 0.0) m[{p.id[i], -1 - w}] = s.walls.get(i, w);
    }
  }
  return m;
}

// The contact history is keyed by particle ids: a settled bed whose store is shuffled mid-run (list rows and
// wall springs moving with their particles) carries every loaded spring through the next rebuild and re-sort to
// the same pair, bit for bit, and the steps until that rebuild are bit-identical too (each particle sums the
// same entries in the same order, and each pair is evaluated with the antisymmetric law from either side).
TEST(DemDeterminism, ContactHistoryIsKeyedByIdsNotStorageSlots) {
  const test::ScopedThreads one(1);
  DemSolver<2> a(settle_config(), settle_bed());
  for (int n = 0; n < kSteps; ++n) a.step();
  const DemSolver<2>::State s = a.state();
  std::vector<std::size_t> order(s.particles.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::shuffle(order.begin(), order.end(), std::mt19937_64(23));
  DemSolver<2> b(settle_config(), ParticleStore<2>{});
  b.restore(permuted(s, order));
  // Until the next rebuild: the same run, in another storage order.
  int before = 0;
  while (a.rebuild_count() == s.rebuilds && before < 1000) {
    a.step();
    b.step();
    ++before;
  }
  ASSERT_EQ(a.rebuild_count(), b.rebuild_count());
  // The step that rebuilt the list evaluated it once, so the springs it carried over are compared after it.
  const auto sa = springs_by_id(a.state()), sb = springs_by_id(b.state());
  std::size_t same = 0;
  for (const auto& [key, xi] : sa) {
    const auto it = sb.find(key);
    if (it != sb.end() && it->second == xi) ++same;
  }
  fmt::print("storage shuffled after {} steps; {} steps to the next rebuild; {} loaded springs (pairs and walls), "
             "{} carried to the same ids bit for bit\n",
             kSteps, before, sa.size(), same);
  EXPECT_GT(before, 0);
  EXPECT_GT(sa.size(), s.particles.size());
  EXPECT_EQ(sa.size(), sb.size());
  EXPECT_EQ(same, sa.size());
}

TEST(DemDeterminism, DuplicateIdsAreBadInput) {
  ParticleStore<2> p;
  const Species s{};
  p.add(3, 0, s, {0.05, 0.01});
  p.add(3, 0, s, {0.02, 0.01});
  EXPECT_THROW(DemSolver<2>(settle_config(), p), Error);
}

// The clock counts whole steps: after n steps it reads n dt with one rounding, not a sum of n roundings.
TEST(DemDeterminism, ClockDoesNotDrift) {
  DemSolver<2> s(settle_config(), ParticleStore<2>{});
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
