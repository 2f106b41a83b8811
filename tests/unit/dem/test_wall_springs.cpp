// WallSprings (src/dem/wall_springs.hpp): the springs against the walls, held only by the particles that hold
// one, must read as the dense per-particle arrays they replace, bit for bit (+0 without a record, a -0 kept), and
// move with their particles when the store is reordered or thinned.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

#include "dem/wall_springs.hpp"

namespace fluidbed {
namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

TEST(WallSprings, ParticlesWithoutARecordHoldPlusZero) {
  WallSprings<2> w;
  w.reset(5);
  EXPECT_EQ(w.records(), 0u);
  for (std::size_t i = 0; i < 5; ++i)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(bits(w.get(i, k).x), 0u);
  w.set(3, 1, Vec2{0.0, 0.0});  // +0: nothing to hold
  EXPECT_EQ(w.records(), 0u);
  EXPECT_EQ(w.record(3), -1);
  w.set(3, 1, Vec2{1e-6, -2e-6});
  ASSERT_GE(w.record(3), 0);
  EXPECT_EQ(w.get(3, 1).y, -2e-6);
  EXPECT_EQ(bits(w.get(3, 0).x), 0u);  // its other walls read +0
}

TEST(WallSprings, MinusZeroKeepsItsRecordThroughCompaction) {
  WallSprings<3> w;
  w.reset(4);
  w.set(0, 5, Vec3{0.0, -0.0, 0.0});
  w.set(2, 0, Vec3{1.0, 2.0, 3.0});
  w.set(2, 0, Vec3{});  // returned to +0: dropped at the next compaction
  EXPECT_EQ(w.records(), 2u);
  w.compact();
  EXPECT_EQ(w.records(), 1u);
  EXPECT_EQ(w.record(2), -1);
  ASSERT_GE(w.record(0), 0);
  EXPECT_EQ(bits(w.get(0, 5).y), bits(-0.0));
}

TEST(WallSprings, SpringsMoveWithTheirParticles) {
  WallSprings<2> w;
  w.reset(5);
  for (std::size_t i = 0; i < 5; ++i) w.set(i, static_cast<int>(i % 4), Vec2{1.0 + static_cast<double>(i), 0.5});
  w.push_back();  // a fed particle: none held
  EXPECT_EQ(w.size(), 6u);
  w.permute({4, 5, 2, 0});  // particles 1 and 3 leave
  ASSERT_EQ(w.size(), 4u);
  EXPECT_EQ(w.records(), 3u);
  EXPECT_EQ(w.get(0, 0).x, 5.0);  // old slot 4, wall 0
  EXPECT_EQ(w.record(1), -1);      // the fed particle
  EXPECT_EQ(w.get(2, 2).x, 3.0);  // old slot 2
  EXPECT_EQ(w.get(3, 0).x, 1.0);  // old slot 0
  // The records are laid out in slot order after a reordering.
  EXPECT_LT(w.record(0), w.record(2));
  EXPECT_LT(w.record(2), w.record(3));
}

}  // namespace
}  // namespace fluidbed
