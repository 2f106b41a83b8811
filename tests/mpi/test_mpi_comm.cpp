// MpiComm on 1 to 4 ranks (ctest runs this under mpiexec -n 1..4): sums that give the same bits on every rank
// count, and halo exchanges that fill every ghost inside the domain with the owner's value.
#include <gtest/gtest.h>
#include <mpi.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "core/field.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/exact_sum.hpp"
#include "parallel/mpi_comm.hpp"
#include "mpi_world.hpp"

namespace fluidbed {
namespace {

// The same 50,000 terms on every rank; rank r takes those k with k mod size == r, then the contiguous split.
std::vector<double> all_terms() {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-40, 40);
  std::vector<double> v(50000);
  for (double& x : v) x = std::ldexp(mant(rng), expo(rng));
  return v;
}

TEST(MpiComm, ExactSumIsTheSameBitsOnAnyRankCount) {
  const Comm& c = world();
  const std::vector<double> v = all_terms();
  const double serial = exact_sum(v);
  ExactSum strided, blocked;
  const std::size_t n = v.size(), r = static_cast<std::size_t>(c.rank()), p = static_cast<std::size_t>(c.size());
  for (std::size_t k = r; k < n; k += p) strided.add(v[k]);
  for (std::size_t k = n * r / p; k < n * (r + 1) / p; ++k) blocked.add(v[k]);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(c.sum(strided)), std::bit_cast<std::uint64_t>(serial));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(c.sum(blocked)), std::bit_cast<std::uint64_t>(serial));
  // Equal to the one-process sum on every rank count ctest runs (1-4), so the same bits on all of them; printed for
  // the log. The sum is collective: every rank takes it.
  const double total = c.sum(strided);
  if (c.rank() == 0) std::printf("exact sum of the terms on %d ranks: %.17g\n", c.size(), total);
}

TEST(MpiComm, ReductionsAgreeOnEveryRank) {
  const Comm& c = world();
  const double mine = 1.5 * (c.rank() + 1);
  const int p = c.size();
  EXPECT_EQ(c.sum(mine), 1.5 * p * (p + 1) / 2);
  EXPECT_EQ(c.max(mine), 1.5 * p);
  EXPECT_EQ(c.min(mine), 1.5);
  // Element-wise: exact, and rounded once (p copies of 0.1 summed exactly, not p - 1 roundings).
  std::vector<double> v{1.0 * c.rank(), 1e308, 0.1};
  c.sum(v);
  EXPECT_EQ(v[0], p * (p - 1) / 2.0);
  EXPECT_EQ(v[1], p == 1 ? 1e308 : std::numeric_limits<double>::infinity());
  EXPECT_EQ(v[2], exact_sum(std::vector<double>(static_cast<std::size_t>(p), 0.1)));
}

// A value unique to each global index, so a ghost filled from the wrong cell shows.
template <int Dim>
double tag(const Index<Dim>& c) {
  double v = 0.0;
  for (int a = 0; a < Dim; ++a) v = 1000.0 * v + c[a] + 7;
  return v;
}

template <int Dim>
void check_exchange(const Index<Dim>& n, int ghost, int face_axis) {
  const Comm& c = world();
  IndexBox<Dim> domain{};
  for (int a = 0; a < Dim; ++a) domain.hi[a] = n[a];
  const Index<Dim> blocks = block_counts<Dim>(c.size(), n);
  ASSERT_GT(blocks[0], 0);
  const IndexBox<Dim> owned = block_of<Dim>(domain, blocks, c.rank());
  // A cell field, or the faces normal to face_axis (the shared face planes owned by both neighbours).
  const IndexBox<Dim> box = face_axis < 0 ? owned : owned.faces(face_axis);
  const IndexBox<Dim> whole = face_axis < 0 ? domain : domain.faces(face_axis);
  Field<Dim> f(box, ghost, -1.0);
  for_each(box, [&](const Index<Dim>& i) { f[i] = tag<Dim>(i); });
  c.exchange_halo(f);
  int wrong = 0;
  for_each(f.allocated(), [&](const Index<Dim>& i) {
    const double want = whole.contains(i) ? tag<Dim>(i) : -1.0;  // beyond the domain: left to the boundary conditions
    if (f[i] != want) ++wrong;
  });
  EXPECT_EQ(wrong, 0) << "rank " << c.rank() << " of " << c.size();
}

TEST(MpiComm, HaloExchangeFillsEveryGhostInsideTheDomain) {
  check_exchange<2>({30, 50}, 1, -1);
  check_exchange<2>({30, 50}, 2, -1);
  check_exchange<2>({30, 50}, 1, 0);
  check_exchange<2>({30, 50}, 2, 1);
  check_exchange<3>({8, 12, 6}, 1, -1);
  check_exchange<3>({8, 12, 6}, 2, 2);
}

TEST(MpiComm, MessagesReachTheirRanks) {
  const Comm& c = world();
  const int p = c.size(), me = c.rank();
  // allgather and gather: every rank's bytes in rank order.
  Bytes mine;
  for (int k = 0; k <= me; ++k) pack(mine, static_cast<std::int64_t>(100 * me + k));
  const std::vector<Bytes> all = c.allgather(mine);
  ASSERT_EQ(all.size(), static_cast<std::size_t>(p));
  for (int r = 0; r < p; ++r) {
    Unpacker u(all[static_cast<std::size_t>(r)]);
    for (int k = 0; k <= r; ++k) EXPECT_EQ(u.get<std::int64_t>(), 100 * r + k);
    EXPECT_TRUE(u.done());
  }
  const std::vector<Bytes> at_root = c.gather(mine, 0);
  EXPECT_EQ(at_root.size(), me == 0 ? static_cast<std::size_t>(p) : 0u);
  if (me == 0) {
    EXPECT_EQ(at_root, all);
  }
  // broadcast: the root's bytes everywhere.
  Bytes b;
  if (me == p - 1) pack(b, 3.25);
  c.broadcast(b, p - 1);
  EXPECT_EQ(Unpacker(b).get<double>(), 3.25);
  // An irregular exchange: rank r sends r + 1 values to each rank q > r, nothing to the others.
  std::vector<Bytes> out(static_cast<std::size_t>(p));
  for (int q = me + 1; q < p; ++q) {
    for (int k = 0; k <= me; ++k) pack(out[static_cast<std::size_t>(q)], 1000.0 * me + q + k);
  }
  const std::vector<Bytes> in = c.exchange(out);
  for (int r = 0; r < p; ++r) {
    const Bytes& got = in[static_cast<std::size_t>(r)];
    if (r >= me) {
      EXPECT_TRUE(got.empty()) << "from " << r;
      continue;
    }
    Unpacker u(got);
    for (int k = 0; k <= r; ++k) EXPECT_EQ(u.get<double>(), 1000.0 * r + me + k);
  }
  // A regular exchange with the neighbours on a ring, sizes known to both sides.
  if (p > 1) {
    const int next = (me + 1) % p, prev = (me + p - 1) % p;
    std::vector<int> ranks{next};
    if (prev != next) ranks.push_back(prev);
    std::vector<std::vector<double>> send(ranks.size()), recv(ranks.size());
    for (std::size_t k = 0; k < ranks.size(); ++k) {
      send[k] = {static_cast<double>(me), static_cast<double>(ranks[k])};
      recv[k].resize(2);
    }
    c.exchange_with(ranks, send, recv);
    for (std::size_t k = 0; k < ranks.size(); ++k) {
      EXPECT_EQ(recv[k][0], ranks[k]);
      EXPECT_EQ(recv[k][1], me);
    }
  }
}

TEST(MpiComm, AFailureIsSaidOnceWithTheSmallestKey) {
  const Comm& c = world();
  // No rank failed.
  EXPECT_FALSE(c.first_failure(std::nullopt, 0.0).has_value());
  // Every odd rank fails, keyed by 10 - rank: the highest odd rank's message everywhere.
  const bool fails = c.rank() % 2 == 1;
  const auto m = c.first_failure(fails ? std::optional<std::string>("rank " + std::to_string(c.rank())) : std::nullopt,
                                 10.0 - c.rank());
  if (c.size() == 1) {
    EXPECT_FALSE(m.has_value());
  } else {
    const int want = c.size() % 2 == 0 ? c.size() - 1 : c.size() - 2;
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(*m, "rank " + std::to_string(want));
  }
  // Every rank arrives at a verdict: all of them within the time.
  EXPECT_TRUE(c.all_arrive_within(30.0));
}

}  // namespace
}  // namespace fluidbed
