// Packing limiter (src/tfm/packing_limiter.hpp) on tiny grids: fluxes into a cell at the bound are cut, the
// total is conserved to rounding, the mixture flux of every face is kept, over-full donors are cut in turn, and
// a limiter that runs out of sweeps fails loudly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>

#include "core/error.hpp"
#include "tfm/packing_limiter.hpp"

namespace fluidbed::tfm {
namespace {

constexpr double kMax = 1.0 - 0.425;  // eps_s bound of the default eps* - max_compaction

Grid<2> grid(double width, double height, int nx, int ny) { return Grid<2>::uniform({width, height}, {nx, ny}, kGhost); }
Field<2> cells(const Grid<2>& g, double value = 0.0) { return Field<2>(g.domain, kGhost, value); }

double total(const Field<2>& phi) {
  double s = 0.0;
  for (double x : phi.interior()) s += x;
  return s;
}

FaceFluxes<2> zero_fluxes(const Grid<2>& g) { return FaceFluxes<2>(g.domain, kGhost); }

// Every face keeps its sign and only shrinks.
void expect_only_reduced(const FaceFluxes<2>& before, const FaceFluxes<2>& after) {
  for (int d = 0; d < 2; ++d) {
    const std::vector<double> b = before[d].interior(), a = after[d].interior();
    for (std::size_t k = 0; k < b.size(); ++k) {
      EXPECT_LE(std::abs(a[k]), std::abs(b[k])) << k;
      EXPECT_GE(a[k] * b[k], 0.0) << k;
    }
  }
}

TEST(PackingLimiter, CutsConvergingFluxesIntoAFullCell) {
  // 3 x 3 cells, the centre at the bound; solids converge on it from all four sides and leave nowhere.
  const Grid<2> g = grid(0.06, 0.06, 3, 3);
  Field<2> phi = cells(g, 0.5);
  phi(1, 1) = kMax;
  FaceFluxes<2> f = zero_fluxes(g);
  f[0](1, 1) = 0.3;   // from the west cell, eastward
  f[0](2, 1) = -0.2;  // from the east cell, westward
  f[1](1, 1) = 0.1;   // from below
  f[1](1, 2) = -0.4;  // from above
  const FaceFluxes<2> before = f;
  const double dt = 1e-3;
  const PackingLimitResult r = limit_packing(g, phi, dt, kMax, f);
  const Field<2> out = conservative_update(g, phi, f, dt);
  // The full cell takes nothing more; its neighbours keep their solids.
  EXPECT_LE(out(1, 1), kMax);
  EXPECT_NEAR(out(1, 1), kMax, 1e-13);
  EXPECT_NEAR(f[0](1, 1), 0.0, 1e-15);
  EXPECT_NEAR(f[0](2, 1), 0.0, 1e-15);
  EXPECT_NEAR(f[1](1, 1), 0.0, 1e-15);
  EXPECT_NEAR(f[1](1, 2), 0.0, 1e-15);
  EXPECT_EQ(r.sweeps, 2);
  expect_only_reduced(before, f);
  EXPECT_NEAR(total(out), total(phi), 1e-15);
}

TEST(PackingLimiter, PartialInflowLandsExactlyOnTheBound) {
  // A cell below the bound with inflow from two sides and one outflow: the inflows share one factor.
  const Grid<2> g = grid(0.06, 0.02, 3, 1);
  Field<2> phi = cells(g);
  phi(0, 0) = 0.5;
  phi(1, 0) = 0.55;
  phi(2, 0) = 0.5;
  FaceFluxes<2> f = zero_fluxes(g);
  const double dt = 1e-2;  // dt / dx = 0.5
  f[0](1, 0) = 0.04;   // west -> centre: +0.02 in phi
  f[0](2, 0) = -0.04;  // east -> centre: +0.02 in phi
  const FaceFluxes<2> before = f;
  limit_packing(g, phi, dt, kMax, f);
  const Field<2> out = conservative_update(g, phi, f, dt);
  EXPECT_LE(out(1, 0), kMax);
  EXPECT_NEAR(out(1, 0), kMax, 1e-13);
  // Allowed rise 0.025 of 0.04: both faces at 5/8 of their flux.
  EXPECT_NEAR(f[0](1, 0), 0.04 * 0.625, 1e-13);
  EXPECT_NEAR(f[0](2, 0), -0.04 * 0.625, 1e-13);
  EXPECT_NEAR(total(out), total(phi), 1e-15);
  expect_only_reduced(before, f);
}

TEST(PackingLimiter, OverFullDonorsAreCutInTurn) {
  // A column of 4 cells, flow downward. The bottom cell is full; cutting its inflow leaves the cell above with
  // its inflow but no outflow, which overfills it, and so on up the column.
  const Grid<2> g = grid(0.02, 0.08, 1, 4);
  Field<2> phi = cells(g);
  phi(0, 0) = kMax;
  phi(0, 1) = 0.56;
  phi(0, 2) = 0.57;
  phi(0, 3) = 0.3;
  FaceFluxes<2> f = zero_fluxes(g);
  const double dt = 1e-2;
  for (int j = 1; j < 4; ++j) f[1](0, j) = -0.05;  // 0.025 in phi per face and step
  const FaceFluxes<2> before = f;
  const PackingLimitResult r = limit_packing(g, phi, dt, kMax, f);
  const Field<2> out = conservative_update(g, phi, f, dt);
  for (int j = 0; j < 4; ++j) EXPECT_LE(out(0, j), kMax) << j;
  EXPECT_NEAR(out(0, 0), kMax, 1e-13);
  EXPECT_NEAR(out(0, 1), kMax, 1e-13);
  EXPECT_NEAR(out(0, 2), kMax, 1e-13);
  EXPECT_NEAR(f[1](0, 1), 0.0, 1e-15);
  EXPECT_NEAR(f[1](0, 2), -0.015 / (dt / 0.02), 1e-12);  // cell 1 may take 0.015
  EXPECT_NEAR(f[1](0, 3), -0.02 / (dt / 0.02), 1e-12);   // cell 2 may take 0.02 (it passes 0.015 on)
  EXPECT_EQ(r.faces_limited, 3);
  EXPECT_NEAR(total(out), total(phi), 1e-15);
  expect_only_reduced(before, f);
}

TEST(PackingLimiter, CellAboveTheBoundMayNotGrowButMayShrink) {
  const Grid<2> g = grid(0.04, 0.02, 2, 1);
  Field<2> phi = cells(g);
  phi(0, 0) = 0.5;
  phi(1, 0) = 0.6;  // above the bound already
  FaceFluxes<2> f = zero_fluxes(g);
  f[0](1, 0) = 0.01;  // into the over-full cell
  limit_packing(g, phi, 1e-2, kMax, f);
  EXPECT_NEAR(f[0](1, 0), 0.0, 1e-15);
  f[0](1, 0) = -0.01;  // out of it: untouched
  limit_packing(g, phi, 1e-2, kMax, f);
  EXPECT_EQ(f[0](1, 0), -0.01);
}

TEST(PackingLimiter, MixtureFluxOfEveryFaceIsKept) {
  const Grid<2> g = grid(0.06, 0.06, 3, 3);
  Field<2> phi = cells(g, 0.55);
  phi(1, 1) = kMax;
  FaceFluxes<2> fs = zero_fluxes(g), fg = zero_fluxes(g);
  fs[0](1, 1) = 0.3;
  fs[0](2, 1) = -0.2;
  fs[1](1, 2) = -0.4;
  fs[1](1, 1) = -0.1;  // outflow from the centre downward
  fg[0](1, 1) = -0.3;
  fg[0](2, 1) = 0.25;
  fg[1](1, 2) = 0.4;
  fg[1](1, 1) = 0.2;
  const FaceFluxes<2> s0 = fs, g0 = fg;
  limit_packing(g, phi, 1e-2, kMax, fs);
  transfer_to_gas(s0, fs, fg);
  for (int d = 0; d < 2; ++d)
    for_each(fs[d].box(), [&](const Index<2>& k) { EXPECT_NEAR(fs[d][k] + fg[d][k], s0[d][k] + g0[d][k], 1e-15); });
  // Something was cut, and the gas took it over on the same face in the same direction.
  EXPECT_LT(std::abs(fs[1](1, 2)), 0.4);
  EXPECT_LT(fg[1](1, 2), 0.4);
}

// The flux field mirrored in x and y: cell (i, j) -> (nx-1-i, ny-1-j), flux signs reversed.
FaceFluxes<2> mirrored(const Grid<2>& g, const FaceFluxes<2>& f) {
  FaceFluxes<2> m = zero_fluxes(g);
  const int nx = g.n(0), ny = g.n(1);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i) m[0](nx - i, ny - 1 - j) = -f[0](i, j);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < nx; ++i) m[1](nx - 1 - i, ny - j) = -f[1](i, j);
  return m;
}

TEST(PackingLimiter, ResultDoesNotDependOnTheCellOrder) {
  // A bed near the bound with a pseudo-random flux field, limited as it is and point-mirrored (which reverses
  // the order the cells are met in, relative to the flow): the limited fluxes must be mirror images to the last
  // bit. Each cell's arithmetic is the same in both (negation and the commuted sums are exact), so only an
  // order-dependent (sequential) sweep could make them differ.
  const Grid<2> g = grid(0.08, 0.1, 8, 10);
  Field<2> phi = cells(g), phi_m = cells(g);
  FaceFluxes<2> f = zero_fluxes(g);
  std::uint64_t state = 12345;
  auto uniform = [&] {  // splitmix64, so the test is reproducible without <random>'s implementation choices
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 8; ++i) phi(i, j) = kMax - 0.02 * uniform();
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 8; ++i) phi_m(7 - i, 9 - j) = phi(i, j);
  for_each(f[0].box(), [&](const Index<2>& k) { f[0][k] = 0.2 * (uniform() - 0.5); });
  for_each(f[1].box(), [&](const Index<2>& k) { f[1][k] = 0.2 * (uniform() - 0.6); });
  for (int j = 0; j < 10; ++j) f[0](0, j) = f[0](8, j) = 0.0;  // closed box
  for (int i = 0; i < 8; ++i) f[1](i, 0) = f[1](i, 10) = 0.0;
  FaceFluxes<2> f_m = mirrored(g, f);
  const double dt = 1e-2;
  const PackingLimitResult r = limit_packing(g, phi, dt, kMax, f);
  const PackingLimitResult r_m = limit_packing(g, phi_m, dt, kMax, f_m);
  EXPECT_GT(r.sweeps, 2);  // cuts cascade through donors, so the order could matter
  EXPECT_EQ(r.sweeps, r_m.sweeps);
  EXPECT_EQ(r.faces_limited, r_m.faces_limited);
  const FaceFluxes<2> back = mirrored(g, f_m);
  double diff = 0.0;
  for (int d = 0; d < 2; ++d)
    for_each(f[d].box(), [&](const Index<2>& k) { diff = std::max(diff, std::abs(back[d][k] - f[d][k])); });
  EXPECT_EQ(diff, 0.0);
  const Field<2> out = conservative_update(g, phi, f, dt);
  for (double x : out.interior()) EXPECT_LE(x, kMax);
  std::printf("order independence: %d sweeps, %d face cuts; exact 0, computed largest face difference %.3g\n",
              r.sweeps, r.faces_limited, diff);
}

TEST(PackingLimiter, OutflowsOfAnEmptyingCellAreCutAtZero) {
  // 3 x 3 cells; the centre holds 1e-6 of solids and the fluxes would take 4e-6 out through its four faces
  // (an undershoot of a high-order correction): its outflows are cut alike, it lands on zero (its voidage on 1
  // exactly), its neighbours receive what it had, and the total is kept.
  const Grid<2> g = grid(0.06, 0.06, 3, 3);
  Field<2> phi = cells(g, 0.3);
  phi(1, 1) = 1e-6;
  FaceFluxes<2> f = zero_fluxes(g);
  const double dt = 1e-3, q = 1e-6 * 0.02 / dt;  // each face alone would empty the centre
  f[0](1, 1) = -q;  // westward out of the centre
  f[0](2, 1) = q;   // eastward out of it
  f[1](1, 1) = -q;
  f[1](1, 2) = q;
  f[0](0, 1) = 0.0;
  const FaceFluxes<2> before = f;
  const double sum0 = total(phi);
  const PackingLimitResult r = limit_packing(g, phi, dt, kMax, f);
  const Field<2> out = conservative_update(g, phi, f, dt);
  EXPECT_EQ(1.0 - out(1, 1), 1.0);
  EXPECT_NEAR(out(1, 1), 0.0, 1e-18);
  EXPECT_NEAR(f[0](2, 1), 0.25 * q, 1e-12 * q);  // the four outflows share the content equally
  EXPECT_NEAR(f[1](1, 1), -0.25 * q, 1e-12 * q);
  EXPECT_NEAR(total(out), sum0, 1e-15);
  expect_only_reduced(before, f);
  EXPECT_GE(r.sweeps, 2);
  // A cell that stays non-negative is not touched: the same fluxes, the same bits.
  FaceFluxes<2> g2 = zero_fluxes(g);
  g2[0](2, 1) = 0.1 * q;
  const FaceFluxes<2> kept = g2;
  limit_packing(g, phi, dt, kMax, g2);
  EXPECT_EQ(g2[0](2, 1), kept[0](2, 1));
}

TEST(PackingLimiter, FailsWhenOutOfSweeps) {
  // Flow to the right into a full last cell: the first sweep cuts the last face, which overfills its donor, so
  // one sweep cannot settle it.
  const Grid<2> g = grid(0.06, 0.02, 3, 1);
  Field<2> phi = cells(g);
  phi(0, 0) = 0.5;
  phi(1, 0) = 0.57;
  phi(2, 0) = kMax;
  FaceFluxes<2> f = zero_fluxes(g);
  f[0](1, 0) = 0.02;
  f[0](2, 0) = 0.02;
  FaceFluxes<2> copy = f;
  EXPECT_THROW(limit_packing(g, phi, 1e-2, kMax, copy, 1), Error);
  EXPECT_NO_THROW(limit_packing(g, phi, 1e-2, kMax, f));
  const Field<2> out = conservative_update(g, phi, f, 1e-2);
  for (int i = 0; i < 3; ++i) EXPECT_LE(out(i, 0), kMax) << i;
}

TEST(PackingLimiter, PeriodicFaceCutsLikeItsImage) {
  // 4 x 1 cells periodic in x: the first cell is at the bound and receives solids through face 0 from the last
  // cell (westward flow across the periodic plane) and through face 1 from its east neighbour. Face 4 is face 0:
  // it holds the same flux on entry and must take the same cut, and the total must be kept.
  Grid<2> g = grid(0.08, 0.02, 4, 1);
  g.periodic = {true, false};
  Field<2> phi = cells(g, 0.3);
  phi(0, 0) = kMax;
  FaceFluxes<2> f = zero_fluxes(g);
  f[0](0, 0) = 0.25;  // eastward across the plane: from cell 3 into cell 0
  f[0](4, 0) = 0.25;  // the same face seen from cell 3
  f[0](1, 0) = -0.1;  // westward from cell 1 into cell 0
  const double dt = 1e-3;
  const double before = total(phi);
  limit_packing(g, phi, dt, kMax, f);
  const Field<2> out = conservative_update(g, phi, f, dt);
  EXPECT_EQ(f[0](0, 0), f[0](4, 0));
  EXPECT_NEAR(f[0](0, 0), 0.0, 1e-15);
  EXPECT_NEAR(f[0](1, 0), 0.0, 1e-15);
  EXPECT_LE(out(0, 0), kMax);
  EXPECT_NEAR(total(out), before, 1e-15);
  // Without the periodic axis face 0 is a wall face: nothing enters there to be cut, and cell 3 keeps its outflow
  // through face 4 (the boundary's business, not the limiter's).
  Grid<2> walled = grid(0.08, 0.02, 4, 1);
  FaceFluxes<2> w = zero_fluxes(walled);
  w[0](4, 0) = 0.25;
  limit_packing(walled, phi, dt, kMax, w);
  EXPECT_EQ(w[0](4, 0), 0.25);
}

}  // namespace
}  // namespace fluidbed::tfm
