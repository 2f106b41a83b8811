// Block decomposition: every cell in exactly one block, the block sizes within one cell, the fewest cut faces.
#include <gtest/gtest.h>

#include <vector>

#include "parallel/decomposition.hpp"

namespace fluidbed {
namespace {

template <int Dim>
void expect_partition(const IndexBox<Dim>& domain, const Index<Dim>& blocks) {
  int ranks = 1;
  for (int a = 0; a < Dim; ++a) ranks *= blocks[a];
  std::vector<int> owner(domain.count(), -1);
  const auto slot = [&](const Index<Dim>& c) {
    std::size_t k = 0, stride = 1;
    for (int a = 0; a < Dim; ++a) {
      k += static_cast<std::size_t>(c[a] - domain.lo[a]) * stride;
      stride *= static_cast<std::size_t>(domain.extent(a));
    }
    return k;
  };
  for (int r = 0; r < ranks; ++r) {
    const IndexBox<Dim> b = block_of<Dim>(domain, blocks, r);
    for (int a = 0; a < Dim; ++a) {
      const int n = domain.extent(a), p = blocks[a];
      EXPECT_TRUE(b.extent(a) == n / p || b.extent(a) == n / p + 1) << "rank " << r << " axis " << a;
    }
    for_each(b, [&](const Index<Dim>& c) {
      EXPECT_EQ(owner[slot(c)], -1);
      owner[slot(c)] = r;
    });
  }
  for (int o : owner) EXPECT_GE(o, 0);
}

TEST(Decomposition, BlocksPartitionTheDomain) {
  expect_partition<2>({{0, 0}, {30, 50}}, {4, 3});
  expect_partition<2>({{0, 0}, {7, 5}}, {7, 1});
  expect_partition<3>({{0, 0, 0}, {16, 50, 16}}, {2, 3, 2});
  expect_partition<3>({{2, 1, 0}, {9, 8, 5}}, {3, 2, 5});
}

TEST(Decomposition, FewestCutFaces) {
  // The paper's 30 x 50 grid on 2 ranks: one horizontal cut (30 faces) beats a vertical one (50).
  EXPECT_EQ((block_counts<2>(2, {30, 50})), (Index<2>{1, 2}));
  // 4 ranks: 2 x 2 cuts 50 + 30 = 80 faces, 1 x 4 cuts 90, 4 x 1 cuts 150.
  EXPECT_EQ((block_counts<2>(4, {30, 50})), (Index<2>{2, 2}));
  // A prime count on a cube: one axis takes it all.
  const Index<3> p = block_counts<3>(7, {16, 50, 16});
  EXPECT_EQ(p[0] * p[1] * p[2], 7);
  EXPECT_EQ(p[1], 7);
  // More ranks than cells along every way of cutting: none fits.
  EXPECT_EQ((block_counts<2>(7, {2, 3})), (Index<2>{0, 0}));
  EXPECT_EQ((block_counts<2>(1, {2, 3})), (Index<2>{1, 1}));
}

}  // namespace
}  // namespace fluidbed
