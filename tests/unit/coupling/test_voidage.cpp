// Particle -> grid and grid -> particle kernels of the CFD-DEM coupling (src/coupling/voidage.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "coupling/voidage.hpp"

namespace fluidbed {
namespace {

// A 5 x 4 grid offset from the origin, so that the origin enters every formula.
Grid<2> test_grid() {
  Grid<2> g = Grid<2>::uniform({0.1, 0.12}, {5, 4});
  g.h = {0.02, 0.03};
  g.origin = {0.1, -0.05};
  return g;
}

// The weights of a point for the ghost-free cell fields of the grid, and the storage index of cell (i, j) in them.
CellWeights<2> weights_at(const Grid<2>& g, VoidageMethod m, double x, double y) {
  return cell_weights(g, cell_field(g), m, Vec2{x, y});
}
std::size_t cell_index(const Grid<2>& g, int i, int j) { return cell_field(g).index({i, j}); }

ParticleStore<2> random_particles(const Grid<2>& g, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(g.origin[0], g.origin[0] + g.length(0)), uy(g.origin[1], g.origin[1] + g.length(1));
  std::uniform_real_distribution<double> ud(0.001, 0.004), uv(-2.0, 2.0);
  ParticleStore<2> p;
  for (int k = 0; k < n; ++k) {
    Species s;
    s.diameter = ud(rng);
    p.add(k, 0, s, {ux(rng), uy(rng)}, {uv(rng), uv(rng)});
  }
  return p;
}

double sphere_volume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

TEST(CellWeights, SumToOneEverywhere) {
  const Grid<2> g = test_grid();
  // Points on a fine lattice that includes the walls, cell faces and cell centres.
  for (VoidageMethod m : {VoidageMethod::Centre, VoidageMethod::Bilinear}) {
    for (int a = 0; a <= 40; ++a) {
      for (int b = 0; b <= 40; ++b) {
        const double x = g.origin[0] + g.length(0) * a / 40.0, y = g.origin[1] + g.length(1) * b / 40.0;
        const CellWeights<2> cw = weights_at(g, m, x, y);
        double sum = 0.0;
        for (int k = 0; k < cw.count; ++k) {
          const double w = cw.w[static_cast<std::size_t>(k)];
          EXPECT_GE(w, 0.0);
          EXPECT_LT(cw.cell[static_cast<std::size_t>(k)], g.cells());
          sum += w;
        }
        EXPECT_NEAR(sum, 1.0, 1e-15) << x << " " << y;
      }
    }
  }
}

TEST(CellWeights, BilinearInteriorPointSharesWithFourNearestCentres) {
  const Grid<2> g = test_grid();
  // A quarter of the way from the centre of cell (1, 1) towards (2, 1) and 0.1 of the way towards (1, 2).
  const double x = g.centre(0, 1) + 0.25 * g.h[0], y = g.centre(1, 1) + 0.1 * g.h[1];
  const CellWeights<2> cw = weights_at(g, VoidageMethod::Bilinear, x, y);
  double w11 = 0, w21 = 0, w12 = 0, w22 = 0;
  for (int k = 0; k < cw.count; ++k) {
    const std::size_t c = cw.cell[static_cast<std::size_t>(k)];
    const double w = cw.w[static_cast<std::size_t>(k)];
    if (c == cell_index(g, 1, 1)) w11 += w;
    if (c == cell_index(g, 2, 1)) w21 += w;
    if (c == cell_index(g, 1, 2)) w12 += w;
    if (c == cell_index(g, 2, 2)) w22 += w;
  }
  EXPECT_NEAR(w11, 0.75 * 0.9, 1e-14);
  EXPECT_NEAR(w21, 0.25 * 0.9, 1e-14);
  EXPECT_NEAR(w12, 0.75 * 0.1, 1e-14);
  EXPECT_NEAR(w22, 0.25 * 0.1, 1e-14);
}

TEST(CellWeights, FoldAtWallsIntoBoundaryCells) {
  const Grid<2> g = test_grid();
  // Left of the first cell centre, near the bottom-left corner: the ghost cells' share goes to cell (0, 0)
  // (all of it) and, in y above the first centre, to (0, 0) and (0, 1) only.
  const auto weight_in = [&](const CellWeights<2>& cw, int i, int j) {
    double w = 0.0;
    for (int k = 0; k < cw.count; ++k) {
      if (cw.cell[static_cast<std::size_t>(k)] == cell_index(g, i, j)) w += cw.w[static_cast<std::size_t>(k)];
    }
    return w;
  };
  const CellWeights<2> corner = weights_at(g, VoidageMethod::Bilinear, g.origin[0] + 0.1 * g.h[0], g.origin[1] + 0.2 * g.h[1]);
  EXPECT_NEAR(weight_in(corner, 0, 0), 1.0, 1e-15);
  const CellWeights<2> left = weights_at(g, VoidageMethod::Bilinear, g.origin[0] + 0.3 * g.h[0], g.centre(1, 0) + 0.4 * g.h[1]);
  EXPECT_NEAR(weight_in(left, 0, 0), 0.6, 1e-14);
  EXPECT_NEAR(weight_in(left, 0, 1), 0.4, 1e-14);
  const CellWeights<2> top_right = weights_at(g, VoidageMethod::Bilinear, g.origin[0] + g.length(0), g.origin[1] + g.length(1));
  EXPECT_NEAR(weight_in(top_right, g.n(0) - 1, g.n(1) - 1), 1.0, 1e-15);
  // Centre method: the cell holding the point, the last one for a point on the far wall.
  const CellWeights<2> c = weights_at(g, VoidageMethod::Centre, g.origin[0] + g.length(0), g.origin[1] + 1.5 * g.h[1]);
  ASSERT_EQ(c.count, 1);
  EXPECT_EQ(c.cell[0], cell_index(g, g.n(0) - 1, 1));
}

TEST(ComputeVoidage, DepositedVolumeEqualsParticleVolume) {
  const Grid<2> g = test_grid();
  const ParticleStore<2> p = random_particles(g, 500, 7);
  // Particles on walls and corners too, where the folding must keep their whole volume.
  ParticleStore<2> q = p;
  Species s;
  for (Vec2 pos : {Vec2{g.origin[0], g.origin[1]}, Vec2{g.origin[0] + g.length(0), g.origin[1]}, Vec2{g.origin[0], g.origin[1] + g.length(1)},
                   Vec2{g.origin[0] + g.length(0), g.origin[1] + g.length(1)}, Vec2{g.origin[0] + 0.5 * g.h[0], g.origin[1] + 0.01 * g.h[1]}}) {
    q.add(static_cast<std::int64_t>(q.size()), 0, s, pos);
  }
  double v_particles = 0.0;
  for (double r : q.radius) v_particles += sphere_volume(r);
  const double depth = 0.004;
  for (VoidageMethod m : {VoidageMethod::Centre, VoidageMethod::Bilinear}) {
    Field<2> eps;
    compute_voidage(q, g, m, depth, eps);
    ASSERT_EQ(eps.box().extent(0), g.n(0));
    ASSERT_EQ(eps.box().extent(1), g.n(1));
    double v_grid = 0.0;
    for (double e : eps.data()) v_grid += (1.0 - e) * g.h[0] * g.h[1] * depth;
    // Round-off only: about one ulp per particle-cell addition and per cell of the sum.
    EXPECT_NEAR(v_grid / v_particles, 1.0, 1e-12);
  }
}

TEST(ComputeVoidage, CentreMethodCountsWholeParticleInItsCell) {
  const Grid<2> g = test_grid();
  ParticleStore<2> p;
  Species s;
  s.diameter = 0.003;
  p.add(0, 0, s, {g.centre(0, 2) + 0.45 * g.h[0], g.centre(1, 1) - 0.45 * g.h[1]});
  Field<2> eps;
  const double depth = 0.003;
  compute_voidage(p, g, VoidageMethod::Centre, depth, eps);
  for (int j = 0; j < g.n(1); ++j) {
    for (int i = 0; i < g.n(0); ++i) {
      const double expected = (i == 2 && j == 1) ? 1.0 - s.volume() / (g.h[0] * g.h[1] * depth) : 1.0;
      EXPECT_NEAR(eps(i, j), expected, 1e-15);
    }
  }
}

TEST(Gather, LinearFieldIsExactInTheInterior) {
  const Grid<2> g = test_grid();
  Field<2> f(cell_field(g));
  const auto linear = [](double x, double y) { return 3.0 - 40.0 * x + 25.0 * y; };
  for (int j = 0; j < g.n(1); ++j) {
    for (int i = 0; i < g.n(0); ++i) f(i, j) = linear(g.centre(0, i), g.centre(1, j));
  }
  // Interior: between the first and last cell centres, where no weight is folded.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(g.centre(0, 0), g.centre(0, g.n(0) - 1)), uy(g.centre(1, 0), g.centre(1, g.n(1) - 1));
  for (int k = 0; k < 200; ++k) {
    const double x = ux(rng), y = uy(rng);
    const CellWeights<2> cw = weights_at(g, VoidageMethod::Bilinear, x, y);
    EXPECT_NEAR(gather(f, cw), linear(x, y), 1e-13) << x << " " << y;
  }
  // Outside the interior the kernel holds the boundary value (a folded weight sees the boundary cell).
  const CellWeights<2> wall = weights_at(g, VoidageMethod::Bilinear, g.origin[0], g.centre(1, 2));
  EXPECT_NEAR(gather(f, wall), linear(g.centre(0, 0), g.centre(1, 2)), 1e-13);
}

TEST(CellSolidsVelocity, UniformVelocityIsReproduced) {
  const Grid<2> g = test_grid();
  ParticleStore<2> p = random_particles(g, 300, 3);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.vx[i] = 0.7;
    p.vy[i] = -1.3;
  }
  for (VoidageMethod m : {VoidageMethod::Centre, VoidageMethod::Bilinear}) {
    std::array<Field<2>, 2> u;
    cell_solids_velocity<2>(p, g, m, u);
    const Field<2>& us = u[0];
    const Field<2>& vs = u[1];
    for (std::size_t c = 0; c < g.cells(); ++c) {
      EXPECT_NEAR(us.data()[c], 0.7, 1e-14);
      EXPECT_NEAR(vs.data()[c], -1.3, 1e-14);
    }
  }
}

TEST(CellSolidsVelocity, VolumeWeightedMeanAndZeroInEmptyCells) {
  const Grid<2> g = test_grid();
  ParticleStore<2> p;
  Species small, big;
  small.diameter = 0.001;
  big.diameter = 0.002;  // eight times the volume
  p.add(0, 0, small, {g.centre(0, 3), g.centre(1, 2)}, {1.0, 0.0});
  p.add(1, 0, big, {g.centre(0, 3), g.centre(1, 2)}, {-1.0, 9.0});
  std::array<Field<2>, 2> u;
  cell_solids_velocity<2>(p, g, VoidageMethod::Bilinear, u);
  const Field<2>& us = u[0];
  const Field<2>& vs = u[1];
  EXPECT_NEAR(us(3, 2), (1.0 - 8.0) / 9.0, 1e-14);
  EXPECT_NEAR(vs(3, 2), 8.0 * 9.0 / 9.0, 1e-14);
  EXPECT_EQ(us(0, 0), 0.0);
  EXPECT_EQ(vs(4, 3), 0.0);
}

}  // namespace
}  // namespace fluidbed
