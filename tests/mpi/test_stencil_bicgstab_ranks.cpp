// StencilBicgstab on 1 to 4 ranks (ctest runs this under mpiexec -n 1..4) against the same solver on one process,
// bit for bit: the answer, the iteration count and the residual estimate, in 2D and 3D, walled and periodic, cut
// along y and along z, warm-started, and through the LU fallback; a non-finite row is named alike on every rank.
// Each rank also solves the one-process reference itself (the problems are small).
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "numerics/stencil_bicgstab.hpp"
#include "parallel/decomposition.hpp"
#include "mpi_world.hpp"

namespace fluidbed {
namespace {

// A value in [e^-1, e^1] from the global cell and a salt.
template <int Dim>
double value(const Index<Dim>& c, int salt) {
  double phase = 0.41 * salt;
  for (int a = 0; a < Dim; ++a) phase += (0.33 + 0.17 * a) * c[a] + 0.011 * c[a] * c[a];
  return std::exp(std::sin(phase));
}

// A nonsymmetric transport-like operator (1/dt + outflows on the diagonal, inflows off it) on grid's owned rows.
template <int Dim>
void fill(const Grid<Dim>& g, StencilBicgstab<Dim>& s, std::vector<double>& b, double scale) {
  b.clear();
  int r = 0;
  for_each(g.owned, [&](const Index<Dim>& c) {
    std::array<double, 2 * Dim> off{};
    double diag = 0.5;  // weakly dominant: a few tens of iterations
    for (int a = 0; a < Dim; ++a)
      for (int side = 0; side < 2; ++side) {
        Index<Dim> nb = c;
        nb[a] += side ? 1 : -1;
        if (!g.periodic[static_cast<std::size_t>(a)] && (nb[a] < g.domain.lo[a] || nb[a] >= g.domain.hi[a])) continue;
        const double w = value<Dim>(c, 2 * a + side);
        off[static_cast<std::size_t>(2 * a + side)] = -w;
        diag += w * (side ? 0.8 : 1.2);
      }
    s.set_row(r++, diag, off);
    b.push_back(scale * (value<Dim>(c, 11) - 1.1));
  });
}

template <int Dim>
std::vector<std::uint64_t> gathered_bits(const Grid<Dim>& whole, const IndexBox<Dim>& mine, const std::vector<double>& x) {
  Field<Dim> all(whole.domain, 0);
  Bytes out;
  pack(out, mine);
  for (double v : x) pack(out, v);
  for (const Bytes& from : world().allgather(out)) {
    Unpacker in(from);
    const auto box = in.get<IndexBox<Dim>>();
    for_each(box, [&](const Index<Dim>& c) { all[c] = in.get<double>(); });
  }
  std::vector<std::uint64_t> bits;
  for (double v : all.data()) bits.push_back(std::bit_cast<std::uint64_t>(v));
  return bits;
}

template <int Dim>
void check(const Index<Dim>& n, int periodic_axis, const Index<Dim>& blocks, int max_iterations = 0) {
  Vec<Dim> ext{};
  for (int a = 0; a < Dim; ++a) ext[a] = 0.1 * n[a];
  Grid<Dim> whole = Grid<Dim>::uniform(ext, n, 1);
  if (periodic_axis >= 0) whole.periodic[static_cast<std::size_t>(periodic_axis)] = true;
  Grid<Dim> part = whole;
  part.owned = block_of<Dim>(whole.domain, blocks, world().rank());
  StencilBicgstab<Dim> one(whole, serial_comm()), many(part, world());
  for (StencilBicgstab<Dim>* s : {&one, &many}) {
    s->set_tolerance(1e-12);
    s->set_max_iterations(max_iterations);
  }
  std::vector<double> b_one, b_many, x_one, x_many;
  // Two solves: from zero, then warm-started from the first answer with a scaled right-hand side.
  for (double scale : {1.0, 1.3}) {
    fill(whole, one, b_one, scale);
    fill(part, many, b_many, scale);
    const LinearSolveOutcome ref = one.solve(b_one, x_one);
    const LinearSolveOutcome got = many.solve(b_many, x_many);
    ASSERT_TRUE(ref.ok) << ref.why;
    ASSERT_TRUE(got.ok) << got.why;
    EXPECT_EQ(got.fell_back, ref.fell_back);
    EXPECT_EQ(got.iterations, ref.iterations);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(got.error), std::bit_cast<std::uint64_t>(ref.error));
    std::vector<std::uint64_t> want;
    for (double v : x_one) want.push_back(std::bit_cast<std::uint64_t>(v));
    EXPECT_EQ(gathered_bits(whole, part.owned, x_many), want) << world().size() << " ranks, scale " << scale;
  }
}

TEST(StencilBicgstabRanks, Walled2dCutAlongY) { check<2>({23, 41}, -1, {1, world().size()}); }
TEST(StencilBicgstabRanks, PeriodicX2dCutAlongY) { check<2>({24, 37}, 0, {1, world().size()}); }
TEST(StencilBicgstabRanks, Walled3dCutAlongYAndZ) {
  const int p = world().size();
  check<3>({11, 14, 9}, -1, {1, p, 1});
  check<3>({11, 14, 9}, -1, {1, 1, p});
  if (p == 4) check<3>({11, 14, 9}, -1, {1, 2, 2});
}
TEST(StencilBicgstabRanks, PeriodicXZ3dCutAlongY) {
  check<3>({10, 13, 7}, 0, {1, world().size(), 1});
  check<3>({10, 13, 7}, 2, {1, world().size(), 1});
}
TEST(StencilBicgstabRanks, LuFallbackIsTheSameOnEveryRank) { check<3>({8, 12, 6}, 0, {1, world().size(), 1}, 2); }

TEST(StencilBicgstabRanks, NonFiniteRowNamedAlike) {
  Grid<2> whole = Grid<2>::uniform({1.0, 2.0}, {10, 20}, 1);
  Grid<2> part = whole;
  part.owned = block_of<2>(whole.domain, {1, world().size()}, world().rank());
  StencilBicgstab<2> s(part, world());
  std::vector<double> b;
  fill(part, s, b, 1.0);
  // Global rows 37 and 170 are poisoned; whoever owns them, every rank names 37.
  int r = 0;
  for_each(part.owned, [&](const Index<2>& c) {
    const int g = c[0] + 10 * c[1];
    if (g == 37 || g == 170) b[static_cast<std::size_t>(r)] = NAN;
    ++r;
  });
  std::vector<double> x;
  const LinearSolveOutcome out = s.solve(b, x);
  EXPECT_FALSE(out.ok);
  EXPECT_EQ(out.bad_row, 37);
}

}  // namespace
}  // namespace fluidbed
