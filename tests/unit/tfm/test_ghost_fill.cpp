// Ghost layers of the two-fluid model's fields (src/tfm/tvd_convection.hpp): zero gradient repeats the boundary
// cell in every layer, edges and corners included, and periodic wrap copies the cell one period away; these stand
// in for the clamped indices the stencils no longer use, so they must be exact copies.
#include <gtest/gtest.h>

#include <algorithm>

#include "tfm/tvd_convection.hpp"

namespace fluidbed::tfm {
namespace {

template <int Dim>
double value(const Index<Dim>& c) {
  double v = 0.0, scale = 1.0;
  for (int a = 0; a < Dim; ++a, scale *= 100.0) v += scale * (c[a] + 1);
  return v;
}

template <int Dim>
void expect_ghosts(const std::array<bool, Dim>& periodic) {
  IndexBox<Dim> box;
  for (int a = 0; a < Dim; ++a) box.hi[a] = 3 + a;  // 3 x 4 (x 5) cells
  Field<Dim> f(box, kGhost, -1.0);
  for_each(box, [&](const Index<Dim>& c) { f[c] = value<Dim>(c); });
  fill_cell_ghosts(f, periodic);
  int checked = 0;
  for_each(f.allocated(), [&](const Index<Dim>& c) {
    Index<Dim> src = c;
    for (int a = 0; a < Dim; ++a) {
      const int n = box.extent(a);
      src[a] = periodic[a] ? ((c[a] % n) + n) % n : std::clamp(c[a], 0, n - 1);
    }
    EXPECT_EQ(f[c], value<Dim>(src));
    ++checked;
  });
  EXPECT_EQ(checked, static_cast<int>(f.allocated().count()));
}

TEST(GhostFill, ZeroGradientRepeatsTheBoundaryCellIn2d) { expect_ghosts<2>({false, false}); }
TEST(GhostFill, PeriodicAndZeroGradientMixIn2d) { expect_ghosts<2>({true, false}); }
TEST(GhostFill, ZeroGradientRepeatsTheBoundaryCellIn3d) { expect_ghosts<3>({false, false, false}); }
TEST(GhostFill, PeriodicAxesWrapIn3d) { expect_ghosts<3>({true, false, true}); }

// On one process the block fill (fill_block_ghosts: owners first, then walls and periodic images over the whole span
// of the other axes) gives every ghost what fill_cell_ghosts gives, for cell and face fields and every periodic set.
template <int Dim>
void expect_block_fill_is_the_cell_fill(const std::array<bool, Dim>& periodic, int face_axis) {
  IndexBox<Dim> cells;
  for (int a = 0; a < Dim; ++a) cells.hi[a] = 4 + a;
  const IndexBox<Dim> box = face_axis < 0 ? cells : cells.faces(face_axis);
  Field<Dim> f(box, kGhost, -1.0), g(box, kGhost, -2.0);
  for_each(box, [&](const Index<Dim>& c) { f[c] = g[c] = value<Dim>(c); });
  fill_cell_ghosts(f, periodic);
  const IndexBox<Dim> boxes[1] = {box};
  fill_block_ghosts<Dim>(g, box, periodic, serial_comm(), boxes);
  for (std::size_t k = 0; k < f.data().size(); ++k) ASSERT_EQ(f.data()[k], g.data()[k]) << k;
}

TEST(GhostFill, BlockFillIsTheCellFillOnOneProcess) {
  for (bool px : {false, true}) {
    expect_block_fill_is_the_cell_fill<2>({px, false}, -1);
    if (!px) expect_block_fill_is_the_cell_fill<2>({false, false}, 1);
    for (bool pz : {false, true}) {
      expect_block_fill_is_the_cell_fill<3>({px, false, pz}, -1);
      if (!px && !pz) expect_block_fill_is_the_cell_fill<3>({false, false, false}, 2);
    }
  }
}

}  // namespace
}  // namespace fluidbed::tfm
