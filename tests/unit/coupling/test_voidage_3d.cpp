// The 3D deposition of the CFD-DEM coupling (src/coupling/voidage.hpp, Dim = 3): cloud-in-cell weights over the
// 8 surrounding cell centres, folded into the boundary cells at all six sides; the cell volume from the grid.
// Tolerances are round-off: a weight is a product of three fractions (a few ulp), a sum over 8 weights or over
// the cells of a grid adds one ulp per term.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "coupling/voidage.hpp"

namespace fluidbed {
namespace {

// 5 x 4 x 3 cells of unequal sizes, offset from the origin, so that every axis's h and origin enter.
Grid<3> test_grid() {
  Grid<3> g = Grid<3>::uniform({0.1, 0.12, 0.045}, {5, 4, 3}, 0);
  g.origin = {0.1, -0.05, 0.02};
  return g;
}

Vec3 corner(const Grid<3>& g, bool high_x, bool high_y, bool high_z) {
  return {g.origin[0] + (high_x ? g.length(0) : 0.0), g.origin[1] + (high_y ? g.length(1) : 0.0),
          g.origin[2] + (high_z ? g.length(2) : 0.0)};
}

ParticleStore<3> random_particles(const Grid<3>& g, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0), ud(0.001, 0.004), uv(-2.0, 2.0);
  ParticleStore<3> p;
  for (int k = 0; k < n; ++k) {
    Species s;
    s.diameter = ud(rng);
    Vec3 x{};
    for (int a = 0; a < 3; ++a) x[a] = g.origin[a] + u01(rng) * g.length(a);
    p.add(k, 0, s, x, {uv(rng), uv(rng), uv(rng)});
  }
  return p;
}

double weight_in(const Field<3>& layout, const CellWeights<3>& cw, int i, int j, int k) {
  double w = 0.0;
  for (int m = 0; m < cw.count; ++m) {
    if (cw.cell[static_cast<std::size_t>(m)] == layout.index({i, j, k})) w += cw.w[static_cast<std::size_t>(m)];
  }
  return w;
}

TEST(CellWeights3d, EightWeightsSumToOneEverywhere) {
  const Grid<3> g = test_grid();
  const Field<3> layout(g.owned, 1);  // with a ghost layer: the indices must still name owned cells
  const std::size_t n_alloc = layout.data().size();
  // A lattice that includes the six walls, the edges, the corners, cell faces and cell centres.
  constexpr int kN = 20;
  for (VoidageMethod m : {VoidageMethod::Centre, VoidageMethod::Bilinear}) {
    for (int a = 0; a <= kN; ++a) {
      for (int b = 0; b <= kN; ++b) {
        for (int c = 0; c <= kN; ++c) {
          const Vec3 x{g.origin[0] + g.length(0) * a / kN, g.origin[1] + g.length(1) * b / kN,
                       g.origin[2] + g.length(2) * c / kN};
          const CellWeights<3> cw = cell_weights(g, layout, m, x);
          ASSERT_EQ(cw.count, m == VoidageMethod::Centre ? 1 : 8);
          double sum = 0.0;
          for (int k = 0; k < cw.count; ++k) {
            const std::size_t cell = cw.cell[static_cast<std::size_t>(k)];
            EXPECT_GE(cw.w[static_cast<std::size_t>(k)], 0.0);
            ASSERT_LT(cell, n_alloc);
            // Never a ghost cell: every weight lands in an owned cell.
            bool owned = false;
            for_each(g.owned, [&](const Index<3>& q) { owned = owned || layout.index(q) == cell; });
            EXPECT_TRUE(owned) << x[0] << " " << x[1] << " " << x[2];
            sum += cw.w[static_cast<std::size_t>(k)];
          }
          EXPECT_NEAR(sum, 1.0, 1e-15) << x[0] << " " << x[1] << " " << x[2];
        }
      }
    }
  }
}

TEST(CellWeights3d, TrilinearInteriorPointSharesWithEightNearestCentres) {
  const Grid<3> g = test_grid();
  const Field<3> layout(g.owned, 0);
  // Fractions 0.25, 0.1 and 0.6 of the way from the centre of cell (1, 1, 0) towards (2, 2, 1).
  const double fx = 0.25, fy = 0.1, fz = 0.6;
  const Vec3 x{g.centre(0, 1) + fx * g.h[0], g.centre(1, 1) + fy * g.h[1], g.centre(2, 0) + fz * g.h[2]};
  const CellWeights<3> cw = cell_weights(g, layout, VoidageMethod::Bilinear, x);
  for (int di = 0; di < 2; ++di) {
    for (int dj = 0; dj < 2; ++dj) {
      for (int dk = 0; dk < 2; ++dk) {
        const double exact = (di ? fx : 1 - fx) * (dj ? fy : 1 - fy) * (dk ? fz : 1 - fz);
        EXPECT_NEAR(weight_in(layout, cw, 1 + di, 1 + dj, dk), exact, 1e-14) << di << dj << dk;
      }
    }
  }
}

TEST(CellWeights3d, FoldIntoBoundaryCellsAtAllSixSides) {
  const Grid<3> g = test_grid();
  const Field<3> layout(g.owned, 0);
  const Index<3> n{g.n(0), g.n(1), g.n(2)};
  // On each side, a point a fifth of a cell from the wall (outside the boundary cell's centre) and 0.3 of a cell
  // past the centre of cell 1 along the other two axes: the weight across the wall folds into the boundary
  // cell, so the boundary layer holds everything and shares it 0.7 / 0.3 along each other axis.
  for (int a = 0; a < 3; ++a) {
    for (bool high : {false, true}) {
      Vec3 x{};
      for (int b = 0; b < 3; ++b) x[b] = g.centre(b, 1) + 0.3 * g.h[b];
      x[a] = high ? g.origin[a] + g.length(a) - 0.2 * g.h[a] : g.origin[a] + 0.2 * g.h[a];
      const CellWeights<3> cw = cell_weights(g, layout, VoidageMethod::Bilinear, x);
      const int wall_cell = high ? n[a] - 1 : 0;
      double in_layer = 0.0;
      for (int di = 0; di < 2; ++di) {
        for (int dj = 0; dj < 2; ++dj) {
          // The two other axes, cells 1 (0.7) and 2 (0.3).
          const int b = (a + 1) % 3, c = (a + 2) % 3;
          Index<3> q{};
          q[a] = wall_cell;
          q[b] = 1 + di;
          q[c] = 1 + dj;
          const double exact = (di ? 0.3 : 0.7) * (dj ? 0.3 : 0.7);
          const double w = weight_in(layout, cw, q[0], q[1], q[2]);
          EXPECT_NEAR(w, exact, 1e-14) << "axis " << a << (high ? " high" : " low");
          in_layer += w;
        }
      }
      EXPECT_NEAR(in_layer, 1.0, 1e-14) << "axis " << a << (high ? " high" : " low");
    }
  }
  // The eight corners of the box: everything in the corner cell.
  for (int k = 0; k < 8; ++k) {
    const bool hx = k & 1, hy = (k >> 1) & 1, hz = (k >> 2) & 1;
    const CellWeights<3> cw = cell_weights(g, layout, VoidageMethod::Bilinear, corner(g, hx, hy, hz));
    EXPECT_NEAR(weight_in(layout, cw, hx ? n[0] - 1 : 0, hy ? n[1] - 1 : 0, hz ? n[2] - 1 : 0), 1.0, 1e-15) << k;
  }
}

TEST(Gather3d, LinearFieldIsExactInTheInteriorAndHeldAtTheWalls) {
  const Grid<3> g = test_grid();
  Field<3> f(g.owned, 1);
  const auto linear = [](const Vec3& x) { return 3.0 - 40.0 * x[0] + 25.0 * x[1] - 70.0 * x[2]; };
  for_each(g.owned, [&](const Index<3>& c) { f[c] = linear(g.centre(c)); });
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  double max_err = 0.0;
  // Between the first and last cell centres along every axis, where nothing is folded.
  for (int k = 0; k < 500; ++k) {
    Vec3 x{};
    for (int a = 0; a < 3; ++a) x[a] = g.centre(a, 0) + u01(rng) * (g.centre(a, g.n(a) - 1) - g.centre(a, 0));
    const double err = std::abs(gather(f, cell_weights(g, f, VoidageMethod::Bilinear, x)) - linear(x));
    max_err = std::max(max_err, err);
    EXPECT_LT(err, 1e-13) << x[0] << " " << x[1] << " " << x[2];
  }
  std::printf("[ gather3d ] linear field, 500 interior points: max |gathered - exact| %.2e\n", max_err);
  // Past the outermost centres the folded kernel holds the boundary cells' value along that axis.
  for (int a = 0; a < 3; ++a) {
    Vec3 x = g.centre(Index<3>{2, 1, 1});
    x[a] = g.origin[a];
    Vec3 held = x;
    held[a] = g.centre(a, 0);
    EXPECT_NEAR(gather(f, cell_weights(g, f, VoidageMethod::Bilinear, x)), linear(held), 1e-13) << a;
  }
}

TEST(ComputeVoidage3d, DepositedVolumeEqualsParticleVolume) {
  const Grid<3> g = test_grid();
  ParticleStore<3> p = random_particles(g, 800, 7);
  // Particles on the corners, edges and faces too, where the folding must keep their whole volume.
  Species s;
  for (int k = 0; k < 8; ++k) p.add(static_cast<std::int64_t>(p.size()), 0, s, corner(g, k & 1, (k >> 1) & 1, (k >> 2) & 1));
  p.add(static_cast<std::int64_t>(p.size()), 0, s, {g.origin[0], g.origin[1] + 0.5 * g.length(1), g.origin[2]});
  p.add(static_cast<std::int64_t>(p.size()), 0, s,
        {g.origin[0] + 0.3 * g.length(0), g.origin[1] + g.length(1), g.origin[2] + 0.01 * g.h[2]});
  double v_particles = 0.0;
  for (double r : p.radius) v_particles += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  // The 2D depth argument must play no part in 3D: a depth far from any cell size.
  const double depth = 0.37;
  const double v_cell = g.h[0] * g.h[1] * g.h[2];
  EXPECT_DOUBLE_EQ(deposition_volume(g, depth), v_cell);
  for (VoidageMethod m : {VoidageMethod::Centre, VoidageMethod::Bilinear}) {
    Field<3> eps(g.owned, 1);
    std::vector<CellWeights<3>> w;
    particle_cell_weights(p, g, eps, m, w);
    compute_voidage(p, w, g, depth, eps);
    double v_grid = 0.0;
    for_each(g.owned, [&](const Index<3>& c) { v_grid += (1.0 - eps[c]) * v_cell; });
    std::printf("[ voidage3d] %s: particle volume %.10e m^3, deposited %.10e m^3, rel. error %.1e\n",
                m == VoidageMethod::Centre ? "centre  " : "trilinear", v_particles, v_grid,
                std::abs(v_grid / v_particles - 1.0));
    EXPECT_NEAR(v_grid / v_particles, 1.0, 1e-12);
  }
}

TEST(ComputeVoidage3d, CentreMethodCountsWholeParticleInItsCell) {
  const Grid<3> g = test_grid();
  ParticleStore<3> p;
  Species s;
  s.diameter = 0.003;
  // Near a corner of cell (2, 1, 2), inside it.
  p.add(0, 0, s, {g.centre(0, 2) + 0.45 * g.h[0], g.centre(1, 1) - 0.45 * g.h[1], g.centre(2, 2) + 0.49 * g.h[2]});
  Field<3> eps(g.owned, 0);
  std::vector<CellWeights<3>> w;
  particle_cell_weights(p, g, eps, VoidageMethod::Centre, w);
  compute_voidage(p, w, g, 0.003, eps);
  const double v_cell = g.h[0] * g.h[1] * g.h[2];
  for_each(g.owned, [&](const Index<3>& c) {
    const bool home = c[0] == 2 && c[1] == 1 && c[2] == 2;
    EXPECT_NEAR(eps[c], home ? 1.0 - s.volume() / v_cell : 1.0, 1e-15) << c[0] << c[1] << c[2];
  });
}

TEST(CellSolidsVelocity3d, UniformVelocityIsReproducedAndEmptyCellsAreZero) {
  const Grid<3> g = test_grid();
  ParticleStore<3> p = random_particles(g, 400, 3);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.vx[i] = 0.7;
    p.vy[i] = -1.3;
    p.vz[i] = 0.2;
  }
  for (VoidageMethod m : {VoidageMethod::Centre, VoidageMethod::Bilinear}) {
    std::array<Field<3>, 3> us;
    std::vector<CellWeights<3>> w;
    particle_cell_weights(p, g, Field<3>(g.owned, 0), m, w);
    cell_solids_velocity<3>(p, w, g, us);
    for_each(g.owned, [&](const Index<3>& c) {
      EXPECT_NEAR(us[0][c], 0.7, 1e-14);
      EXPECT_NEAR(us[1][c], -1.3, 1e-14);
      EXPECT_NEAR(us[2][c], 0.2, 1e-14);
    });
  }
  // One particle at a cell centre: only its cell holds solids.
  ParticleStore<3> one;
  one.add(0, 0, Species{}, g.centre(Index<3>{3, 2, 1}), {1.0, 2.0, 3.0});
  std::array<Field<3>, 3> us;
  std::vector<CellWeights<3>> w;
  particle_cell_weights(one, g, Field<3>(g.owned, 0), VoidageMethod::Bilinear, w);
  cell_solids_velocity<3>(one, w, g, us);
  EXPECT_NEAR(us[2](3, 2, 1), 3.0, 1e-14);
  EXPECT_EQ(us[2](0, 0, 0), 0.0);
  EXPECT_EQ(us[0](4, 3, 2), 0.0);
}

}  // namespace
}  // namespace fluidbed
