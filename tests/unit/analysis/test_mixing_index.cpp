// Lacey mixing index: exactly 0 when every sample holds one colour, 1 within sampling noise for a random mixture.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "analysis/layer_tracers.hpp"
#include "analysis/mixing_index.hpp"

namespace fluidbed {
namespace {

// n_per particles on a lattice inside every sample cell of a 20 x 20 sample grid.
struct Lattice {
  std::vector<double> x, y;
  std::array<std::span<const double>, 2> pos() const { return {x, y}; }
};
Lattice lattice(const Grid<2>& g, int per_side) {
  Lattice l;
  for (int j = 0; j < g.n(1) * per_side; ++j)
    for (int i = 0; i < g.n(0) * per_side; ++i) {
      l.x.push_back((i + 0.5) * g.h[0] / per_side);
      l.y.push_back((j + 0.5) * g.h[1] / per_side);
    }
  return l;
}

TEST(LaceyIndex, SegregatedIsZero) {
  const Grid<2> g = Grid<2>::uniform({0.4, 0.4}, {20, 20});
  const Lattice l = lattice(g, 3);
  std::vector<std::uint8_t> lower(l.x.size());
  for (std::size_t k = 0; k < l.x.size(); ++k) lower[k] = l.y[k] < 0.16 ? 1 : 0;  // boundary on a sample edge
  const LaceyResult r = lacey_index<2>(l.pos(), lower, cell_geometry(g), MixingConfig{});
  ASSERT_TRUE(r.valid);
  EXPECT_NEAR(r.index, 0.0, 1e-12);
  EXPECT_NEAR(r.p, 0.4, 1e-12);
  EXPECT_NEAR(r.mean_per_sample, 9.0, 1e-12);
  EXPECT_EQ(r.samples, 400);
}

TEST(LaceyIndex, RandomMixtureIsOne) {
  // Colours drawn independently with p = 1/2, n = 9 per sample, N_s = 400 samples: S^2 averages N_s values of
  // (c - p)^2 of variance ~ 2 sigma^4, so sd(M) ~ sqrt(2 / N_s) / (n - 1) = 0.0088; 5 sd = 0.044.
  const Grid<2> g = Grid<2>::uniform({0.4, 0.4}, {20, 20});
  const Lattice l = lattice(g, 3);
  std::mt19937_64 rng(12345);
  std::bernoulli_distribution coin(0.5);
  std::vector<std::uint8_t> colour(l.x.size());
  for (auto& c : colour) c = coin(rng) ? 1 : 0;
  const LaceyResult r = lacey_index<2>(l.pos(), colour, cell_geometry(g), MixingConfig{});
  ASSERT_TRUE(r.valid);
  const double sd = std::sqrt(2.0 / r.samples) / (r.mean_per_sample - 1.0);
  EXPECT_NEAR(r.index, 1.0, 5.0 * sd);
}

TEST(LaceyIndex, SampleSizeIsAParameter) {
  // The same segregated halves sampled with cells that straddle the boundary are partly "mixed".
  const Grid<2> g = Grid<2>::uniform({0.4, 0.4}, {20, 20});
  const Lattice l = lattice(g, 3);
  std::vector<std::uint8_t> lower(l.x.size());
  for (std::size_t k = 0; k < l.x.size(); ++k) lower[k] = l.y[k] < 0.2 ? 1 : 0;
  MixingConfig whole;
  whole.sample_dx = 0.4;
  whole.sample_dy = 0.4;
  const LaceyResult one = lacey_index<2>(l.pos(), lower, cell_geometry(g), whole);
  EXPECT_EQ(one.samples, 1);
  EXPECT_NEAR(one.s2, 0.0, 1e-15);  // one sample holds the mean: S^2 = 0, the index is 1 by construction
  EXPECT_NEAR(lacey_index<2>(l.pos(), lower, cell_geometry(g), MixingConfig{}).index, 0.0, 1e-12);
}

TEST(LaceyIndex, PerGroupForThreeColours) {
  // Three horizontal bands aligned with the sample rows: every group is segregated from the rest (M = 0 exactly);
  // three colours dealt at random: each group's index is 1 within 5 sd (sd as in RandomMixtureIsOne).
  const Grid<2> g = Grid<2>::uniform({0.4, 0.4}, {20, 20});
  const Lattice l = lattice(g, 3);
  std::vector<std::int32_t> band(l.x.size()), dealt(l.x.size());
  std::mt19937_64 rng(99);
  std::uniform_int_distribution<int> die(0, 2);
  for (std::size_t k = 0; k < l.x.size(); ++k) {
    band[k] = l.y[k] < 0.12 ? 0 : (l.y[k] < 0.26 ? 1 : 2);
    dealt[k] = die(rng);
  }
  const auto seg = lacey_index_per_group<2>(l.pos(), band, 3, cell_geometry(g), MixingConfig{});
  const auto mix = lacey_index_per_group<2>(l.pos(), dealt, 3, cell_geometry(g), MixingConfig{});
  ASSERT_EQ(seg.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(seg[static_cast<std::size_t>(k)].index, 0.0, 1e-12);
    const LaceyResult& r = mix[static_cast<std::size_t>(k)];
    EXPECT_NEAR(r.index, 1.0, 5.0 * std::sqrt(2.0 / r.samples) / (r.mean_per_sample - 1.0));
  }
}

TEST(LaceyIndex, TracersOfInitialBedAreSegregated) {
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {30, 50});
  const BallTracers<2> tr(cell_geometry(g), 0.54, 2);
  const LaceyResult r = lacey_index<2>(tr, 1, cell_geometry(g), MixingConfig{});
  EXPECT_NEAR(r.index, 0.0, 1e-12);
  EXPECT_EQ(r.mean_per_sample, 1.0);
  EXPECT_FALSE(r.valid);  // one ball per sample: S0^2 = SR^2, the index is undefined
  MixingConfig coarse;
  coarse.sample_dx = 0.06;
  coarse.sample_dy = 0.06;
  EXPECT_TRUE(lacey_index<2>(tr, 1, cell_geometry(g), coarse).valid);
}

}  // namespace
}  // namespace fluidbed
