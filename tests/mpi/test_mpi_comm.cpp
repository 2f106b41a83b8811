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

namespace fluidbed {
namespace {

const MpiComm& world() {
  static const MpiComm comm;
  return comm;
}

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

}  // namespace
}  // namespace fluidbed

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const fluidbed::Comm& c = fluidbed::world();
  if (c.rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int failed = RUN_ALL_TESTS();
  // Every rank's verdict: a failure on any rank fails the run.
  failed = c.max(failed) > 0 ? 1 : 0;
  return failed;
}
