// Case files of 3D beds (issue 12): case.dimension, domain.depth, three gravity components, grid.cell_depth and
// jets as regions of the bottom face; and 2D cases refusing the keys of a depth.
#include <gtest/gtest.h>

#include <string>

#include "config/case_check.hpp"
#include "config/case_loader.hpp"
#include "unit/case/case_errors.hpp"

namespace fluidbed {
namespace {

// A 3D slab 0.2 x 0.4 x 0.04 m on 0.01 m cells with `extra` keys.
std::string slab(const std::string& extra = "") {
  return "case.name = \"s\"\ncase.dimension = 3\nsettle.enabled = false\nparticles.count = 1000\n"
         "domain.width = 0.2\ndomain.height = 0.4\ndomain.depth = 0.04\ngrid.cell_width = 0.01\n" + extra;
}
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(Case3d, DomainGridAndGravity) {
  const CaseConfig c = load_case_text(slab("domain.gravity = [0.0, -9.81, 0.5]\n"), "t.toml").config;
  EXPECT_EQ(c.domain.dimension, 3);
  EXPECT_DOUBLE_EQ(c.domain.depth, 0.04);
  EXPECT_DOUBLE_EQ(c.domain.gravity.z, 0.5);
  EXPECT_EQ(c.grid.dimension, 3);
  EXPECT_EQ(c.grid.nx, 20);
  EXPECT_EQ(c.grid.ny, 40);
  EXPECT_EQ(c.grid.nz, 4);  // cell_depth defaults to cell_width
  EXPECT_DOUBLE_EQ(c.grid.dz, 0.01);
  EXPECT_EQ(c.grid.cells(), 3200u);
  const Grid<3> g = c.grid.grid_of<3>();
  EXPECT_EQ(g.n(2), 4);
  EXPECT_DOUBLE_EQ(g.h[2], 0.01);
  EXPECT_EQ(g.owned.hi[1], 40);
  EXPECT_DOUBLE_EQ(c.coupling.depth, 0.04);  // the per-depth columns divide by the domain's depth
  // A slab one cell deep (a bed between front and back walls a few particles apart).
  const CaseConfig thin = load_case_text(slab("grid.cell_depth = 0.04\n"), "t.toml").config;
  EXPECT_EQ(thin.grid.nz, 1);
  const std::string text = describe_case(c);
  EXPECT_TRUE(contains(text, "0.2 x 0.4 x 0.04 m (width x height x depth, front and back walls), gravity (0, -9.81, 0.5)")) << text;
  EXPECT_TRUE(contains(text, "20 x 40 x 4 cells of 0.01 x 0.01 x 0.01 m")) << text;
  EXPECT_TRUE(contains(text, "front and back (particles)")) << text;
}

TEST(Case3d, JetsAreRegionsOfTheBottomFace) {
  const CaseConfig c = load_case_text(
      slab("inlet.jet = [{centre = 0.1, width = 0.02}, {shape = \"rectangle\", centre = 0.05, width = 0.02, "
           "centre_z = 0.01, depth = 0.02}, {shape = \"disc\", centre = 0.15, centre_z = 0.02, diameter = 0.03}]\n"),
      "t.toml").config;
  const auto& jets = c.gas.boundary.jets;
  ASSERT_EQ(jets.size(), 3u);
  EXPECT_EQ(jets[0].shape, InletShape::Slot);
  EXPECT_DOUBLE_EQ(jets[0].depth, 0.04);  // a slot spans the depth
  EXPECT_EQ(jets[1].shape, InletShape::Rectangle);
  EXPECT_DOUBLE_EQ(jets[1].z_centre, 0.01);
  EXPECT_DOUBLE_EQ(jets[1].depth, 0.02);
  EXPECT_EQ(jets[2].shape, InletShape::Disc);
  EXPECT_DOUBLE_EQ(jets[2].width, 0.03);  // the diameter
  const std::string text = describe_case(c);
  EXPECT_TRUE(contains(text, "a disc of diameter 0.03 m centred at (x, z) = (0.15, 0.02) m")) << text;
  EXPECT_TRUE(contains(text, "a rectangle x in [0.04")) << text;
  EXPECT_TRUE(contains(text, "z in [0, 0.02] m")) << text;
  EXPECT_TRUE(contains(text, "across the whole depth")) << text;
}

TEST(Case3d, RefusesWhatA3dBedCannotBe) {
  EXPECT_TRUE(contains(error_of("case.name = \"s\"\ncase.dimension = 3\n"), "domain.depth"));
  EXPECT_TRUE(contains(error_of(slab("domain.gravity = [0.0, -9.81]\n")), "three components"));
  EXPECT_TRUE(contains(error_of(slab("grid.cell_depth = 0.03\n")), "does not divide the domain depth"));
  EXPECT_TRUE(contains(error_of(slab("coupling.depth = 0.004\n")), "coupling.depth"));
  // The two-fluid model runs in 3D (issue 13) on cubic cells.
  const std::string tfm = "case.name = \"s\"\ncase.dimension = 3\ncase.model = \"tfm\"\ntfm.packed_height = 0.2\n"
                          "domain.width = 0.2\ndomain.height = 0.4\ndomain.depth = 0.04\ngrid.cell_width = 0.01\n";
  EXPECT_EQ(load_case_text(tfm, "t.toml").config.tfm.domain.dimension, 3);
  EXPECT_TRUE(contains(error_of(tfm + "grid.cell_depth = 0.02\n"), "cubic cells"));
  EXPECT_TRUE(contains(error_of(slab("case.dimension = 4\n")), "case.dimension"));
  const std::string disc = "inlet.jet = [{shape = \"disc\", centre = 0.1, centre_z = 0.035, diameter = 0.02}]\n";
  EXPECT_TRUE(contains(error_of(slab(disc)), "inlet.jet[0].centre_z: the jet's z range"));
  EXPECT_TRUE(contains(error_of(slab("inlet.jet = [{shape = \"disc\", width = 0.02}]\n")), "diameter"));
  EXPECT_TRUE(contains(error_of(slab("inlet.jet = [{diameter = 0.02}]\n")), "only a disc jet has a diameter"));
  EXPECT_TRUE(contains(error_of(slab("inlet.jet = [{centre_z = 0.02}]\n")), "a slot spans the whole depth"));
  EXPECT_TRUE(contains(error_of(slab("inlet.jet = [{shape = \"rectangle\", depth = 0.005}]\n")), "shallower"));
  EXPECT_TRUE(contains(error_of(slab("inlet.jet = [{shape = \"cone\"}]\n")), "inlet.jet[0].shape"));
  // Placement counts the sites across the depth too: 0.2 / 0.0044 x 0.4 / 0.0044 x 0.04 / 0.0044 = 45 x 90 x 9.
  EXPECT_NO_THROW(load_case_text(slab(), "t.toml", {"particles.count=36450"}));
  EXPECT_TRUE(contains(error_of(slab(), {"particles.count=36451"}), "0.2 x 0.4 x 0.04 m placement region"));
}

TEST(Case3d, TwoDimensionalCasesRefuseTheKeysOfADepth) {
  const std::string base = "case.name = \"x\"\nsettle.enabled = false\nparticles.count = 1000\n";
  EXPECT_TRUE(contains(error_of(base + "domain.depth = 0.1\n"), "a 2D case (case.dimension = 2) has no depth"));
  EXPECT_TRUE(contains(error_of(base + "grid.cell_depth = 0.02\n"), "grid.cell_depth"));
  EXPECT_TRUE(contains(error_of(base + "domain.gravity = [0.0, -9.81, 1.0]\n"), "z = 1 m/s^2 in a 2D case"));
  EXPECT_TRUE(contains(error_of(base + "inlet.jet = [{shape = \"disc\"}]\n"), "inlet.jet[0].shape"));
  // Three components with z = 0 are the 2D gravity; the 2D grid is as before.
  const CaseConfig c = load_case_text(base + "domain.gravity = [0.0, -9.81, 0.0]\n", "t.toml").config;
  EXPECT_EQ(c.domain.dimension, 2);
  EXPECT_EQ(c.grid.nz, 1);
  EXPECT_EQ(c.grid.dz, 0.0);
  EXPECT_EQ(c.grid.cells(), 1500u);
  EXPECT_EQ(c.grid.grid_of<2>().n(0), 30);
}

}  // namespace
}  // namespace fluidbed
