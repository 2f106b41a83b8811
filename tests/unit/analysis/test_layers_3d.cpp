// Layer colouring, tracer balls and the Lacey index in 3D: the layers are horizontal slabs in y, z rides along.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <span>
#include <vector>

#include "analysis/layer_tracers.hpp"
#include "analysis/mixing_index.hpp"
#include "core/error.hpp"
#include "run/analysis_csv.hpp"

namespace fluidbed {
namespace {

const CellGeometry<3> grid3{{10, 25, 6}, {0.02, 0.02, 0.02}, {0.0, 0.0, 0.0}};

TEST(AssignLayers3d, ByHeightOnlyFromPlainArrays) {
  const std::vector<double> y{0.001, 0.059, 0.061, 0.31, 0.539, 0.6};
  std::vector<std::int32_t> layer(y.size(), -1);
  assign_layers(y, layer, 9, 0.54);
  const std::vector<std::int32_t> expected{0, 0, 1, 5, 8, 8};
  EXPECT_EQ(layer, expected);
  std::vector<std::int32_t> short_layer(2);
  EXPECT_THROW(assign_layers(y, short_layer, 9, 0.54), Error);
}

TEST(BallTracers3d, OneBallPerInitialBedCellAndUniformMotion) {
  // 10 x 25 x 6 cells of 2 cm, bed 0.3 m: 15 slabs of 60 balls, numbered in storage order, layers of 0.1 m by
  // height alone. A uniform velocity moves every ball by v t along each axis (round-off of n additions, below
  // n ulp(1 m) ~ 1e-13 m), clamped at the walls of the box (x reaches its far wall here).
  BallTracers<3> tr(grid3, 0.3, 3);
  ASSERT_EQ(tr.size(), static_cast<std::size_t>(10 * 15 * 6));
  ASSERT_EQ(tr.z.size(), tr.size());
  for (std::size_t k = 0; k < tr.size(); ++k) {
    EXPECT_EQ(tr.id[k], static_cast<std::int64_t>(k));
    EXPECT_LT(tr.y[k], 0.3);
    EXPECT_EQ(tr.layer[k], static_cast<int>(std::floor(tr.y[k] / 0.1)));
  }
  EXPECT_DOUBLE_EQ(tr.x[1], 0.03);   // axis 0 fastest
  EXPECT_DOUBLE_EQ(tr.y[10], 0.03);  // then y
  EXPECT_DOUBLE_EQ(tr.z[150], 0.03); // then z
  const BallTracers<3> start = tr;
  const std::vector<double> u(grid3.cells(), 0.05), v(grid3.cells(), 0.021), w(grid3.cells(), -0.013);
  const std::array<CellView<3>, 3> vel{CellView<3>{grid3, u.data()}, {grid3, v.data()}, {grid3, w.data()}};
  const int steps = 1000;
  const double dt = 1e-3;
  for (int n = 0; n < steps; ++n) tr.advance(vel, dt);
  for (std::size_t k = 0; k < tr.size(); ++k) {
    EXPECT_NEAR(tr.x[k], std::min(start.x[k] + 0.05 * steps * dt, 0.2), 1e-12);
    EXPECT_NEAR(tr.y[k], start.y[k] + 0.021 * steps * dt, 1e-12);
    EXPECT_NEAR(tr.z[k], std::max(start.z[k] - 0.013 * steps * dt, 0.0), 1e-12);
    EXPECT_EQ(tr.layer[k], start.layer[k]);
  }
  EXPECT_EQ(tracer_csv(tr).substr(0, 21), "ball_id,x,y,z,layer\n0");
}

TEST(BallTracers3d, CheckpointArraysAreChecked) {
  EXPECT_THROW(BallTracers<3>(grid3, {0, 1}, {std::vector<double>{0.1, 0.1}, {0.1, 0.1}, {0.1}}, {0, 0}), Error);
  EXPECT_THROW(BallTracers<3>(grid3, {0}, {std::vector<double>{0.1}, {0.1}, {0.5}}, {0}), Error);  // z > 0.12
  const BallTracers<3> ok(grid3, {7}, {std::vector<double>{0.1}, {0.1}, {0.12}}, {2});
  EXPECT_EQ(ok.size(), 1u);
}

TEST(LaceyIndex3d, SegregatedIsZeroRandomIsOne) {
  // 3 x 3 x 3 particles per sample box of a 8 x 8 x 8 box grid: slabs below y = 0.16 (a sample face) give M = 0
  // exactly; colours dealt at random with p = 1/2 give M = 1 within 5 sd, sd = sqrt(2 / N_s) / (n - 1) with
  // N_s = 512 samples of n = 27 (as in 2D).
  const CellGeometry<3> g{{8, 8, 8}, {0.04, 0.04, 0.04}, {0.0, 0.0, 0.0}};
  std::vector<double> x, y, z;
  for (int k = 0; k < 24; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i) {
        x.push_back((i + 0.5) * 0.04 / 3);
        y.push_back((j + 0.5) * 0.04 / 3);
        z.push_back((k + 0.5) * 0.04 / 3);
      }
  std::vector<std::uint8_t> lower(x.size()), dealt(x.size());
  std::mt19937_64 rng(2026);
  std::bernoulli_distribution coin(0.5);
  for (std::size_t k = 0; k < x.size(); ++k) {
    lower[k] = y[k] < 0.16 ? 1 : 0;
    dealt[k] = coin(rng) ? 1 : 0;
  }
  const std::array<std::span<const double>, 3> pos{x, y, z};
  const LaceyResult seg = lacey_index<3>(pos, lower, g, MixingConfig{});
  ASSERT_TRUE(seg.valid);
  EXPECT_EQ(seg.samples, 512);
  EXPECT_NEAR(seg.mean_per_sample, 27.0, 1e-12);
  EXPECT_NEAR(seg.index, 0.0, 1e-12);
  const LaceyResult mix = lacey_index<3>(pos, dealt, g, MixingConfig{});
  const double sd = std::sqrt(2.0 / mix.samples) / (mix.mean_per_sample - 1.0);
  std::printf("random 3D mixture: M exact 1 computed %.4f error %.2e (5 sd = %.2e)\n", mix.index, mix.index - 1.0,
              5.0 * sd);
  EXPECT_NEAR(mix.index, 1.0, 5.0 * sd);
  // A sample box as deep as the whole bed (sample_dz) sees the same slabs: still segregated.
  MixingConfig deep;
  deep.sample_dz = 0.32;
  const LaceyResult seg_deep = lacey_index<3>(pos, lower, g, deep);
  EXPECT_EQ(seg_deep.samples, 64);
  EXPECT_NEAR(seg_deep.index, 0.0, 1e-12);
  // The tracer balls of a 3D bed 0.32 m high, split at half height, on a sample face.
  const BallTracers<3> tr(grid3, 0.32, 2);
  MixingConfig coarse;
  coarse.sample_dx = coarse.sample_dy = coarse.sample_dz = 0.04;
  EXPECT_NEAR(lacey_index<3>(tr, 1, grid3, coarse).index, 0.0, 1e-12);
}

}  // namespace
}  // namespace fluidbed
