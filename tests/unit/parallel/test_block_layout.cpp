// The blocks of a particle run and their deal to ranks: the Hilbert index is a bijection whose consecutive points
// are neighbours, every cell lies in one block (the one block_at gives for its points), blocks are at least the
// asked width, the deal follows the curve with about equal weight per rank, and neighbours wrap on periodic axes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <vector>

#include "parallel/block_layout.hpp"

namespace fluidbed {
namespace {

template <int Dim>
void expect_hilbert_walk(int bits) {
  const std::uint32_t side = 1u << bits;
  std::size_t points = 1;
  for (int a = 0; a < Dim; ++a) points *= side;
  std::vector<std::array<std::uint32_t, Dim>> at(points);
  std::vector<bool> seen(points, false);
  std::array<std::uint32_t, Dim> c{};
  for (std::size_t k = 0; k < points; ++k) {
    std::size_t rest = k;
    for (int a = 0; a < Dim; ++a) {
      c[static_cast<std::size_t>(a)] = static_cast<std::uint32_t>(rest % side);
      rest /= side;
    }
    const std::uint64_t h = hilbert_index<Dim>(c, bits);
    ASSERT_LT(h, points);
    EXPECT_FALSE(seen[h]) << "index " << h << " given twice";
    seen[h] = true;
    at[h] = c;
  }
  // Consecutive indices are face neighbours: one step along one axis.
  for (std::size_t h = 1; h < points; ++h) {
    int dist = 0;
    for (int a = 0; a < Dim; ++a) {
      dist += std::abs(static_cast<int>(at[h][static_cast<std::size_t>(a)]) - static_cast<int>(at[h - 1][static_cast<std::size_t>(a)]));
    }
    EXPECT_EQ(dist, 1) << "between indices " << h - 1 << " and " << h;
  }
}

TEST(BlockLayout, HilbertIndexIsAWalkThroughNeighbours) {
  expect_hilbert_walk<2>(1);
  expect_hilbert_walk<2>(4);
  expect_hilbert_walk<3>(1);
  expect_hilbert_walk<3>(3);
}

TEST(BlockLayout, EveryCellInOneBlockAtLeastTheAskedWidth) {
  const BlockLayout<2> l({30, 50}, {0.02, 0.02}, {0.0, 0.0}, {4, 3}, {false, false});
  EXPECT_EQ(l.counts()[0], 7);  // 30 / 4
  EXPECT_EQ(l.counts()[1], 16);
  std::vector<int> block_of_cell(30 * 50, -1);
  for (int b = 0; b < l.blocks(); ++b) {
    const IndexBox<2> box = l.cells_of(b);
    EXPECT_GE(box.extent(0), 4);
    EXPECT_GE(box.extent(1), 3);
    for_each(box, [&](const Index<2>& c) {
      EXPECT_EQ(block_of_cell[static_cast<std::size_t>(c[0] + 30 * c[1])], -1);
      block_of_cell[static_cast<std::size_t>(c[0] + 30 * c[1])] = b;
    });
  }
  EXPECT_EQ(l.min_width(0), 4 * 0.02);
  // Any point of a cell (its centre, its corners' insides) lies in the cell's block; points beyond the box clamp.
  for (int j = 0; j < 50; ++j) {
    for (int i = 0; i < 30; ++i) {
      const int b = block_of_cell[static_cast<std::size_t>(i + 30 * j)];
      ASSERT_GE(b, 0);
      for (double fx : {0.001, 0.5, 0.999}) {
        for (double fy : {0.001, 0.5, 0.999}) EXPECT_EQ(l.block_at(Vec2{(i + fx) * 0.02, (j + fy) * 0.02}), b);
      }
    }
  }
  EXPECT_EQ(l.block_at(Vec2{-1.0, -1.0}), 0);
  EXPECT_EQ(l.block_at(Vec2{7.0, 9.0}), l.blocks() - 1);
}

TEST(BlockLayout, TheDealFollowsTheCurveWithEqualWeights) {
  BlockLayout<3> l({12, 20, 8}, {0.01, 0.01, 0.01}, {0.0, 0.0, 0.0}, {2, 2, 2}, {false, false, false});
  // A bed in the lower third: weight there, none above (the bubbling bed's imbalance).
  std::vector<double> w(static_cast<std::size_t>(l.blocks()));
  for (int b = 0; b < l.blocks(); ++b) w[static_cast<std::size_t>(b)] = l.coords(b)[1] < 3 ? 10.0 + b % 7 : 0.0;
  for (int ranks : {1, 2, 3, 4, 7}) {
    l.assign(w, ranks);
    const std::vector<double> per = l.rank_weights(w, ranks);
    double most = 0.0, total = 0.0;
    for (double x : per) {
      most = std::max(most, x);
      total += x;
    }
    // Whole blocks of at most 16 weight: a rank holds its share up to one block more.
    EXPECT_LE(most, total / ranks + 16.0) << ranks << " ranks";
    EXPECT_LT(imbalance(per), ranks == 1 ? 1.0 + 1e-12 : 1.25) << ranks << " ranks";
    // Runs along the curve: the owners never step back.
    const std::vector<int> order = l.curve_order();
    for (std::size_t k = 1; k < order.size(); ++k) EXPECT_LE(l.owner(order[k - 1]), l.owner(order[k]));
  }
}

TEST(BlockLayout, NeighboursWrapOnPeriodicAxesOnly) {
  const BlockLayout<2> l({10, 10}, {0.1, 0.1}, {0.0, 0.0}, {2, 2}, {true, false});
  Index<2> shift{};
  // Block (0, 0): its left neighbour is the last block of the row, one period to the left.
  EXPECT_EQ(l.neighbour(l.block({0, 0}), {-1, 0}, shift), l.block({4, 0}));
  EXPECT_EQ(shift[0], -1);
  EXPECT_EQ(l.neighbour(l.block({4, 2}), {1, 1}, shift), l.block({0, 3}));
  EXPECT_EQ(shift[0], 1);
  EXPECT_EQ(shift[1], 0);
  // Below the bottom row: no block (a wall).
  EXPECT_EQ(l.neighbour(l.block({2, 0}), {0, -1}, shift), -1);
}

}  // namespace
}  // namespace fluidbed
