// Layer colouring and the cell tracer balls of the paper's Fig. 4, in 2D.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "analysis/layer_tracers.hpp"
#include "run/analysis_csv.hpp"

namespace fluidbed {
namespace {

TEST(BallTracers2d, OneBallPerInitialBedCellWithLayers) {
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {30, 50});
  const double bed_height = 0.54;  // 27 rows of 2 cm
  const BallTracers<2> tr(cell_geometry(g), bed_height, 9);
  ASSERT_EQ(tr.size(), static_cast<std::size_t>(30 * 27));
  for (std::size_t k = 0; k < tr.size(); ++k) {
    EXPECT_LT(tr.y[k], bed_height);
    EXPECT_EQ(tr.layer[k], static_cast<int>(std::floor(tr.y[k] / 0.06)));  // 9 layers of 6 cm
    EXPECT_EQ(tr.id[k], static_cast<std::int64_t>(k));
  }
}

TEST(BallTracers2d, UniformVelocityMovesEveryBallByVt) {
  // Every cell has the same velocity, so after n steps each ball has moved (u n dt, v n dt); the only error is the
  // round-off of n additions, below n ulp(1 m) ~ 1e-13 m for n = 2000. Balls of the last column would cross the
  // right wall and are held on it.
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {30, 50});
  BallTracers<2> tr(cell_geometry(g), 0.54, 9);
  const BallTracers<2> start = tr;
  const double u = 0.013, v = 0.021, dt = 1e-3;
  const int steps = 2000;  // moves 2.6 cm and 4.2 cm
  const Field<2> us(cell_field(g, u)), vs(cell_field(g, v));
  for (int n = 0; n < steps; ++n) tr.advance({cell_view(g, us, "us"), cell_view(g, vs, "vs")}, dt);
  for (std::size_t k = 0; k < tr.size(); ++k) {
    EXPECT_NEAR(tr.x[k], std::min(start.x[k] + u * steps * dt, g.length(0)), 1e-12);
    EXPECT_LE(tr.x[k], g.length(0));
    EXPECT_NEAR(tr.y[k], start.y[k] + v * steps * dt, 1e-12);
    EXPECT_EQ(tr.layer[k], start.layer[k]);
  }
}

TEST(BallTracers2d, PiecewiseConstantVelocityAndClampedToDomain) {
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {30, 50});
  BallTracers<2> tr(cell_geometry(g), 0.1, 1);
  Field<2> us(cell_field(g, 0.0)), vs(cell_field(g, 0.0));
  // Only column 3 moves; a ball leaving the domain is held at its edge.
  for (int j = 0; j < g.n(1); ++j) {
    us(3, j) = -1.5;
    vs(3, j) = 0.5;
  }
  const BallTracers<2> start = tr;
  for (int n = 0; n < 100; ++n) tr.advance({cell_view(g, us, "us"), cell_view(g, vs, "vs")}, 0.01);
  for (std::size_t k = 0; k < tr.size(); ++k) {
    EXPECT_GE(tr.x[k], 0.0);
    EXPECT_LE(tr.x[k], g.length(0));
    EXPECT_GE(tr.y[k], 0.0);
    EXPECT_LE(tr.y[k], g.length(1));
    if (g.cell(0, start.x[k]) != 3) {
      EXPECT_EQ(tr.x[k], start.x[k]);
      EXPECT_EQ(tr.y[k], start.y[k]);
    } else {
      // After the first step (x = 0.07 - 0.015 = 0.055) the ball sits in column 2, which does not move.
      EXPECT_NEAR(tr.x[k], start.x[k] - 0.015, 1e-15);
      EXPECT_NEAR(tr.y[k], start.y[k] + 0.005, 1e-15);
    }
  }
  // A strong leftward field drives every ball onto the wall x = 0 and no further.
  const Field<2> left(cell_field(g, -10.0)), none(cell_field(g, 0.0));
  for (int n = 0; n < 10; ++n) tr.advance({cell_view(g, left, "us"), cell_view(g, none, "vs")}, 0.01);
  for (std::size_t k = 0; k < tr.size(); ++k) EXPECT_EQ(tr.x[k], 0.0);
}

TEST(BallTracers2d, WrapAcrossAPeriodicSide) {
  // Periodic in x: a ball that moves u n dt = 0.65 m in a 0.6 m wide bed ends where it started plus 0.05 m, modulo
  // the period, inside [0, 0.6); the same round-off bound as UniformVelocityMovesEveryBallByVt. y stays clamped.
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {30, 50});
  BallTracers<2> tr(cell_geometry(g), 0.1, 1);
  tr.set_periodic(0, true);
  const BallTracers<2> start = tr;
  const Field<2> us(cell_field(g, 0.65)), vs(cell_field(g, -1.0));
  for (int n = 0; n < 1000; ++n) tr.advance({cell_view(g, us, "us"), cell_view(g, vs, "vs")}, 1e-3);
  for (std::size_t k = 0; k < tr.size(); ++k) {
    EXPECT_GE(tr.x[k], 0.0);
    EXPECT_LT(tr.x[k], g.length(0));
    const double want = std::fmod(start.x[k] + 0.05, 0.6);
    EXPECT_NEAR(std::remainder(tr.x[k] - want, 0.6), 0.0, 1e-12) << "ball " << k;
    EXPECT_EQ(tr.y[k], 0.0);
  }
}

TEST(AssignLayers, ByInitialHeight) {
  ParticleStore<2> p;
  const Species s;
  const double ys[] = {0.001, 0.059, 0.061, 0.31, 0.539, 0.6};
  for (int k = 0; k < 6; ++k) p.add(k, 0, s, {0.1, ys[k]});
  assign_layers(p, 9, 0.54);
  const int expected[] = {0, 0, 1, 5, 8, 8};  // heights above the bed go to the top layer
  for (int k = 0; k < 6; ++k) EXPECT_EQ(p.layer[static_cast<std::size_t>(k)], expected[k]) << ys[k];
}

TEST(TracerCsv, HeaderAndRows) {
  const Grid<2> g = Grid<2>::uniform({0.04, 0.04}, {2, 2});
  const BallTracers<2> tr(cell_geometry(g), 0.02, 1);
  EXPECT_EQ(tracer_csv<2>(tr), "ball_id,x,y,layer\n0,0.01,0.01,0\n1,0.03,0.01,0\n");
}

}  // namespace
}  // namespace fluidbed
