// The size-distribution keys of [[species]] (docs/case-format.md), `check`'s size report, and a particle file
// with its own diameters: what a case asks for is what the particles get.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <unistd.h>

#include "core/error.hpp"
#include "config/case_check.hpp"
#include "config/case_loader.hpp"
#include "io/csv.hpp"
#include "models/dem_model.hpp"

namespace fluidbed {
namespace {

const std::string kBase = "case.name = \"sizes\"\ndomain.width = 0.1\ndomain.height = 0.2\ngrid.cell_width = 0.01\n"
                          "particles.count = 100\n";

std::string load_error(const std::string& text) {
  try {
    load_case_text(kBase + text, "sizes.toml");
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(SizeKeys, DistributionsAreReadAndChecked) {
  const CaseConfig c = load_case_text(kBase + "species = [{size_distribution = \"log-normal\", median = 0.003, "
                                      "sigma = 0.2}]\n", "sizes.toml").config;
  const Species& s = c.dem.species[0];
  ASSERT_EQ(s.size.law, SizeLaw::LogNormal);
  // Default cut-offs median exp(-+3 sigma); the representative diameter is the truncated number mean.
  EXPECT_DOUBLE_EQ(s.size.d_min, 0.003 * std::exp(-0.6));
  EXPECT_DOUBLE_EQ(s.size.d_max, 0.003 * std::exp(0.6));
  // Truncated log-normal mean: median exp(sigma^2 / 2) [Phi(3 - sigma) - Phi(-3 - sigma)] / [Phi(3) - Phi(-3)].
  const auto Phi = [](double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); };
  const double mean = 0.003 * std::exp(0.02) * (Phi(2.8) - Phi(-3.2)) / (Phi(3.0) - Phi(-3.0));
  EXPECT_NEAR(s.diameter, mean, 1e-12 * mean);
  EXPECT_NE(load_error("species = [{size_distribution = \"normal\", mean = 0.003, std = 0.0002, diameter = 0.003}]\n")
                .find("species[0].diameter"), std::string::npos);
  EXPECT_NE(load_error("species = [{size_distribution = \"uniform\", d_min = 0.003}]\n").find("species[0].d_max"),
            std::string::npos);
  EXPECT_NE(load_error("species = [{size_distribution = \"list\", diameters = [0.002, 0.003], fractions = [0.5]}]\n")
                .find("species[0].fractions"), std::string::npos);
  EXPECT_NE(load_error("species = [{size_distribution = \"normal\", mean = 0.003, std = 0.0002, median = 0.003}]\n")
                .find("median"), std::string::npos);  // a key of another law is unknown here
  // Mass fractions become number fractions f / d^3, renormalised: half the mass each of 2 and 4 mm is 8 : 1.
  const CaseConfig m = load_case_text(kBase + "species = [{size_distribution = \"list\", diameters = [0.002, 0.004], "
                                      "fractions = [0.5, 0.5], fraction_basis = \"mass\"}]\n", "sizes.toml").config;
  EXPECT_NEAR(m.dem.species[0].size.fractions[0], 8.0 / 9.0, 1e-15);
  EXPECT_NEAR(m.dem.species[0].diameter, (8.0 * 0.002 + 0.004) / 9.0, 1e-15);
  // check: every species with its law, count, mean, d32, cut-offs.
  const std::string report = describe_case(m);
  std::printf("%s\n", report.c_str());
  EXPECT_NE(report.find("species 0 sizes"), std::string::npos);
  EXPECT_NE(report.find("list (requested): 100 particles"), std::string::npos);
}

TEST(SizeKeys, ParticleFileWithDiametersGivesEachParticleItsSize) {
  const auto dir = std::filesystem::temp_directory_path() / ("fluidbed-sizes-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "p.csv") << "id,x,y,vx,vy,omega,species,diameter\n0,0.02,0.02,0,0,0,0,0.003\n"
                                  "1,0.05,0.02,0,0,0,0,0.005\n";
  const CaseConfig c = load_case_text(kBase + "particles.source = \"file\"\nparticles.file = \"p.csv\"\n",
                                      (dir / "sizes.toml").string()).config;
  const ParticleStore<2> p = particles_from_csv<2>((dir / "p.csv").string(), c.dem);
  ASSERT_EQ(p.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const double d = i == 0 ? 0.003 : 0.005;
    EXPECT_EQ(p.radius[i], 0.5 * d);
    EXPECT_NEAR(p.mass[i], 2700.0 * std::numbers::pi * d * d * d / 6.0, 1e-15);
  }
  EXPECT_TRUE(p.has_own_sizes(c.dem.species));
  const std::string report = describe_case(c);
  EXPECT_NE(report.find("sizes of the file: 2 particles in the file, mean d = 0.004 m"), std::string::npos) << report;
  std::ofstream(dir / "bad.csv") << "id,x,y,vx,vy,omega,species,diameter\n0,0.02,0.02,0,0,0,0,-0.003\n";
  EXPECT_THROW(read_particles_csv(dir / "bad.csv", 2), Error);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fluidbed
