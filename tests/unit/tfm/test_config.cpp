// TfmConfig validation: every bad setting is an input error (exit code 2) that names the setting.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "core/error.hpp"
#include "tfm/tfm_config.hpp"

namespace fluidbed::tfm {
namespace {

void expect_rejected(const std::function<void(TfmConfig&)>& spoil, const std::string& key) {
  TfmConfig c;
  spoil(c);
  try {
    validate(c);
    ADD_FAILURE() << "accepted a bad " << key;
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(TfmConfig, PaperDefaultsAreValid) {
  const TfmConfig c;
  EXPECT_NO_THROW(validate(c));
  // Table 1, TFM column.
  EXPECT_DOUBLE_EQ(c.d_p, 0.004);
  EXPECT_DOUBLE_EQ(c.rho_s, 2700.0);
  EXPECT_DOUBLE_EQ(c.eps_initial, 0.431);
  EXPECT_DOUBLE_EQ(c.eps_star, 0.43);
  EXPECT_DOUBLE_EQ(c.phi_deg, 40.0);
  EXPECT_DOUBLE_EQ(c.cell_size, 0.02);
  EXPECT_DOUBLE_EQ(c.packed_height, 0.54);
  ASSERT_EQ(c.boundary.jets.size(), 1u);
  EXPECT_DOUBLE_EQ(c.boundary.jets[0].velocity, 30.0);
  EXPECT_DOUBLE_EQ(c.boundary.jets[0].t_end, 0.4);
  EXPECT_DOUBLE_EQ(c.boundary.inlet_velocity, 1.8);
  // Packing limiter: by default just below where the rheology's solids pressure carries the bed.
  EXPECT_FALSE(c.max_compaction.has_value());
  EXPECT_DOUBLE_EQ(packing_allowance(c), 0.015);
  TfmConfig eq20 = c;
  eq20.rheology = SolidsRheology::Inviscid;
  EXPECT_DOUBLE_EQ(packing_allowance(eq20), 0.03);
  eq20.max_compaction = 0.005;
  EXPECT_DOUBLE_EQ(packing_allowance(eq20), 0.005);
}

TEST(TfmConfig, BadSettingsAreNamed) {
  expect_rejected([](TfmConfig& c) { c.cell_size = 0.03; }, "cell_size");
  expect_rejected([](TfmConfig& c) { c.eps_initial = 0.4; }, "eps_initial");
  expect_rejected([](TfmConfig& c) { c.e = 1.5; }, "e must");
  expect_rejected([](TfmConfig& c) { c.cfl = 0.0; }, "cfl");
  expect_rejected([](TfmConfig& c) { c.packed_height = 2.0; }, "packed_height");
  expect_rejected([](TfmConfig& c) { c.rho_s = 1.0; }, "rho_s");
  expect_rejected([](TfmConfig& c) { c.boundary.jets[0].width = 0.0; }, "jet");
  expect_rejected([](TfmConfig& c) { c.max_compaction = -0.001; }, "max_compaction");
  expect_rejected([](TfmConfig& c) { c.max_compaction = c.eps_star; }, "max_compaction");
  expect_rejected(
      [](TfmConfig& c) {
        c.boundary.top = TopBoundary::Wall;
        c.boundary.lid_velocity = 1.0;
      },
      "lid_velocity");
}

}  // namespace
}  // namespace fluidbed::tfm
