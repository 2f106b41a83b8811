// The dimension-generic core: boxes, grids, ghost-layered fields and the serial communicator.
#include <gtest/gtest.h>

#include "parallel/comm.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/vec.hpp"

namespace fluidbed {
namespace {

TEST(Vec, CrossProductsAgreeBetweenDimensions) {
  // The 2D cross product is the z component of the 3D one, and (0,0,w) x a its in-plane part.
  const Vec2 a{0.3, -1.2}, b{2.0, 0.7};
  const Vec3 c = cross(Vec3{a.x, a.y, 0.0}, Vec3{b.x, b.y, 0.0});
  EXPECT_EQ(cross(a, b), c.z);
  EXPECT_EQ(c.x, 0.0);
  const Vec3 w = cross(Vec3{0.0, 0.0, 1.5}, Vec3{a.x, a.y, 0.0});
  const Vec2 w2 = cross(1.5, a);
  EXPECT_EQ(w2.x, w.x);
  EXPECT_EQ(w2.y, w.y);
  Vec3 v{1, 2, 3};
  v[2] = 5;
  EXPECT_EQ(v.z, 5);
  EXPECT_EQ(unit<3>(1), (Vec3{0, 1, 0}));
}

TEST(IndexBox, CountsFacesGhostsAndSides) {
  const IndexBox<3> cells{{0, 0, 0}, {4, 3, 2}};
  EXPECT_EQ(cells.count(), 24u);
  EXPECT_EQ(cells.faces(1).count(), 4u * 4u * 2u);
  EXPECT_EQ(cells.grown(1).count(), 6u * 5u * 4u);
  EXPECT_EQ(cells.outside(0, true).lo[0], 4);
  EXPECT_EQ(cells.outside(0, false).lo[0], -1);
  EXPECT_EQ(cells.inside(2, true).lo[2], 1);
  std::size_t n = 0;
  Index<3> last{};
  for_each(cells, [&](const Index<3>& c) {
    ++n;
    last = c;
  });
  EXPECT_EQ(n, 24u);
  EXPECT_EQ(last, (Index<3>{3, 2, 1}));
}

TEST(Field, GhostEntriesAreAddressableAndAxisZeroIsFastest) {
  Field<2> f(IndexBox<2>{{0, 0}, {3, 2}}, 1, 0.0);
  EXPECT_EQ(f.data().size(), 5u * 4u);
  f(-1, -1) = 1.0;
  f(3, 2) = 2.0;
  EXPECT_EQ(f.data().front(), 1.0);
  EXPECT_EQ(f.data().back(), 2.0);
  EXPECT_EQ(f.index({1, 0}) - f.index({0, 0}), 1u);
  EXPECT_EQ(f.stride(1), 5u);
  f.fill(f.box().outside(1, false), 7.0);  // the bottom ghost row
  EXPECT_EQ(f(0, -1), 7.0);
  EXPECT_EQ(f(0, 0), 0.0);
  std::vector<double> in{1, 2, 3, 4, 5, 6};
  f.set_interior(in);
  EXPECT_EQ(f(2, 1), 6.0);
  EXPECT_EQ(f.interior(), in);
}

TEST(Grid, SubBlockKnowsItsPhysicalSides) {
  auto g = Grid<3>::uniform({0.6, 1.0, 0.1}, {30, 50, 5});
  EXPECT_DOUBLE_EQ(g.cell_measure(), 0.02 * 0.02 * 0.02);
  EXPECT_EQ(g.cell(Vec3{0.6, 0.5, 0.0}), (Index<3>{29, 25, 0}));
  g.owned = IndexBox<3>{{0, 25, 0}, {30, 50, 5}};  // the top half, as one of two ranks would own it
  EXPECT_FALSE(g.at_domain_side(1, false));
  EXPECT_TRUE(g.at_domain_side(1, true));
  FaceFields<3> u(g.owned, g.ghost);
  EXPECT_EQ(u[1].box().hi[1], 51);
  EXPECT_EQ(u[1](0, 24, 0), 0.0);  // the ghost row below the block: the neighbour rank's faces
}

TEST(Comm, SerialReductionsAreTheLocalValues) {
  const SerialComm comm;
  EXPECT_EQ(comm.size(), 1);
  EXPECT_EQ(comm.sum(2.5), 2.5);
  EXPECT_EQ(comm.max(-1.0), -1.0);
}

}  // namespace
}  // namespace fluidbed
