// `--set SECTION.KEY=VALUE` through sections, arrays of tables and plain values (issue 11, item 1): every
// malformed override is a bad-input error (exit 2) naming the override; none creates an array entry.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "config/case_loader.hpp"

namespace fluidbed {
namespace {

// One species and one jet, as in the paper's case.
const std::string kCase =
    "case.name = \"x\"\nparticles.count = 50\nsettle.enabled = false\ndem.time_step = 5e-5\n"
    "[[species]]\ndiameter = 0.004\n"
    "[[inlet.jet]]\ncentre = 0.31\n";

std::string override_error(const std::string& assignment) {
  try {
    load_case_text(kCase, "t.toml", {assignment});
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2) << assignment;
    return e.what();
  }
  ADD_FAILURE() << assignment << " was accepted";
  return "";
}

TEST(CaseOverrides, AKeyUnderAnArrayOfTablesNeedsAnIndex) {
  // Before: a null dereference in insert_at (exit 139).
  EXPECT_NE(override_error("species.diameter=0.003").find("'species' is an array of tables: name one entry, as in "
                                                          "species[0].diameter"),
            std::string::npos);
  EXPECT_NE(override_error("inlet.jet.velocity=20").find("as in inlet.jet[0].velocity"), std::string::npos);
}

TEST(CaseOverrides, AKeyUnderAValueOrAnIndexOnATableIsRefused) {
  EXPECT_NE(override_error("case.name.x=1").find("'case.name' is a string, not a section"), std::string::npos);
  EXPECT_NE(override_error("case[0].name=1").find("'case' is a table, not an array"), std::string::npos);
  EXPECT_NE(override_error("species[0].diameter.x=1").find("'species[0].diameter' is a number"), std::string::npos);
  EXPECT_NE(override_error("species[0][0].diameter=1").find("'species[0]' is a table, not an array"),
            std::string::npos);
}

TEST(CaseOverrides, AnIndexPastTheEndNeverAddsAnEntry) {
  // Before: species[1] silently added a second species; species[100000] ran out of memory (exit 3).
  for (const char* a : {"species[1].diameter=0.003", "species[100000].diameter=0.003",
                        "species[99999999999999999999999].diameter=0.003", "inlet.jet[1].velocity=20"}) {
    const std::string e = override_error(a);
    EXPECT_NE(e.find("--set changes existing entries only"), std::string::npos) << e;
  }
  EXPECT_NE(override_error("species[1].diameter=0.003").find("'species' has 1 entry (species[0])"), std::string::npos);
  EXPECT_NE(override_error("contact.pair[0].restitution=0.5").find("the case has no 'contact.pair'"),
            std::string::npos);
}

TEST(CaseOverrides, ASectionOrAnArrayIsNotReplacedByAValue) {
  EXPECT_NE(override_error("case=1").find("'case' is a section"), std::string::npos);
  EXPECT_NE(override_error("species=0.003").find("'species' is an array of tables"), std::string::npos);
  EXPECT_NE(override_error("species[0]=1").find("'species[0]' is a table"), std::string::npos);
  EXPECT_NE(override_error("dem.time_step=").find("no value after '='"), std::string::npos);
  EXPECT_NE(override_error("=1").find("expected SECTION.KEY=VALUE"), std::string::npos);
  EXPECT_NE(override_error("a..b=1").find("is not a valid key path"), std::string::npos);
}

TEST(CaseOverrides, ExistingEntriesAndWholeArraysCanBeSet) {
  const CaseConfig one = load_case_text(kCase, "t.toml", {"species[0].diameter=0.003", "inlet.jet[0].velocity=20"}).config;
  ASSERT_EQ(one.dem.n_species(), 1u);
  EXPECT_DOUBLE_EQ(one.dem.species[0].diameter, 0.003);
  EXPECT_DOUBLE_EQ(one.gas.boundary.jets.at(0).velocity, 20.0);
  // A whole array replaces the file's; an entry can be given as an inline table.
  const CaseConfig two =
      load_case_text(kCase, "t.toml", {"species=[{diameter = 0.004}, {diameter = 0.002, density = 2500.0}]"}).config;
  ASSERT_EQ(two.dem.n_species(), 2u);
  EXPECT_DOUBLE_EQ(two.dem.species[1].density, 2500.0);
  const CaseConfig table = load_case_text(kCase, "t.toml", {"species[0]={diameter = 0.005}"}).config;
  EXPECT_DOUBLE_EQ(table.dem.species[0].diameter, 0.005);
}

TEST(CaseOverrides, AnErrorInsideAnOverriddenArrayNamesTheOverride) {
  const std::string e = override_error("species=[{diameter = -0.003}]");
  EXPECT_NE(e.find("--set species=[{diameter = -0.003}]: species[0].diameter: -0.003 is out of range"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace fluidbed
