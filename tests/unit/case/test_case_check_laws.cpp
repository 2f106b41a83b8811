// `check` from the law the case uses, the slab depth of a mixture, the regime, the run-time estimate and the
// notes on settings that do nothing (issue 27, items 1-3, 5, 6, 9-15, 17).
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <regex>
#include <string>

#include "dem/contact_model.hpp"
#include "config/case_check.hpp"
#include "config/case_loader.hpp"
#include "unit/case/case_errors.hpp"

namespace fluidbed {
namespace {

std::string dem_case(const std::string& extra = "", int count = 1000) {
  return "case.name = \"x\"\nsettle.enabled = false\nparticles.count = " + std::to_string(count) + "\n" + extra;
}
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
std::string check(const std::string& text) { return describe_case(load_case_text(text, "t.toml").config); }
// The value printed after `label` up to the end of its line.
std::string line_of(const std::string& s, const std::string& label) {
  const auto at = s.find(label);
  if (at == std::string::npos) return "";
  return s.substr(at, s.find('\n', at) - at);
}
// Every line of `check` but the notes (which name the keys given).
std::string without_notes(const std::string& s) {
  return std::regex_replace(s, std::regex("  note: [^\n]*\n"), "");
}

// A glass bed with Hertz contacts (E = 6e10 Pa, nu = 0.25) and the linear spring's unused k set to `k`.
std::string glass(double e, double k, const std::string& extra = "") {
  return dem_case(fmt::format("contact.normal = \"hertz\"\ncontact.stiffness = {}\ncontact.wall_youngs_modulus = {}\n"
                              "species = [{{diameter = 0.004, density = 2500.0, youngs_modulus = {}}}]\n{}",
                              k, e, e, extra));
}

// ---- item 1: the slab of a 2D mixture is as deep as its largest sphere, whatever the order

TEST(CaseCheckLaws, TheSlabDepthOfAMixtureIsTheLargestDiameterInAnyOrder) {
  const std::string small_first = "species = [{diameter = 0.001, fraction = 0.5}, {diameter = 0.002, fraction = 0.5}]\n";
  const std::string large_first = "species = [{diameter = 0.002, fraction = 0.5}, {diameter = 0.001, fraction = 0.5}]\n";
  const CaseConfig a = load_case_text(dem_case(small_first + "dem.time_step = 1e-5\n"), "t.toml").config;
  const CaseConfig b = load_case_text(dem_case(large_first + "dem.time_step = 1e-5\n"), "t.toml").config;
  EXPECT_DOUBLE_EQ(a.coupling.depth, 0.002);  // before: 0.001, the first species'
  EXPECT_DOUBLE_EQ(b.coupling.depth, 0.002);
  const std::string s = describe_case(a);
  EXPECT_TRUE(contains(s, "slab depth (coupling.depth)")) << s;
  EXPECT_TRUE(contains(line_of(s, "slab depth"), "0.002 m")) << s;
  // An explicit slab thinner than the largest spheres: a packed layer of them has no room (1 - 0.82 (2/3) 2 < 0).
  const std::string thin = check(dem_case(small_first + "dem.time_step = 1e-5\ncoupling.depth = 0.001\n"));
  EXPECT_TRUE(contains(thin, "note: coupling.depth = 0.001 m is thinner than the largest particle (0.002 m)")) << thin;
  EXPECT_TRUE(contains(thin, "warning: coupling.depth = 0.001 m is too thin")) << thin;
  EXPECT_TRUE(contains(thin, "below zero: the run fails")) << thin;
}

// ---- items 2, 11: Hertz lines from the moduli, every pair

TEST(CaseCheckLaws, HertzLinesComeFromTheModuliNotFromTheLinearSpring) {
  const std::string base = without_notes(check(glass(6e10, 800.0)));
  EXPECT_EQ(base, without_notes(check(glass(6e10, 1e6))));  // before: t_cr and the overlaps moved with k
  const std::string softer = without_notes(check(glass(6e9, 800.0)));
  for (const char* label : {"overlap of a head-on impact", "mean overlap under the bed's weight",
                            "youngs_modulus for a 1% impact overlap", "Hertz contact 0-0"}) {
    EXPECT_NE(line_of(base, label), "") << label << "\n" << base;
    EXPECT_NE(line_of(base, label), line_of(softer, label)) << label;  // before: they stayed put when E changed
  }
  EXPECT_FALSE(contains(base, "t_cr = 2 pi sqrt(m/k)")) << base;  // the linear spring's period
}

TEST(CaseCheckLaws, AHertzImpactOfGlassAt2MetresPerSecondOverlapsAFifthOfAPercent) {
  // Johnson (1985): delta = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5) for a particle on a wall of the same glass
  // (m* = m, R* = d / 2, E* = E / (2 (1 - nu^2))), the worst of the impacts.
  const std::string s = check(glass(6e10, 800.0, "gas.enabled = true\ninlet.velocity = 2.0\ninlet.jet = []\n"));
  const double m = 2500.0 * std::numbers::pi * 0.004 * 0.004 * 0.004 / 6.0;
  const double e_star = 6e10 / (2.0 * (1.0 - 0.25 * 0.25));
  const double wall = std::pow(15.0 * m * 4.0 / (16.0 * e_star * std::sqrt(0.002)), 0.4);
  const double pair = std::pow(15.0 * 0.5 * m * 4.0 / (16.0 * e_star * std::sqrt(0.001)), 0.4);
  const double worst = std::max(wall, pair) / 0.004;
  EXPECT_NEAR(worst, 0.002, 0.0003);  // the "about 0.2%" (the linear k = 800 N/m gave 11.4%)
  EXPECT_TRUE(contains(line_of(s, "overlap of a head-on impact"), fmt::format("{:.3g}% of d at the fastest inflow 2 m/s",
                                                                            100.0 * worst)))
      << s;
}

TEST(CaseCheckLaws, HertzListsTheCrossPairOfAMixture) {
  const std::string s = check(dem_case(
      "contact.normal = \"hertz\"\ncontact.wall_youngs_modulus = 1e7\n"
      "species = [{diameter = 0.004, youngs_modulus = 1e7}, {diameter = 0.002, youngs_modulus = 1e7}]\n"));
  for (const char* kind : {"Hertz contact 0-0", "Hertz contact 0-1", "Hertz contact 1-1", "Hertz contact 0-wall",
                           "Hertz contact 1-wall"}) {
    EXPECT_TRUE(contains(s, kind)) << kind << "\n" << s;  // before: 0-1 was missing
  }
}

// ---- item 3: Hertz asks for the moduli

TEST(CaseCheckLaws, HertzWithoutAYoungsModulusIsRefusedWithTheStepItWouldCost) {
  const std::string e = error_of(dem_case("contact.normal = \"hertz\"\n"));
  EXPECT_TRUE(contains(e, "species[0].youngs_modulus: contact.normal = \"hertz\" takes the contact stiffness")) << e;
  EXPECT_TRUE(contains(e, "at 7e10 Pa")) << e;
  EXPECT_TRUE(contains(error_of(dem_case("contact.tangential = \"mindlin\"\n")), "contact.tangential = \"mindlin\""));
  // The walls default to the stiffest particles, not to a modulus of their own.
  const CaseConfig c = load_case_text(dem_case("contact.normal = \"hertz\"\nspecies = [{youngs_modulus = 1e7}]\n"),
                                      "t.toml").config;
  EXPECT_DOUBLE_EQ(c.dem.contact.wall_material.youngs_modulus, 1e7);
}

// ---- item 5: the run-time estimate, and what multiplies it

TEST(CaseCheckLaws, TheRunTimeEstimateIsParticleStepsAndCellStepsAtTheMeasuredCosts) {
  const CaseConfig c = load_case_text(dem_case("case.end_time = 1.0\ndem.time_step = 1e-4\ngas.enabled = false\n", 2000), "t.toml").config;
  const std::string s = describe_case(c);
  // 2000 particles x 1e4 steps x 62 ns = 1.24 s (no gas).
  EXPECT_TRUE(contains(line_of(s, "run-time estimate"), "2e+07 particle-steps x 62 ns")) << s;
  EXPECT_TRUE(contains(line_of(s, "run-time estimate"), "1.2 s on one thread")) << s;
  // A stiff glass bed: the step is far below what a 1% overlap needs, and check says how much it costs.
  const std::string stiff = check(glass(6e10, 800.0, "gas.enabled = true\ninlet.velocity = 2.0\ninlet.jet = []\n"));
  EXPECT_TRUE(contains(stiff, "warning: the contacts are")) << stiff;
  EXPECT_TRUE(contains(stiff, "times stiffer than a 1% impact overlap needs")) << stiff;
  // A step set far below the derived one.
  const std::string small = check(dem_case("dem.time_step = 1e-6\n"));
  EXPECT_TRUE(contains(small, "warning: dem.time_step = 1e-06 s is")) << small;
}

// ---- item 6: a derived gas step divides the output intervals

TEST(CaseCheckLaws, ADerivedGasStepDividesEveryOutputInterval) {
  // 1 mm particles: dt = 4e-6 s; the Courant limit (0.5 x 0.02 m x 0.3 / 3.6 m/s) alone would allow 208 steps.
  for (const char* extra : {"inlet.velocity = 3.6\n", "inlet.velocity = 2.9\noutput.monitor_interval = 0.0015\n",
                            "inlet.velocity = 1.3\noutput.interval = 0.037\noutput.checkpoint_interval = 0.2\n"}) {
    const CaseConfig c = load_case_text(dem_case(std::string("species = [{diameter = 0.001}]\ngas.enabled = true\n") + extra),
                                        "t.toml").config;
    const double gas_dt = c.dem.dt * c.coupling.dem_substeps;
    for (double interval : {c.output.interval, c.output.monitor_interval, c.output.checkpoint_interval}) {
      const double n = interval / gas_dt;
      EXPECT_NEAR(n, std::round(n), 1e-6 * n) << extra << " interval " << interval << " gas step " << gas_dt;
    }
    EXPECT_GT(c.coupling.dem_substeps, 1) << extra;
  }
  // Given by hand and not dividing: said.
  const std::string s = check(dem_case("gas.enabled = true\ndem.time_step = 1e-4\ncoupling.dem_substeps = 3\n"));
  EXPECT_TRUE(contains(s, "note: output.monitor_interval = 0.001 s is not a whole number of model steps")) << s;
}

// ---- item 9: the regime

TEST(CaseCheckLaws, CheckNamesTheGeldartGroupAndTheSlugging) {
  // 4 mm glass: (rho_p - rho_g) d^2 = 0.04 kg/m, far above B/D's 1e-3: group D. In a 0.06 m column 0.3 m deep
  // at 2 U_mf, U - U_mf (about 2 m/s) is far above 0.07 sqrt(g D) = 0.054 m/s: slugs.
  const std::string narrow = check(dem_case("domain.width = 0.06\ndomain.height = 0.6\ngas.enabled = true\n"
                                            "inlet.velocity = 3.8\ninlet.jet = []\ngrid.cell_width = 0.01\n"
                                            "dem.time_step = 1e-4\n", 600));
  EXPECT_TRUE(contains(line_of(narrow, "Geldart group"), "D (d32 = 0.004 m")) << narrow;
  EXPECT_TRUE(contains(line_of(narrow, "slugging (Stewart & Davidson 1967)"), "slugging likely")) << narrow;
  EXPECT_TRUE(contains(narrow, "warning: the bed is likely to slug")) << narrow;
  // 300 um sand in the paper's wide bed: group B, free bubbling.
  const std::string sand = check(dem_case("species = [{diameter = 0.0003, density = 2600.0}]\ngas.enabled = true\n"
                                          "inlet.velocity = 0.2\ninlet.jet = []\ndem.time_step = 1e-6\n", 2000));
  EXPECT_TRUE(contains(line_of(sand, "Geldart group"), "B (")) << sand;
  EXPECT_TRUE(contains(line_of(sand, "slugging"), "free bubbling expected")) << sand;
}

// ---- item 10: a particle deeper than the box blames the depth

TEST(CaseCheckLaws, AParticleDeeperThanTheBoxBlamesDomainDepth) {
  const std::string e = error_of("case.name = \"s\"\ncase.dimension = 3\nsettle.enabled = false\nparticles.count = 10\n"
                                 "domain.width = 0.2\ndomain.height = 0.4\ndomain.depth = 0.002\ngrid.cell_width = 0.01\n"
                                 "grid.cell_depth = 0.002\nspecies = [{diameter = 0.004}]\n");
  EXPECT_TRUE(contains(e, "domain.depth: 0.002 m is shallower than a particle of species[0].diameter = 0.004 m")) << e;
  EXPECT_FALSE(contains(e, "millimetres")) << e;
}

// ---- item 12: the impact speed is the peak of the schedule

TEST(CaseCheckLaws, TheImpactOverlapUsesThePeakOfTheSchedule) {
  const std::string table = check(dem_case("gas.enabled = true\ninlet.jet = []\ninlet.schedule = \"table\"\n"
                                           "inlet.table_times = [0.0, 0.1]\ninlet.table_velocities = [1.0, 4.5]\n"));
  EXPECT_TRUE(contains(line_of(table, "overlap of a head-on impact"), "at the fastest inflow 4.5 m/s")) << table;
  const std::string square = check(dem_case("gas.enabled = true\ninlet.jet = []\ninlet.velocity = 2.0\n"
                                            "inlet.schedule = \"square\"\ninlet.frequency = 5.0\ninlet.amplitude = 1.5\n"));
  EXPECT_TRUE(contains(line_of(square, "overlap of a head-on impact"), "at the fastest inflow 3.5 m/s")) << square;
}

// ---- item 13: one U_mf law, said on both lines

TEST(CaseCheckLaws, TheSpeciesAndTheBedUmfComeFromOneLaw) {
  const std::string s = check(dem_case("gas.enabled = true\ncoupling.drag_law = \"di-felice\"\n"));
  const std::string species = line_of(s, "species 0   ");
  const std::string bed = line_of(s, "U_mf of the case's drag law at eps_mf");
  ASSERT_NE(bed, "") << s;
  EXPECT_TRUE(contains(species, "U_mf of the case's drag law alone")) << species;
  // One species: the bed is the species, so both give one number.
  const std::string u_bed = bed.substr(bed.rfind(' ', bed.find(" m/s") - 1) + 1, bed.find(" m/s") - bed.rfind(' ', bed.find(" m/s") - 1) - 1);
  EXPECT_TRUE(contains(species, "alone " + u_bed + " m/s")) << species << " | " << bed;
}

// ---- item 14: 3D settled height from frictional packing

TEST(CaseCheckLaws, TheSettledHeightOfFrictionalSpheresUsesTheirPacking) {
  const std::string box = "case.dimension = 3\ndomain.width = 0.1\ndomain.height = 0.4\ndomain.depth = 0.05\n"
                          "grid.cell_width = 0.01\n";
  const double volume = 1000 * std::numbers::pi * 0.004 * 0.004 * 0.004 / 6.0;
  const std::string s = check(dem_case(box));
  EXPECT_TRUE(contains(line_of(s, "estimated settled bed height"), fmt::format("{:.3f} m", volume / 0.58 / 0.005))) << s;
  EXPECT_TRUE(contains(line_of(s, "estimated settled bed height"), "0.56-0.6")) << s;
  const std::string smooth = check(dem_case(box + "contact.friction = 0.0\n"));
  EXPECT_TRUE(contains(line_of(smooth, "estimated settled bed height"), fmt::format("{:.3f} m", volume / 0.64 / 0.005)))
      << smooth;
}

// ---- item 15: settings that do nothing get a note

TEST(CaseCheckLaws, SettingsThatDoNothingAreNoted) {
  const std::string rolling = check(dem_case("contact.rolling = \"constant\"\n"));
  EXPECT_TRUE(contains(rolling, "note: contact.rolling = \"constant\" with a rolling friction of 0")) << rolling;
  EXPECT_FALSE(contains(check(dem_case("contact.rolling = \"constant\"\ncontact.rolling_friction = 0.1\n")),
                        "resists nothing"));
  const std::string linear = check(dem_case("species = [{youngs_modulus = 6e10}]\n"));
  EXPECT_TRUE(contains(linear, "note: species[0].youngs_modulus: read by the Hertz and Mindlin laws only")) << linear;
  const std::string hertz_k = check(glass(1e7, 900.0));
  EXPECT_TRUE(contains(hertz_k, "note: contact.stiffness: the linear spring's")) << hertz_k;
}

// ---- item 17: numbers as a person writes them; both periodic axes named

TEST(CaseCheckLaws, NumbersAreFormattedAndBothPeriodicAxesNamed) {
  const std::string s = check(dem_case("gas.enabled = true\ninlet.jet = [{centre = 0.031, width = 0.02}]\n"));
  EXPECT_TRUE(contains(s, "[0.021, 0.041] m")) << s;
  EXPECT_FALSE(contains(s, "0.020999999")) << s;
  const std::string p = check("case.name = \"s\"\ncase.dimension = 3\nsettle.enabled = false\nparticles.count = 100\n"
                              "domain.width = 0.1\ndomain.height = 0.2\ndomain.depth = 0.05\ngrid.cell_width = 0.01\n"
                              "domain.periodic = [\"x\", \"z\"]\n");
  EXPECT_TRUE(contains(p, "(width x height x depth, periodic in x and z)")) << p;
}

}  // namespace
}  // namespace fluidbed
