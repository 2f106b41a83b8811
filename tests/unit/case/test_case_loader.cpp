// The case loader: defaults, overrides, the resolved case and the registry of keys.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "config/case_loader.hpp"
#include "config/case_reader.hpp"
#include "unit/case/case_errors.hpp"

namespace fluidbed {
namespace {

TEST(CaseLoader, DefaultsAreThePapersTable1) {
  const LoadedCase lc = load_case_text("case.name = \"x\"\n", "t.toml");
  const CaseConfig& c = lc.config;
  EXPECT_EQ(c.model, Model::Dem);
  EXPECT_DOUBLE_EQ(c.dem.species[0].diameter, 0.004);
  EXPECT_DOUBLE_EQ(c.dem.species[0].density, 2700.0);
  EXPECT_DOUBLE_EQ(c.dem.stiffness, 800.0);
  EXPECT_DOUBLE_EQ(c.dem.pair_params(0, 0).restitution, 0.9);
  EXPECT_DOUBLE_EQ(c.dem.pair_params(0, 0).friction, 0.3);
  EXPECT_EQ(c.particles.packing.count, 22000);
  EXPECT_EQ(c.grid.nx, 30);
  EXPECT_EQ(c.grid.ny, 50);
  EXPECT_DOUBLE_EQ(c.gas.rho_g, 1.205);
  EXPECT_DOUBLE_EQ(c.gas.mu_g, 1.8e-5);
  EXPECT_DOUBLE_EQ(c.gas.boundary.inlet_velocity, 1.8);
}

TEST(CaseLoader, OverridesUseTheSameChecksAndReachTheResolvedCase) {
  const LoadedCase lc = load_case_text("case.name = \"x\"\n", "t.toml", {"contact.stiffness=1000", "case.model=dem"});
  EXPECT_DOUBLE_EQ(lc.config.dem.stiffness, 1000.0);
  EXPECT_NE(lc.resolved_toml.find("stiffness = 1000"), std::string::npos) << lc.resolved_toml;
  // The resolved case loads back to the same configuration.
  const LoadedCase again = load_case_text(lc.resolved_toml, "resolved.toml");
  EXPECT_DOUBLE_EQ(again.config.dem.stiffness, 1000.0);
  EXPECT_EQ(again.resolved_toml, lc.resolved_toml);
  EXPECT_NE(error_of("case.name = \"x\"\n", {"contact.stiffness=-1"}).find("contact.stiffness: -1 is out of range"),
            std::string::npos);
}

TEST(CaseLoader, UnknownKeysNameTheNearestKnownOne) {
  const std::string e = error_of("case.name = \"x\"\n[gas]\nvicosity = 1e-5\n");
  EXPECT_NE(e.find("t.toml:3:12: unknown key 'gas.vicosity'; did you mean 'gas.viscosity'?"), std::string::npos) << e;
}

TEST(CaseLoader, ArraysOfTablesAndTheTwoFluidModel) {
  const LoadedCase lc = load_case_text(
      "case.name = \"x\"\ncase.model = \"tfm\"\n[tfm]\nrheology = \"inviscid\"\nmax_compaction = 0.01\n"
      "[[inlet.jet]]\ncentre = 0.31\n"
      "[[inlet.jet]]\ncentre = 0.11\nstart = 0.5\nend = 0.6\n",
      "t.toml");
  EXPECT_EQ(lc.config.model, Model::Tfm);
  EXPECT_EQ(lc.config.tfm.rheology, tfm::SolidsRheology::Inviscid);
  EXPECT_DOUBLE_EQ(lc.config.tfm.max_compaction.value_or(-1.0), 0.01);
  // The packing limiter's allowance must leave a positive voidage: [0, eps*).
  EXPECT_NE(error_of("case.name = \"x\"\ncase.model = \"tfm\"\n[tfm]\nmax_compaction = 0.43\n").find("tfm.max_compaction"),
            std::string::npos);
  ASSERT_EQ(lc.config.gas.boundary.jets.size(), 2u);
  EXPECT_DOUBLE_EQ(lc.config.gas.boundary.jets[1].t_start, 0.5);
  EXPECT_DOUBLE_EQ(lc.config.tfm.boundary.jets[1].x_centre, 0.11);
  EXPECT_NE(error_of("case.name = \"x\"\ncase.model = \"tfm\"\n[contact]\nstiffness = 1\n").find("unknown key 'contact.stiffness'"),
            std::string::npos);
}

TEST(CaseLoader, FrictionalModelsAndTheirKeys) {
  const std::string head = "case.name = \"x\"\ncase.model = \"tfm\"\n[tfm]\n";
  const LoadedCase lc = load_case_text(head + "frictional_model = \"srivastava_sundaresan\"\nfrictional_onset = 0.52\n"
                                              "frictional_packing_limit = 0.64\n",
                                       "t.toml");
  EXPECT_EQ(lc.config.tfm.frictional, tfm::FrictionalModel::SrivastavaSundaresan);
  EXPECT_DOUBLE_EQ(lc.config.tfm.friction.eps_s_min, 0.52);
  EXPECT_DOUBLE_EQ(lc.config.tfm.friction.eps_s_max, 0.64);
  EXPECT_EQ(load_case_text(head, "t.toml").config.tfm.frictional, tfm::FrictionalModel::Schaeffer);
  // The constants belong to the Johnson-Jackson pressure; the model to the kinetic theory.
  EXPECT_NE(error_of(head + "frictional_onset = 0.52\n").find("tfm.frictional_onset"), std::string::npos);
  EXPECT_NE(error_of(head + "rheology = \"inviscid\"\nfrictional_model = \"johnson_jackson\"\n")
                .find("tfm.frictional_model"),
            std::string::npos);
  // A packing limit at or below the densest state the limiter allows (1 - (0.43 - 0.015) = 0.585) would diverge.
  EXPECT_NE(error_of(head + "frictional_model = \"johnson_jackson\"\nfrictional_packing_limit = 0.58\n")
                .find("packing"),
            std::string::npos);
}

TEST(CaseLoader, BinghamRheologyAndItsKeys) {
  const LoadedCase lc = load_case_text("case.name = \"x\"\ncase.model = \"tfm\"\n[tfm]\nrheology = \"bingham\"\n"
                                       "yield = \"mohr_coulomb\"\nyield_stress = 40\nyield_regularisation = 1000\n"
                                       "solids_viscosity = 2\n",
                                       "t.toml");
  EXPECT_EQ(lc.config.tfm.rheology, tfm::SolidsRheology::Bingham);
  EXPECT_EQ(lc.config.tfm.yield, tfm::YieldStress::MohrCoulomb);
  EXPECT_DOUBLE_EQ(lc.config.tfm.yield_stress, 40.0);
  EXPECT_DOUBLE_EQ(lc.config.tfm.yield_regularisation, 1000.0);
  EXPECT_DOUBLE_EQ(lc.config.tfm.mu_s_constant, 2.0);
  EXPECT_DOUBLE_EQ(lc.config.tfm.max_compaction.value_or(-1.0), 0.03);  // the Eq. 20 rheologies' allowance
  // A yield key with another rheology is a mistake, said by name.
  EXPECT_NE(error_of("case.name = \"x\"\ncase.model = \"tfm\"\n[tfm]\nyield_stress = 40\n").find("tfm.yield_stress"),
            std::string::npos);
  EXPECT_NE(error_of("case.name = \"x\"\ncase.model = \"tfm\"\n[tfm]\nrheology = \"bingham\"\nyield_regularisation = 0\n")
                .find("tfm.yield_regularisation"),
            std::string::npos);
  // A sliding wall: tangential, with the solids stuck to the walls.
  const LoadedCase slides = load_case_text("case.name = \"x\"\ncase.model = \"tfm\"\n[tfm]\nsolids_no_slip_walls = true\n"
                                           "sliding_wall_velocity = [0.0, 0.3]\n",
                                           "t.toml");
  EXPECT_DOUBLE_EQ(slides.config.tfm.sliding_wall[1], 0.3);
  EXPECT_NE(error_of("case.name = \"x\"\ncase.model = \"tfm\"\n[tfm]\nsliding_wall_velocity = [0.0, 0.3]\n").find("sliding wall"),
            std::string::npos);
  EXPECT_NE(error_of("case.name = \"x\"\ncase.model = \"tfm\"\n[tfm]\nsolids_no_slip_walls = true\n"
                     "sliding_wall_velocity = [0.1, 0.0]\n")
                .find("tangential"),
            std::string::npos);
}

TEST(CaseLoader, NonAsciiIsRejectedWithItsPosition) {
  EXPECT_NE(error_of("case.name = \"x\"\n# caf\xc3\xa9\n").find("t.toml:2:6: non-ASCII character"), std::string::npos);
}

TEST(CaseLoader, KeysTableListsEveryKeyOnce) {
  const std::string md = case_keys_markdown();
  for (const char* key : {"`case.name`", "`dem.time_step`", "`gas.viscosity`", "`inlet.jet[].centre`", "`tfm.eps_star`",
                          "`coupling.voidage`", "`bubble.threshold`", "`output.interval`"}) {
    // A row starts with its key (a default may name another key, as output.particle_interval's does).
    const std::string row = std::string("\n| ") + key + " |";
    const auto first = md.find(row);
    ASSERT_NE(first, std::string::npos) << key;
    EXPECT_EQ(md.find(row, first + 1), std::string::npos) << key << " listed twice";
  }
}

TEST(CaseLoader, EditDistance) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("dem.time_step", "dem.time_step"), 0u);
}

}  // namespace
}  // namespace fluidbed
