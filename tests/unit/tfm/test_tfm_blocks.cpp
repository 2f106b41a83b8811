// tfm_blocks (src/tfm/tfm_solver.hpp): how the two-fluid model's grid is cut among ranks. x is never cut (the
// nonsymmetric solves sum whole x-lines), nor a periodic axis (its images stay on the rank); of the cuts along y and z
// the one with the fewest cell faces between blocks; none when the ranks do not fit.
#include <gtest/gtest.h>

#include "tfm/tfm_solver.hpp"

namespace fluidbed::tfm {
namespace {

TEST(TfmBlocks, TwoDimensionsCutAlongYOnly) {
  EXPECT_EQ((tfm_blocks<2>(1, {30, 50}, {false, false})), (Index<2>{1, 1}));
  EXPECT_EQ((tfm_blocks<2>(4, {30, 50}, {false, false})), (Index<2>{1, 4}));
  EXPECT_EQ((tfm_blocks<2>(4, {30, 50}, {true, false})), (Index<2>{1, 4}));  // periodic x: still only y is cut
  EXPECT_EQ((tfm_blocks<2>(51, {30, 50}, {false, false}))[0], 0);           // more ranks than rows
}

TEST(TfmBlocks, ThreeDimensionsTakeTheSmallerCutAndKeepPeriodicAxesWhole) {
  // 16 x 50 x 16: 4 ranks as 1 x 4 x 1 (3 planes of 16 x 16 faces) rather than 1 x 2 x 2 (16 x 16 + 16 x 50) or
  // 1 x 1 x 4 (3 planes of 16 x 50).
  EXPECT_EQ((tfm_blocks<3>(4, {16, 50, 16}, {false, false, false})), (Index<3>{1, 4, 1}));
  // A wide, shallow grid: cutting z is cheaper.
  EXPECT_EQ((tfm_blocks<3>(4, {16, 10, 60}, {false, false, false})), (Index<3>{1, 1, 4}));
  // z periodic: only y may be cut.
  EXPECT_EQ((tfm_blocks<3>(4, {16, 10, 60}, {false, false, true})), (Index<3>{1, 4, 1}));
  EXPECT_EQ((tfm_blocks<3>(6, {8, 3, 2}, {false, false, false})), (Index<3>{1, 3, 2}));
  EXPECT_EQ((tfm_blocks<3>(7, {8, 3, 2}, {false, false, false}))[0], 0);  // 7 cannot be placed on 3 x 2
}

}  // namespace
}  // namespace fluidbed::tfm
