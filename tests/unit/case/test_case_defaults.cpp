// Defaults derived from the bed instead of the paper's numbers, `check` over every species, one domain for every
// model, the same rules in `check` and `run`, and plausibility of units (issue 11, items 11-14).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "core/error.hpp"
#include "closures/drag.hpp"
#include "fluid/gas_solver.hpp"
#include "config/case_check.hpp"
#include "config/case_loader.hpp"
#include "unit/case/case_errors.hpp"

namespace fluidbed {
namespace {

// A DEM case of `count` randomly placed particles with `extra` keys.
std::string dem_case(const std::string& extra = "", int count = 1000) {
  return "case.name = \"x\"\nsettle.enabled = false\nparticles.count = " + std::to_string(count) + "\n" + extra;
}
const std::string kTfm = "case.name = \"x\"\ncase.model = \"tfm\"\n";

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Eq. 8 on the reduced mass of a pair of equal spheres: the damped half period of the linear spring.
double equal_pair_contact_duration(double d, double rho, double k, double e) {
  const double m_eff = 0.5 * rho * std::numbers::pi * d * d * d / 6.0;
  const double l = std::log(1.0 / e);
  const double eta = 2.0 * std::sqrt(m_eff * k) * l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
  return std::numbers::pi / std::sqrt(k / m_eff - std::pow(eta / (2.0 * m_eff), 2));
}

// The most DEM steps per gas step within `limit` whose gas step divides every output interval (issue 27, item 6),
// by trying each count.
int largest_dividing_substeps(const CaseConfig& c, double limit) {
  for (int n = static_cast<int>(std::floor(limit / c.dem.dt * (1 + 1e-12))); n > 1; --n) {
    bool divides = true;
    for (double interval : {c.output.interval, c.output.monitor_interval, c.output.checkpoint_interval}) {
      const double k = interval / (n * c.dem.dt);
      divides = divides && (interval == 0.0 || std::abs(k - std::round(k)) <= 1e-6 * k);
    }
    if (divides) return n;
  }
  return 1;
}

// ---- item 11: defaults tied to the bed, not to the paper

TEST(CaseDefaults, TheGasStepOfADerivedTimeStepIsAMultipleWithinCourantAndStokes) {
  // 4 mm particles, the paper's grid (0.02 m) and a 30 m/s jet: Courant 0.5 on 30 m/s / eps_min 0.3 gives
  // 1e-4 s; the Stokes time of 4 mm particles (133 s) does not bind.
  const CaseConfig c = load_case_text(dem_case("inlet.jet = [{centre = 0.31, velocity = 30.0}]\n"), "t.toml").config;
  const double gas_dt_max = 0.5 * 0.02 * 0.3 / 30.0;
  const double gas_dt = c.coupling.dem_substeps * c.dem.dt;
  EXPECT_GT(c.coupling.dem_substeps, 1);
  EXPECT_LE(gas_dt, gas_dt_max * (1 + 1e-12));
  EXPECT_EQ(c.coupling.dem_substeps, largest_dividing_substeps(c, gas_dt_max));  // the largest such multiple
  // Without the jet the background 1.8 m/s sets the limit.
  const CaseConfig b = load_case_text(dem_case(), "t.toml").config;
  EXPECT_LE(b.coupling.dem_substeps * b.dem.dt, 0.5 * 0.02 * 0.3 / 1.8 * (1 + 1e-12));
  EXPECT_EQ(b.coupling.dem_substeps, largest_dividing_substeps(b, 0.5 * 0.02 * 0.3 / 1.8));
  // 50 um particles at 1 cm/s: the gas step of 1000 DEM steps (the key's upper bound) is within both limits.
  const CaseConfig f = load_case_text(dem_case("species = [{diameter = 5e-5}]\ninlet.velocity = 0.01\n"
                                               "grid.cell_width = 0.005\ndomain.width = 0.05\ndomain.height = 0.1\n", 200),
                                      "t.toml").config;
  EXPECT_EQ(f.coupling.dem_substeps, 1000);
  EXPECT_LE(f.coupling.dem_substeps * f.dem.dt, 0.5 * 2700.0 * 5e-5 * 5e-5 / (18.0 * 1.8e-5));
  // A given time step keeps the old default of one DEM step per gas step.
  EXPECT_EQ(load_case_text(dem_case("dem.time_step = 1e-4\n"), "t.toml").config.coupling.dem_substeps, 1);
}

TEST(CaseDefaults, TheTimeStepOfASmallerParticleIsDerivedFromItsContactDuration) {
  // Before: the paper's 2e-4 s was the default and failed the stability check for 1 mm particles.
  const CaseConfig c = load_case_text(dem_case("species = [{diameter = 0.001}]\n"), "t.toml").config;
  const double t_c = equal_pair_contact_duration(0.001, 2700.0, 800.0, 0.9);
  // dt = t_c / 20 rounded down to 1, 1.25, 2, 2.5, 4, 5, 8 x 10^n: at most a factor 1.6 below t_c / 20.
  EXPECT_LE(c.dem.dt, t_c / 20.0);
  EXPECT_GT(c.dem.dt, t_c / 20.0 / 1.6);
  EXPECT_LE(c.dem.dt, dem_stable_time_step(c.dem));
  const double mantissa = c.dem.dt / std::pow(10.0, std::floor(std::log10(c.dem.dt)));
  EXPECT_TRUE(std::any_of(std::begin({1.0, 1.25, 2.0, 2.5, 4.0, 5.0, 8.0}), std::end({1.0, 1.25, 2.0, 2.5, 4.0, 5.0, 8.0}),
                          [&](double m) { return std::abs(mantissa - m) < 1e-9; }))
      << c.dem.dt;
  ASSERT_FALSE(c.notes.empty());
  EXPECT_TRUE(contains(c.notes[0], "dem.time_step not given")) << c.notes[0];
  EXPECT_TRUE(contains(c.notes[0], "t_c / 20")) << c.notes[0];
  EXPECT_TRUE(contains(describe_case(c), "note: dem.time_step not given"));
}

TEST(CaseDefaults, TheStiffestPairOfAMixtureSetsTheTimeStep) {
  // The lighter pair (2 mm with 2 mm) has the shortest contact.
  const CaseConfig c =
      load_case_text(dem_case("species = [{diameter = 0.004}, {diameter = 0.002}]\n"), "t.toml").config;
  const StiffestContact sc = stiffest_contact(c.dem);
  EXPECT_EQ(sc.a, 1);
  EXPECT_EQ(sc.b, 1);
  EXPECT_NEAR(sc.t_c, equal_pair_contact_duration(0.002, 2700.0, 800.0, 0.9), 1e-12);
  EXPECT_DOUBLE_EQ(c.dem.dt, default_dem_time_step(c.dem));
  EXPECT_LE(c.dem.dt, sc.t_c / 20.0);
}

TEST(CaseDefaults, AGivenTimeStepIsKeptAndThePapersCasesSetTheirOwn) {
  EXPECT_DOUBLE_EQ(load_case_text(dem_case("dem.time_step = 2e-4\n"), "t.toml").config.dem.dt, 2e-4);
  const std::string root = FLUIDBED_SOURCE_DIR;
  const CaseConfig dem = load_case(root + "/cases/gera1998/dem.toml").config;
  EXPECT_DOUBLE_EQ(dem.dem.dt, 1e-4);
  EXPECT_DOUBLE_EQ(dem.bubble.u_mf, 1.8);
  for (const char* f : {"tfm.toml", "tfm-constant-viscosity.toml", "tfm-inviscid.toml"}) {
    EXPECT_DOUBLE_EQ(load_case(root + "/cases/gera1998/" + f).config.bubble.u_mf, 1.8) << f;
  }
  for (const char* f : {"settle-22k.toml", "scale-100k.toml", "scale-300k.toml", "scale-1m.toml"}) {
    EXPECT_DOUBLE_EQ(load_case(root + "/cases/bench/" + f).config.dem.dt, 2e-4) << f;
  }
}

TEST(CaseDefaults, UmfDefaultsToTheErgunValueOfTheBed) {
  // Before: bubble.u_mf defaulted to the inlet velocity.
  const CaseConfig c = load_case_text(dem_case("inlet.velocity = 3.6\n"), "t.toml").config;
  EXPECT_NEAR(c.bubble.u_mf, ergun_minimum_fluidisation_velocity(0.43, 0.004, 2700.0, 1.205, 1.8e-5, 9.81), 1e-12);
  EXPECT_TRUE(contains(describe_case(c), "note: bubble.u_mf not given"));
  // A mixture: the Sauter mean diameter sum f d^3 / sum f d^2 and the volume-mean density.
  const CaseConfig m = load_case_text(dem_case("dem.time_step = 1e-5\nspecies = [{diameter = 0.004, fraction = 0.25}, "
                                               "{diameter = 0.002, density = 2500.0, fraction = 0.75}]\n"),
                                      "t.toml")
                           .config;
  const double d32 = (0.25 * 64e-9 + 0.75 * 8e-9) / (0.25 * 16e-6 + 0.75 * 4e-6);
  const double rho = (0.25 * 64e-9 * 2700.0 + 0.75 * 8e-9 * 2500.0) / (0.25 * 64e-9 + 0.75 * 8e-9);
  EXPECT_NEAR(m.bubble.u_mf, ergun_minimum_fluidisation_velocity(0.43, d32, rho, 1.205, 1.8e-5, 9.81), 1e-12);
  // The two-fluid bed at its initial voidage.
  const CaseConfig t = load_case_text(kTfm, "t.toml").config;
  EXPECT_NEAR(t.bubble.u_mf, ergun_minimum_fluidisation_velocity(0.431, 0.004, 2700.0, 1.205, 1.8e-5, 9.81), 1e-12);
  EXPECT_DOUBLE_EQ(load_case_text(kTfm + "bubble.u_mf = 1.8\n", "t.toml").config.bubble.u_mf, 1.8);
}

TEST(CaseDefaults, CheckSuggestsAStiffnessForATargetOverlap) {
  // 1000 particles of 4 mm on 0.6 m: a bottom particle carries the column over its width, delta / d = M g / (W k);
  // for a 1% overlap k = M g / (0.01 W) = 1000 * 9.048e-5 kg * 9.81 / 0.006 m = 148 N/m.
  const std::string s = describe_case(load_case_text(dem_case(), "t.toml").config);
  const double mass = 2700.0 * std::numbers::pi * 0.004 * 0.004 * 0.004 / 6.0;
  EXPECT_TRUE(contains(s, fmt::format("k = {:.3g} N/m", 1000 * mass * 9.81 / (0.01 * 0.6)))) << s;
  EXPECT_TRUE(contains(s, "stiffness for a 1% impact overlap")) << s;
  EXPECT_TRUE(contains(s, fmt::format("{:.3g}% of d at the bottom", 100.0 * 1000 * mass * 9.81 / (0.6 * 800.0)))) << s;
}

// ---- item 12: `check` covers every species; `check` and `run` apply the same rules

TEST(CaseCheck, EverySpeciesEveryPairAndTheBedOfAllSpecies) {
  const CaseConfig c = load_case_text(dem_case("species = [{diameter = 0.004}, {diameter = 0.002, density = 2500.0}]\n"),
                                      "t.toml")
                           .config;
  const std::string s = describe_case(c);
  for (const char* part : {"species 0 ", "species 1 ", "contact duration 0-0", "contact duration 0-1",
                           "contact duration 1-1", "contact duration 1-wall", "Sauter mean diameter"}) {
    EXPECT_TRUE(contains(s, part)) << part << "\n" << s;
  }
  EXPECT_TRUE(contains(s, "mass 1.047e-05 kg")) << s;  // 2500 pi (0.002)^3 / 6
  // 500 discs of each: area 500 pi (0.004^2 + 0.002^2) / 4 at a packing fraction 0.82 over 0.6 m.
  const double h = 500.0 * std::numbers::pi * (16e-6 + 4e-6) / 4.0 / 0.82 / 0.6;
  EXPECT_TRUE(contains(s, fmt::format("{:.3f} m from every species' area", h))) << s;
}

TEST(CaseCheck, AGridTheGasSolverRefusesIsRefusedByTheLoaderGasOrNot) {
  // Before: `check` passed a one-cell-wide grid that GasSolver then refused at the start of `run`.
  const Grid<2> one_wide = Grid<2>::uniform({0.6, 1.0}, {1, 50});
  EXPECT_THROW(GasSolver<2>(one_wide, GasConfig{}), Error);
  EXPECT_NO_THROW(GasSolver<2>(Grid<2>::uniform({0.04, 0.04}, {2, 2}), GasConfig{}));
  for (const char* gas : {"true", "false"}) {
    const std::string e = error_of(dem_case(std::string("gas.enabled = ") + gas + "\ngrid.cell_width = 0.6\ngrid.cell_height = 0.02\n"));
    EXPECT_TRUE(contains(e, "grid.cell_width: 0.6 m leaves 1 cell across the domain width 0.6 m")) << e;
  }
  EXPECT_TRUE(contains(error_of(kTfm + "grid.cell_width = 1.0\ndomain.width = 1.0\n"), "the gas needs at least 2"));
  const CaseConfig two = load_case_text(dem_case("gas.enabled = false\ndomain.width = 0.04\ndomain.height = 0.04\n", 10),
                                        "t.toml")
                             .config;
  EXPECT_EQ(two.grid.nx, 2);
}

// ---- item 13: one domain and gravity for every model; the full viscous stress

TEST(CaseDomain, GravityReachesEveryModelFromTheDomain) {
  const CaseConfig d = load_case_text(dem_case("domain.gravity = [0.5, -5.0]\n"), "t.toml").config;
  EXPECT_DOUBLE_EQ(d.domain.gravity.y, -5.0);
  EXPECT_DOUBLE_EQ(d.dem.domain.gravity.x, 0.5);
  EXPECT_DOUBLE_EQ(d.dem.domain.gravity.y, -5.0);
  EXPECT_DOUBLE_EQ(d.gas.gravity.y, -5.0);
  // Before: a two-fluid case could not set gravity at all (dem.gravity was an unknown key there).
  const CaseConfig t = load_case_text(kTfm + "domain.gravity = [0.0, -5.0]\ndomain.width = 0.4\n", "t.toml").config;
  EXPECT_DOUBLE_EQ(t.tfm.domain.gravity.y, -5.0);
  EXPECT_DOUBLE_EQ(t.gas.gravity.y, -5.0);
  EXPECT_DOUBLE_EQ(t.tfm.domain.width, 0.4);
  EXPECT_DOUBLE_EQ(t.domain.width, 0.4);
}

TEST(CaseDomain, TheOldNameDemGravityIsReadAsDomainGravity) {
  const LoadedCase lc = load_case_text(dem_case("[dem]\ngravity = [0.0, -3.0]\n"), "t.toml");
  EXPECT_DOUBLE_EQ(lc.config.dem.domain.gravity.y, -3.0);
  EXPECT_TRUE(contains(lc.resolved_toml, "[domain]")) << lc.resolved_toml;
  EXPECT_FALSE(contains(lc.resolved_toml, "[dem]\ngravity")) << lc.resolved_toml;
  EXPECT_DOUBLE_EQ(load_case_text(kTfm, "t.toml", {"dem.gravity=[0.0, -2.0]"}).config.tfm.domain.gravity.y, -2.0);
  EXPECT_TRUE(contains(error_of(dem_case("dem.gravity = [0.0, -3.0]\ndomain.gravity = [0.0, -3.0]\n")),
                       "dem.gravity: is the old name of domain.gravity; give only domain.gravity"));
}

TEST(CaseDomain, TheFullViscousStressCanBeChosen) {
  EXPECT_EQ(load_case_text(dem_case("gas.viscous_stress = \"full\"\n"), "t.toml").config.gas.viscous, ViscousStress::Full);
  EXPECT_EQ(load_case_text(dem_case("gas.viscous_stress = \"laplacian\"\n"), "t.toml").config.gas.viscous,
            ViscousStress::Laplacian);
  // The two-fluid model's gas has no viscous stress: choosing one there is refused, not ignored.
  EXPECT_TRUE(contains(error_of(kTfm + "gas.viscous_stress = \"full\"\n"), "gas.viscous_stress: the two-fluid model"));
}

// ---- item 14: implausible units say what looks wrong

TEST(CasePlausibility, AParticleInMetresThatWasMeantInMillimetres) {
  // Before: "particles do not fit".
  const std::string e = error_of(dem_case("species = [{diameter = 4.0}]\n"));
  EXPECT_TRUE(contains(e, "species[0].diameter: a particle of 4 m is larger than the domain (0.6 x 1 m)")) << e;
  EXPECT_TRUE(contains(e, "4 mm is 0.004 m")) << e;
  const std::string cell = error_of(dem_case("dem.time_step = 1e-4\nspecies = [{diameter = 0.03}]\n", 10));
  EXPECT_TRUE(contains(cell, "larger than a gas cell (0.02 x 0.02 m)")) << cell;
  // Without gas the particles need no cell.
  EXPECT_NO_THROW(load_case_text(dem_case("gas.enabled = false\nspecies = [{diameter = 0.03}]\n", 10),
                                 "t.toml"));
  EXPECT_TRUE(contains(error_of(kTfm + "tfm.particle_diameter = 4.0\n"), "tfm.particle_diameter: a particle of 4 m"));
  EXPECT_TRUE(contains(error_of(kTfm + "tfm.particle_diameter = 0.03\n"), "larger than a gas cell"));
}

TEST(CasePlausibility, SizesNoBedHasAndGridsNoMemoryHolds) {
  // Found by the fuzzer: a 1.1e307 m domain overflowed the packing's site count (undefined behaviour).
  EXPECT_TRUE(contains(error_of(dem_case("domain.width = 1.1e307\n")), "domain.width: 1.1e+307 m is larger than any"));
  EXPECT_TRUE(contains(error_of(dem_case("domain.width = 600.0\n")), "a size in millimetres? 600 mm is 0.6 m"));
  EXPECT_TRUE(contains(error_of(dem_case("species = [{diameter = 1e-300}]\n")), "is smaller than any particle"));
  EXPECT_TRUE(contains(error_of(dem_case("gas.enabled = false\ngrid.cell_width = 1e-6\n")), "at most 1e8"));
}

TEST(CasePlausibility, ADensityInGramsPerCubicCentimetre) {
  // Before: a time-step error (the 2.7 kg/m^3 particles are 1000 times too light for the spring).
  const std::string e = error_of(dem_case("species = [{density = 2.7}]\n"));
  EXPECT_TRUE(contains(e, "species[0].density: 2.7 kg/m^3 is the density of a gas, not of a solid")) << e;
  EXPECT_TRUE(contains(e, "2.7 g/cm^3 is 2700 kg/m^3")) << e;
  EXPECT_TRUE(contains(error_of(kTfm + "tfm.particle_density = 2.7\n"), "the density of a gas, not of a solid"));
  EXPECT_TRUE(contains(error_of(dem_case("species = [{density = 2.7e6}]\n")), "denser than any solid"));
  // Heavier than a gas but not heavier than this gas.
  EXPECT_TRUE(contains(error_of(dem_case("species = [{density = 50.0}]\ngas.density = 60.0\ndem.time_step = 1e-5\n")),
                       "are not heavier than the gas"));
}

TEST(CasePlausibility, GasPropertiesOutsideAnyFluidAndOfALiquid) {
  EXPECT_TRUE(contains(error_of(dem_case("gas.density = 0.001205\n")), "gas.density: 0.001205 kg/m^3 is thinner than any gas"));
  EXPECT_TRUE(contains(error_of(dem_case("gas.density = 1205.0e3\n")), "denser than a gas or a common liquid"));
  EXPECT_TRUE(contains(error_of(dem_case("gas.viscosity = 18.0\n")), "in micropascal seconds? 18 uPa s is 1.8e-05 Pa s"));
  EXPECT_TRUE(contains(error_of(dem_case("gas.viscosity = 1e-8\n")), "below the viscosity of any gas"));
  // A liquid's values are allowed (the drag laws hold), with a note.
  const CaseConfig c = load_case_text(dem_case("gas.viscosity = 0.018\n"), "t.toml").config;
  EXPECT_TRUE(std::any_of(c.notes.begin(), c.notes.end(),
                          [](const std::string& n) { return contains(n, "gas.viscosity = 0.018 Pa s is the viscosity of a liquid"); }));
  EXPECT_TRUE(contains(error_of(kTfm + "gas.viscosity = 18.0\n"), "gas.viscosity"));
}

}  // namespace
TEST(CaseDefaults, AStepAboveThePackedBedSpinModeIsNoted) {
  // The paper's spheres (4 mm, 2700 kg/m^3, k_n = k_t = 800 N/m): the spin mode of a hexagonal monolayer with all
  // contacts sticking has omega^2 = 2 Z k_t r^2 / I = 30 k_t / m (Z = 6, I = 0.4 m r^2), about 16,300 1/s, so the
  // undamped limit 2 / omega is 1.23e-4 s; the single dashpot (e = 0.9 on the pair's reduced mass m / 2, Eq. 8)
  // lowers it by sqrt(1 + zeta^2) - zeta, zeta = eta (30 / m) / (2 omega) = 0.13, to 1.08e-4 s. The paper case's
  // 1e-4 s is below it; bench/dem_timestep_modes.py finds 16,236 1/s for the settled random bed (lattice: 16,290).
  const double m = 2700.0 * std::numbers::pi / 6.0 * 0.004 * 0.004 * 0.004;
  const double w0 = std::sqrt(30.0 * 800.0 / m);
  const double l = std::log(1.0 / 0.9);
  const double eta = 2.0 * std::sqrt(0.5 * m * 800.0) * l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
  const double zeta = 0.5 * eta * (30.0 / m) / w0;
  const double expected = 2.0 / w0 * (std::sqrt(1.0 + zeta * zeta) - zeta);
  const CaseConfig at_2e4 = load_case_text(dem_case("dem.time_step = 2e-4\n"), "t.toml").config;
  const double dt_bed = dem_packed_bed_time_step(at_2e4.dem);
  EXPECT_NEAR(dt_bed, expected, 1e-12 * expected);  // the same closed form: round-off only
  EXPECT_NEAR(expected, 1.08e-4, 0.005e-4);
  EXPECT_LT(dt_bed, dem_stable_time_step(at_2e4.dem));
  ASSERT_TRUE(std::any_of(at_2e4.notes.begin(), at_2e4.notes.end(),
                          [](const std::string& n) { return contains(n, "spin mode of a packed bed"); }));
  const CaseConfig at_1e4 = load_case_text(dem_case("dem.time_step = 1e-4\n"), "t.toml").config;
  EXPECT_TRUE(std::none_of(at_1e4.notes.begin(), at_1e4.notes.end(),
                           [](const std::string& n) { return contains(n, "spin mode of a packed bed"); }));
}

}  // namespace fluidbed
