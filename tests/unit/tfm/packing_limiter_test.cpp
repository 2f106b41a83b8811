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
#include "core/grid2.hpp"
#include "tfm/packing_limiter.hpp"

namespace fluidbed::tfm {
namespace {

constexpr double kMax = 1.0 - 0.425;  // eps_s bound of the default eps* - max_compaction

double total(const Field2& phi) {
  double s = 0.0;
  for (double x : phi.v) s += x;
  return s;
}

FaceFluxes zero_fluxes(const Grid2& g) { return {Field2(g.nx + 1, g.ny), Field2(g.nx, g.ny + 1)}; }

// Every face keeps its sign and only shrinks.
void expect_only_reduced(const FaceFluxes& before, const FaceFluxes& after) {
  for (const auto& [b, a] : {std::pair{&before.x, &after.x}, std::pair{&before.y, &after.y}}) {
    for (std::size_t k = 0; k < b->size(); ++k) {
      EXPECT_LE(std::abs(a->v[k]), std::abs(b->v[k])) << k;
      EXPECT_GE(a->v[k] * b->v[k], 0.0) << k;
    }
  }
}

TEST(PackingLimiter, CutsConvergingFluxesIntoAFullCell) {
  // 3 x 3 cells, the centre at the bound; solids converge on it from all four sides and leave nowhere.
  const Grid2 g = Grid2::uniform(0.06, 0.06, 3, 3);
  Field2 phi(3, 3, 0.5);
  phi(1, 1) = kMax;
  FaceFluxes f = zero_fluxes(g);
  f.x(1, 1) = 0.3;   // from the west cell, eastward
  f.x(2, 1) = -0.2;  // from the east cell, westward
  f.y(1, 1) = 0.1;   // from below
  f.y(1, 2) = -0.4;  // from above
  const FaceFluxes before = f;
  const double dt = 1e-3;
  const PackingLimitResult r = limit_packing(g, phi, dt, kMax, f);
  const Field2 out = conservative_update(g, phi, f, dt);
  // The full cell takes nothing more; its neighbours keep their solids.
  EXPECT_LE(out(1, 1), kMax);
  EXPECT_NEAR(out(1, 1), kMax, 1e-13);
  EXPECT_NEAR(f.x(1, 1), 0.0, 1e-15);
  EXPECT_NEAR(f.x(2, 1), 0.0, 1e-15);
  EXPECT_NEAR(f.y(1, 1), 0.0, 1e-15);
  EXPECT_NEAR(f.y(1, 2), 0.0, 1e-15);
  EXPECT_EQ(r.sweeps, 2);
  expect_only_reduced(before, f);
  EXPECT_NEAR(total(out), total(phi), 1e-15);
}

TEST(PackingLimiter, PartialInflowLandsExactlyOnTheBound) {
  // A cell below the bound with inflow from two sides and one outflow: the inflows share one factor.
  const Grid2 g = Grid2::uniform(0.06, 0.02, 3, 1);
  Field2 phi(3, 1);
  phi(0, 0) = 0.5;
  phi(1, 0) = 0.55;
  phi(2, 0) = 0.5;
  FaceFluxes f = zero_fluxes(g);
  const double dt = 1e-2;  // dt / dx = 0.5
  f.x(1, 0) = 0.04;   // west -> centre: +0.02 in phi
  f.x(2, 0) = -0.04;  // east -> centre: +0.02 in phi
  const FaceFluxes before = f;
  limit_packing(g, phi, dt, kMax, f);
  const Field2 out = conservative_update(g, phi, f, dt);
  EXPECT_LE(out(1, 0), kMax);
  EXPECT_NEAR(out(1, 0), kMax, 1e-13);
  // Allowed rise 0.025 of 0.04: both faces at 5/8 of their flux.
  EXPECT_NEAR(f.x(1, 0), 0.04 * 0.625, 1e-13);
  EXPECT_NEAR(f.x(2, 0), -0.04 * 0.625, 1e-13);
  EXPECT_NEAR(total(out), total(phi), 1e-15);
  expect_only_reduced(before, f);
}

TEST(PackingLimiter, OverFullDonorsAreCutInTurn) {
  // A column of 4 cells, flow downward. The bottom cell is full; cutting its inflow leaves the cell above with
  // its inflow but no outflow, which overfills it, and so on up the column.
  const Grid2 g = Grid2::uniform(0.02, 0.08, 1, 4);
  Field2 phi(1, 4);
  phi(0, 0) = kMax;
  phi(0, 1) = 0.56;
  phi(0, 2) = 0.57;
  phi(0, 3) = 0.3;
  FaceFluxes f = zero_fluxes(g);
  const double dt = 1e-2;
  for (int j = 1; j < 4; ++j) f.y(0, j) = -0.05;  // 0.025 in phi per face and step
  const FaceFluxes before = f;
  const PackingLimitResult r = limit_packing(g, phi, dt, kMax, f);
  const Field2 out = conservative_update(g, phi, f, dt);
  for (int j = 0; j < 4; ++j) EXPECT_LE(out(0, j), kMax) << j;
  EXPECT_NEAR(out(0, 0), kMax, 1e-13);
  EXPECT_NEAR(out(0, 1), kMax, 1e-13);
  EXPECT_NEAR(out(0, 2), kMax, 1e-13);
  EXPECT_NEAR(f.y(0, 1), 0.0, 1e-15);
  EXPECT_NEAR(f.y(0, 2), -0.015 / (dt / 0.02), 1e-12);  // cell 1 may take 0.015
  EXPECT_NEAR(f.y(0, 3), -0.02 / (dt / 0.02), 1e-12);   // cell 2 may take 0.02 (it passes 0.015 on)
  EXPECT_EQ(r.faces_limited, 3);
  EXPECT_NEAR(total(out), total(phi), 1e-15);
  expect_only_reduced(before, f);
}

TEST(PackingLimiter, CellAboveTheBoundMayNotGrowButMayShrink) {
  const Grid2 g = Grid2::uniform(0.04, 0.02, 2, 1);
  Field2 phi(2, 1);
  phi(0, 0) = 0.5;
  phi(1, 0) = 0.6;  // above the bound already
  FaceFluxes f = zero_fluxes(g);
  f.x(1, 0) = 0.01;  // into the over-full cell
  limit_packing(g, phi, 1e-2, kMax, f);
  EXPECT_NEAR(f.x(1, 0), 0.0, 1e-15);
  f.x(1, 0) = -0.01;  // out of it: untouched
  limit_packing(g, phi, 1e-2, kMax, f);
  EXPECT_EQ(f.x(1, 0), -0.01);
}

TEST(PackingLimiter, MixtureFluxOfEveryFaceIsKept) {
  const Grid2 g = Grid2::uniform(0.06, 0.06, 3, 3);
  Field2 phi(3, 3, 0.55);
  phi(1, 1) = kMax;
  FaceFluxes fs = zero_fluxes(g), fg = zero_fluxes(g);
  fs.x(1, 1) = 0.3;
  fs.x(2, 1) = -0.2;
  fs.y(1, 2) = -0.4;
  fs.y(1, 1) = -0.1;  // outflow from the centre downward
  fg.x(1, 1) = -0.3;
  fg.x(2, 1) = 0.25;
  fg.y(1, 2) = 0.4;
  fg.y(1, 1) = 0.2;
  const FaceFluxes s0 = fs, g0 = fg;
  limit_packing(g, phi, 1e-2, kMax, fs);
  transfer_to_gas(s0, fs, fg);
  for (std::size_t k = 0; k < fs.x.size(); ++k) EXPECT_NEAR(fs.x.v[k] + fg.x.v[k], s0.x.v[k] + g0.x.v[k], 1e-15);
  for (std::size_t k = 0; k < fs.y.size(); ++k) EXPECT_NEAR(fs.y.v[k] + fg.y.v[k], s0.y.v[k] + g0.y.v[k], 1e-15);
  // Something was cut, and the gas took it over on the same face in the same direction.
  EXPECT_LT(std::abs(fs.y(1, 2)), 0.4);
  EXPECT_LT(fg.y(1, 2), 0.4);
}

// The flux field mirrored in x and y: cell (i, j) -> (nx-1-i, ny-1-j), flux signs reversed.
FaceFluxes mirrored(const Grid2& g, const FaceFluxes& f) {
  FaceFluxes m = zero_fluxes(g);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i <= g.nx; ++i) m.x(g.nx - i, g.ny - 1 - j) = -f.x(i, j);
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) m.y(g.nx - 1 - i, g.ny - j) = -f.y(i, j);
  return m;
}

TEST(PackingLimiter, ResultDoesNotDependOnTheCellOrder) {
  // A bed near the bound with a pseudo-random flux field, limited as it is and point-mirrored (which reverses
  // the order the cells are met in, relative to the flow): the limited fluxes must be mirror images to the last
  // bit. Each cell's arithmetic is the same in both (negation and the commuted sums are exact), so only an
  // order-dependent (sequential) sweep could make them differ.
  const Grid2 g = Grid2::uniform(0.08, 0.1, 8, 10);
  Field2 phi(8, 10), phi_m(8, 10);
  FaceFluxes f = zero_fluxes(g);
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
  for (double& x : f.x.v) x = 0.2 * (uniform() - 0.5);
  for (double& x : f.y.v) x = 0.2 * (uniform() - 0.6);
  for (int j = 0; j < 10; ++j) f.x(0, j) = f.x(8, j) = 0.0;  // closed box
  for (int i = 0; i < 8; ++i) f.y(i, 0) = f.y(i, 10) = 0.0;
  FaceFluxes f_m = mirrored(g, f);
  const double dt = 1e-2;
  const PackingLimitResult r = limit_packing(g, phi, dt, kMax, f);
  const PackingLimitResult r_m = limit_packing(g, phi_m, dt, kMax, f_m);
  EXPECT_GT(r.sweeps, 2);  // cuts cascade through donors, so the order could matter
  EXPECT_EQ(r.sweeps, r_m.sweeps);
  EXPECT_EQ(r.faces_limited, r_m.faces_limited);
  const FaceFluxes back = mirrored(g, f_m);
  double diff = 0.0;
  for (std::size_t k = 0; k < f.x.size(); ++k) diff = std::max(diff, std::abs(back.x.v[k] - f.x.v[k]));
  for (std::size_t k = 0; k < f.y.size(); ++k) diff = std::max(diff, std::abs(back.y.v[k] - f.y.v[k]));
  EXPECT_EQ(diff, 0.0);
  const Field2 out = conservative_update(g, phi, f, dt);
  for (double x : out.v) EXPECT_LE(x, kMax);
  std::printf("order independence: %d sweeps, %d face cuts; exact 0, computed largest face difference %.3g\n",
              r.sweeps, r.faces_limited, diff);
}

TEST(PackingLimiter, FailsWhenOutOfSweeps) {
  // Flow to the right into a full last cell: the first sweep cuts the last face, which overfills its donor, so
  // one sweep cannot settle it.
  const Grid2 g = Grid2::uniform(0.06, 0.02, 3, 1);
  Field2 phi(3, 1);
  phi(0, 0) = 0.5;
  phi(1, 0) = 0.57;
  phi(2, 0) = kMax;
  FaceFluxes f = zero_fluxes(g);
  f.x(1, 0) = 0.02;
  f.x(2, 0) = 0.02;
  FaceFluxes copy = f;
  EXPECT_THROW(limit_packing(g, phi, 1e-2, kMax, copy, 1), Error);
  EXPECT_NO_THROW(limit_packing(g, phi, 1e-2, kMax, f));
  const Field2 out = conservative_update(g, phi, f, 1e-2);
  for (int i = 0; i < 3; ++i) EXPECT_LE(out(i, 0), kMax) << i;
}

}  // namespace
}  // namespace fluidbed::tfm
