// Case files of earlier versions and DEM-alone boxes without a grid (issue 28, item 5).
#include <gtest/gtest.h>

#include <string>

#include "config/case_loader.hpp"
#include "unit/case/case_errors.hpp"

namespace fluidbed {
namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
const std::string kDem = "case.name = \"x\"\nsettle.enabled = false\nparticles.count = 20\n";

TEST(CaseOldKeys, RenamedKeysNameWhatReplacedThem) {
  const std::string top = error_of(kDem + "domain.top_wall = true\n");
  EXPECT_TRUE(contains(top, "domain.top_wall is now domain.particle_top: \"wall\" for top_wall = true")) << top;
  EXPECT_FALSE(contains(top, "unknown key")) << top;
  const std::string noise = error_of("case.name = \"x\"\ncase.model = \"tfm\"\ntfm.inlet_noise = 0.1\n");
  EXPECT_TRUE(contains(noise, "tfm.inlet_noise is now inlet.noise")) << noise;
  // Still read under its old name: gravity of the discrete model.
  EXPECT_DOUBLE_EQ(load_case_text(kDem + "dem.gravity = [0.0, -5.0]\n", "t.toml").config.domain.gravity.y, -5.0);
}

TEST(CaseOldKeys, DemAloneInASmallBoxNeedsNoGrid) {
  // 0.03 m wide: the 0.02 m default cell would leave one cell and no whole number of them.
  const CaseConfig c = load_case_text(kDem + "gas.enabled = false\ndomain.width = 0.03\ndomain.height = 0.05\n",
                                      "t.toml").config;
  EXPECT_EQ(c.grid.nx, 2);
  EXPECT_DOUBLE_EQ(c.grid.dx, 0.015);
  EXPECT_EQ(c.grid.ny, 3);  // 0.05 / 0.02 = 2.5, rounded: three cells of 0.0167 m
  // The paper's box keeps the paper's cells; a grid given with the gas off is checked as given.
  const CaseConfig paper = load_case_text(kDem + "gas.enabled = false\n", "t.toml").config;
  EXPECT_DOUBLE_EQ(paper.grid.dx, 0.02);
  EXPECT_EQ(paper.grid.nx, 30);
  const std::string e = error_of(kDem + "gas.enabled = false\ngrid.cell_width = 0.6\ngrid.cell_height = 0.02\n");
  EXPECT_TRUE(contains(e, "the grid needs (the gas is off")) << e;
  // With the gas on, the paper's default cell and the gas's rule.
  const std::string g = error_of(kDem + "domain.width = 0.03\ndomain.height = 0.05\n");
  EXPECT_TRUE(contains(g, "grid.cell_width: 0.02 m does not divide the domain width 0.03 m")) << g;
}

}  // namespace
}  // namespace fluidbed
