// Particle -> grid and grid -> particle kernels of the CFD-DEM coupling (src/coupling/voidage.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "coupling/voidage.hpp"

namespace fluidbed {
namespace {

// A 5 x 4 grid offset from the origin, so that x0 and y0 enter every formula.
Grid2 test_grid() { return Grid2{5, 4, 0.02, 0.03, 0.1, -0.05}; }

ParticleStore<2> random_particles(const Grid2& g, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(g.x0, g.x0 + g.width()), uy(g.y0, g.y0 + g.height());
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
  const Grid2 g = test_grid();
  // Points on a fine lattice that includes the walls, cell faces and cell centres.
  for (VoidageMethod m : {VoidageMethod::Centre, VoidageMethod::Bilinear}) {
    for (int a = 0; a <= 40; ++a) {
      for (int b = 0; b <= 40; ++b) {
        const double x = g.x0 + g.width() * a / 40.0, y = g.y0 + g.height() * b / 40.0;
        const CellWeights<2> cw = cell_weights(g, m, x, y);
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
  const Grid2 g = test_grid();
  // A quarter of the way from the centre of cell (1, 1) towards (2, 1) and 0.1 of the way towards (1, 2).
  const double x = g.xc(1) + 0.25 * g.dx, y = g.yc(1) + 0.1 * g.dy;
  const CellWeights<2> cw = cell_weights(g, VoidageMethod::Bilinear, x, y);
  double w11 = 0, w21 = 0, w12 = 0, w22 = 0;
  for (int k = 0; k < cw.count; ++k) {
    const std::size_t c = cw.cell[static_cast<std::size_t>(k)];
    const double w = cw.w[static_cast<std::size_t>(k)];
    if (c == g.index(1, 1)) w11 += w;
    if (c == g.index(2, 1)) w21 += w;
    if (c == g.index(1, 2)) w12 += w;
    if (c == g.index(2, 2)) w22 += w;
  }
  EXPECT_NEAR(w11, 0.75 * 0.9, 1e-14);
  EXPECT_NEAR(w21, 0.25 * 0.9, 1e-14);
  EXPECT_NEAR(w12, 0.75 * 0.1, 1e-14);
  EXPECT_NEAR(w22, 0.25 * 0.1, 1e-14);
}

TEST(CellWeights, FoldAtWallsIntoBoundaryCells) {
  const Grid2 g = test_grid();
  // Left of the first cell centre, near the bottom-left corner: the ghost cells' share goes to cell (0, 0)
  // (all of it) and, in y above the first centre, to (0, 0) and (0, 1) only.
  const auto weight_in = [&](const CellWeights<2>& cw, int i, int j) {
    double w = 0.0;
    for (int k = 0; k < cw.count; ++k) {
      if (cw.cell[static_cast<std::size_t>(k)] == g.index(i, j)) w += cw.w[static_cast<std::size_t>(k)];
    }
    return w;
  };
  const CellWeights<2> corner = cell_weights(g, VoidageMethod::Bilinear, g.x0 + 0.1 * g.dx, g.y0 + 0.2 * g.dy);
  EXPECT_NEAR(weight_in(corner, 0, 0), 1.0, 1e-15);
  const CellWeights<2> left = cell_weights(g, VoidageMethod::Bilinear, g.x0 + 0.3 * g.dx, g.yc(0) + 0.4 * g.dy);
  EXPECT_NEAR(weight_in(left, 0, 0), 0.6, 1e-14);
  EXPECT_NEAR(weight_in(left, 0, 1), 0.4, 1e-14);
  const CellWeights<2> top_right = cell_weights(g, VoidageMethod::Bilinear, g.x0 + g.width(), g.y0 + g.height());
  EXPECT_NEAR(weight_in(top_right, g.nx - 1, g.ny - 1), 1.0, 1e-15);
  // Centre method: the cell holding the point, the last one for a point on the far wall.
  const CellWeights<2> c = cell_weights(g, VoidageMethod::Centre, g.x0 + g.width(), g.y0 + 1.5 * g.dy);
  ASSERT_EQ(c.count, 1);
  EXPECT_EQ(c.cell[0], g.index(g.nx - 1, 1));
}

TEST(ComputeVoidage, DepositedVolumeEqualsParticleVolume) {
  const Grid2 g = test_grid();
  const ParticleStore<2> p = random_particles(g, 500, 7);
  // Particles on walls and corners too, where the folding must keep their whole volume.
  ParticleStore<2> q = p;
  Species s;
  for (Vec2 pos : {Vec2{g.x0, g.y0}, Vec2{g.x0 + g.width(), g.y0}, Vec2{g.x0, g.y0 + g.height()},
                   Vec2{g.x0 + g.width(), g.y0 + g.height()}, Vec2{g.x0 + 0.5 * g.dx, g.y0 + 0.01 * g.dy}}) {
    q.add(static_cast<std::int64_t>(q.size()), 0, s, pos);
  }
  double v_particles = 0.0;
  for (double r : q.radius) v_particles += sphere_volume(r);
  const double depth = 0.004;
  for (VoidageMethod m : {VoidageMethod::Centre, VoidageMethod::Bilinear}) {
    Field2 eps;
    compute_voidage(q, g, m, depth, eps);
    ASSERT_EQ(eps.nx, g.nx);
    ASSERT_EQ(eps.ny, g.ny);
    double v_grid = 0.0;
    for (double e : eps.v) v_grid += (1.0 - e) * g.dx * g.dy * depth;
    // Round-off only: about one ulp per particle-cell addition and per cell of the sum.
    EXPECT_NEAR(v_grid / v_particles, 1.0, 1e-12);
  }
}

TEST(ComputeVoidage, CentreMethodCountsWholeParticleInItsCell) {
  const Grid2 g = test_grid();
  ParticleStore<2> p;
  Species s;
  s.diameter = 0.003;
  p.add(0, 0, s, {g.xc(2) + 0.45 * g.dx, g.yc(1) - 0.45 * g.dy});
  Field2 eps;
  const double depth = 0.003;
  compute_voidage(p, g, VoidageMethod::Centre, depth, eps);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double expected = (i == 2 && j == 1) ? 1.0 - s.volume() / (g.dx * g.dy * depth) : 1.0;
      EXPECT_NEAR(eps(i, j), expected, 1e-15);
    }
  }
}

TEST(Gather, LinearFieldIsExactInTheInterior) {
  const Grid2 g = test_grid();
  Field2 f(g.nx, g.ny);
  const auto linear = [](double x, double y) { return 3.0 - 40.0 * x + 25.0 * y; };
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) f(i, j) = linear(g.xc(i), g.yc(j));
  }
  // Interior: between the first and last cell centres, where no weight is folded.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(g.xc(0), g.xc(g.nx - 1)), uy(g.yc(0), g.yc(g.ny - 1));
  for (int k = 0; k < 200; ++k) {
    const double x = ux(rng), y = uy(rng);
    const CellWeights<2> cw = cell_weights(g, VoidageMethod::Bilinear, x, y);
    EXPECT_NEAR(gather(f, cw), linear(x, y), 1e-13) << x << " " << y;
  }
  // Outside the interior the kernel holds the boundary value (a folded weight sees the boundary cell).
  const CellWeights<2> wall = cell_weights(g, VoidageMethod::Bilinear, g.x0, g.yc(2));
  EXPECT_NEAR(gather(f, wall), linear(g.xc(0), g.yc(2)), 1e-13);
}

TEST(CellSolidsVelocity, UniformVelocityIsReproduced) {
  const Grid2 g = test_grid();
  ParticleStore<2> p = random_particles(g, 300, 3);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.vx[i] = 0.7;
    p.vy[i] = -1.3;
  }
  for (VoidageMethod m : {VoidageMethod::Centre, VoidageMethod::Bilinear}) {
    Field2 us, vs;
    cell_solids_velocity(p, g, m, us, vs);
    for (std::size_t c = 0; c < g.cells(); ++c) {
      EXPECT_NEAR(us.v[c], 0.7, 1e-14);
      EXPECT_NEAR(vs.v[c], -1.3, 1e-14);
    }
  }
}

TEST(CellSolidsVelocity, VolumeWeightedMeanAndZeroInEmptyCells) {
  const Grid2 g = test_grid();
  ParticleStore<2> p;
  Species small, big;
  small.diameter = 0.001;
  big.diameter = 0.002;  // eight times the volume
  p.add(0, 0, small, {g.xc(3), g.yc(2)}, {1.0, 0.0});
  p.add(1, 0, big, {g.xc(3), g.yc(2)}, {-1.0, 9.0});
  Field2 us, vs;
  cell_solids_velocity(p, g, VoidageMethod::Bilinear, us, vs);
  EXPECT_NEAR(us(3, 2), (1.0 - 8.0) / 9.0, 1e-14);
  EXPECT_NEAR(vs(3, 2), 8.0 * 9.0 / 9.0, 1e-14);
  EXPECT_EQ(us(0, 0), 0.0);
  EXPECT_EQ(vs(4, 3), 0.0);
}

}  // namespace
}  // namespace fluidbed
