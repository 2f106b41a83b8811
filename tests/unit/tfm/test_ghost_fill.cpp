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

}  // namespace
}  // namespace fluidbed::tfm
