// The drag law as the case file chooses it: coupling.drag_law reaches CFD-DEM and the TFM, drag_switch defaults
// per law, and the one run-time switch (with_drag_law) hands each law its own type.
#include <gtest/gtest.h>

#include <cmath>

#include <string>
#include <type_traits>

#include "closures/drag.hpp"
#include "config/case_loader.hpp"
#include "unit/case/case_errors.hpp"

namespace fluidbed {
namespace {

const std::string kDem = "case.name = \"x\"\nsettle.enabled = false\nparticles.count = 100\n";
const std::string kTfm = "case.name = \"x\"\ncase.model = \"tfm\"\n";

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(DragConfig, ThePapersLawIsTheDefault) {
  const CaseConfig c = load_case_text(kDem, "t.toml").config;
  EXPECT_EQ(c.coupling.drag_law, DragLaw::ErgunWenYu);
  EXPECT_EQ(c.coupling.drag_switch, DragSwitch::Sharp);
}

TEST(DragConfig, EachNameSelectsItsLawInBothModels) {
  const std::pair<const char*, DragLaw> names[] = {{"ergun-wen-yu", DragLaw::ErgunWenYu},
                                                   {"gidaspow", DragLaw::Gidaspow},
                                                   {"di-felice", DragLaw::DiFelice},
                                                   {"beetstra", DragLaw::Beetstra},
                                                   {"koch-hill", DragLaw::KochHill}};
  for (const auto& [name, law] : names) {
    const std::string key = std::string("coupling.drag_law = \"") + name + "\"\n";
    EXPECT_EQ(load_case_text(kDem + key, "t.toml").config.coupling.drag_law, law) << name;
    const CaseConfig t = load_case_text(kTfm + key, "t.toml").config;
    EXPECT_EQ(t.tfm.drag_law, law) << name;
    // Gidaspow comes with the Huilin-Gidaspow blend unless told otherwise; the others default to no blend.
    EXPECT_EQ(t.tfm.drag_switch, law == DragLaw::Gidaspow ? DragSwitch::Smooth : DragSwitch::Sharp) << name;
  }
  const CaseConfig g = load_case_text(kDem, "t.toml", {"coupling.drag_law=gidaspow", "coupling.drag_switch=sharp"}).config;
  EXPECT_EQ(g.coupling.drag_switch, DragSwitch::Sharp);
}

TEST(DragConfig, ABlendOfALawWithoutBranchesAndAnUnknownLawAreRefused) {
  EXPECT_TRUE(contains(error_of(kDem + "coupling.drag_law = \"beetstra\"\ncoupling.drag_switch = \"smooth\"\n"),
                       "coupling.drag_switch"));
  EXPECT_TRUE(contains(error_of(kDem + "coupling.drag_law = \"syamlal\"\n"), "coupling.drag_law"));
  // The resolved case.toml writes drag_switch = "sharp" for every law: it must read back.
  EXPECT_EQ(load_case_text(kDem + "coupling.drag_law = \"koch-hill\"\ncoupling.drag_switch = \"sharp\"\n", "t.toml")
                .config.coupling.drag_law,
            DragLaw::KochHill);
}

TEST(DragDispatch, EachModelGetsItsOwnLawType) {
  const auto type_of = [](DragModel m) {
    return with_drag_law(m, [](auto law) -> int {
      using L = decltype(law);
      if constexpr (std::is_same_v<L, ErgunWenYuSharpLaw>) return 0;
      if constexpr (std::is_same_v<L, ErgunWenYuSmoothLaw>) return 1;
      if constexpr (std::is_same_v<L, GidaspowSharpLaw>) return 2;
      if constexpr (std::is_same_v<L, GidaspowSmoothLaw>) return 3;
      if constexpr (std::is_same_v<L, DiFeliceLaw>) return 4;
      if constexpr (std::is_same_v<L, BeetstraLaw>) return 5;
      if constexpr (std::is_same_v<L, KochHillLaw>) return 6;
      return -1;
    });
  };
  EXPECT_EQ(type_of({DragLaw::ErgunWenYu, DragSwitch::Sharp}), 0);
  EXPECT_EQ(type_of({DragLaw::ErgunWenYu, DragSwitch::Smooth}), 1);
  EXPECT_EQ(type_of({DragLaw::Gidaspow, DragSwitch::Sharp}), 2);
  EXPECT_EQ(type_of({DragLaw::Gidaspow, DragSwitch::Smooth}), 3);
  EXPECT_EQ(type_of({DragLaw::DiFelice, DragSwitch::Sharp}), 4);
  EXPECT_EQ(type_of({DragLaw::Beetstra, DragSwitch::Smooth}), 5);
  EXPECT_EQ(type_of({DragLaw::KochHill, DragSwitch::Sharp}), 6);
  // The function-pointer form (the TFM's) is the same law.
  const DragInput in{0.6, 0.004, 1.205, 1.8e-5, 0.7};
  for (DragLaw law : {DragLaw::ErgunWenYu, DragLaw::Gidaspow, DragLaw::DiFelice, DragLaw::Beetstra, DragLaw::KochHill}) {
    const DragModel m{law, DragSwitch::Sharp};
    EXPECT_EQ(drag_beta_function(m)(in), drag_beta(m, in));
  }
}

TEST(DragLaws, FiniteAndPositiveAtZeroSlipAndAtTheClippedVoidages) {
  // The coupling clips eps to [eps_min, 1 - 1e-9] and a bed at rest has zero slip: every law must stay finite there.
  for (DragLaw law : {DragLaw::ErgunWenYu, DragLaw::Gidaspow, DragLaw::DiFelice, DragLaw::Beetstra, DragLaw::KochHill}) {
    for (double eps : {0.3, 0.4, 0.8, 0.99, 1.0 - 1e-9}) {
      for (double slip : {0.0, 1e-12, 1.0, 30.0}) {
        const double b = drag_beta({law, DragSwitch::Sharp}, DragInput{eps, 0.004, 1.205, 1.8e-5, slip});
        EXPECT_TRUE(std::isfinite(b) && b > 0.0) << static_cast<int>(law) << " eps " << eps << " slip " << slip;
      }
    }
  }
}

}  // namespace
}  // namespace fluidbed
