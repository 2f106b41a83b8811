// The discrete-particle model behind `fluidbed run`: the overlap limit judged per contact (issue 11, item 2) and
// a run that lands exactly on its end time when the gas step does not divide it (item 8).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <spdlog/spdlog.h>

#include "core/error.hpp"
#include "config/case_loader.hpp"
#include "models/dem_model.hpp"

namespace fluidbed {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / fmt::format("fluidbed-dem-model-{}-{}", name, ::getpid());
  fs::create_directories(d);
  return d;
}

// Two species, 4 mm and 2 mm, no gas, no gravity: the first force evaluation sees the overlaps as placed.
CaseConfig two_species_case(const fs::path& dir, const std::string& rows) {
  const fs::path csv = dir / "particles.csv";
  std::ofstream(csv) << "id,x,y,vx,vy,omega,species\n" << rows;
  const std::string text = fmt::format(R"(case.name = "overlap"
domain.width = 0.1
domain.height = 0.1
gas.enabled = false
grid.cell_width = 0.01
dem.gravity = [0.0, 0.0]
dem.time_step = 1e-5
particles.source = "file"
particles.file = "{}"
[[species]]
diameter = 0.004
[[species]]
diameter = 0.002
)", csv.string());
  return load_case_text(text, (dir / "overlap.toml").string()).config;
}

// One step of the model built from the case; returns the failure message, empty when it ran.
std::string first_step(const CaseConfig& c, const fs::path& dir) {
  spdlog::logger log("test");
  auto m = make_dem_model(c, (dir / "out").string(), true, log);
  try {
    m->advance(1.0);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(DemModelOverlap, JudgedAgainstTheContactsOwnDiameter) {
  const fs::path dir = temp_dir("overlap");
  // Two 4 mm particles at 6% of 4 mm (0.24 mm): below the default 10% limit, although 0.24 mm is 12% of the
  // 2 mm species that the case also defines.
  EXPECT_EQ(first_step(two_species_case(dir, "0,0.05,0.05,0,0,0,0\n1,0.05376,0.05,0,0,0,0\n"), dir), "");
  // A 4 mm particle 0.3 mm (7.5% of its own diameter) into the left wall.
  EXPECT_EQ(first_step(two_species_case(dir, "0,0.0017,0.05,0,0,0,0\n"), dir), "");
  // The same 0.24 mm between a 4 mm and a 2 mm particle is 12% of the smaller one: over the limit.
  const std::string msg = first_step(two_species_case(dir, "0,0.05,0.05,0,0,0,0\n1,0.05276,0.05,0,0,0,1\n"), dir);
  EXPECT_NE(msg.find("12.0% of its diameter"), std::string::npos) << msg;
  EXPECT_NE(msg.find("particles 0 (d = 0.004 m) and 1 (d = 0.002 m)"), std::string::npos) << msg;
  fs::remove_all(dir);
}

// Runs the model to t_end as the run driver does (advance until the time reaches t_end); returns the calls.
int run_to(ModelRun& m, double t_end) {
  int calls = 0;
  while (m.time() < t_end && calls < 100000) {
    m.advance(t_end);
    ++calls;
  }
  return calls;
}

TEST(DemModelEndTime, LastStepIsShortenedToLandOnTheEndTime) {
  const fs::path dir = temp_dir("end");
  for (const bool gas : {true, false}) {
    const std::string text = fmt::format(R"(case.name = "end"
domain.width = 0.02
domain.height = 0.04
particles.count = 10
settle.enabled = false
gas.enabled = {}
grid.cell_width = 0.01
dem.time_step = 1e-4
coupling.dem_substeps = 2
)", gas);
    const CaseConfig c = load_case_text(text, (dir / "end.toml").string()).config;
    spdlog::logger log("test");
    auto m = make_dem_model(c, (dir / "out").string(), true, log);
    const double step = m->macro_dt();
    EXPECT_EQ(step, gas ? 2e-4 : 1e-4);
    // 0.0101 s is 50.5 gas steps (101 DEM steps alone): 50 full steps and a half one with gas.
    const int calls = run_to(*m, 0.0101);
    EXPECT_EQ(calls, gas ? 51 : 101);
    EXPECT_EQ(m->time(), 0.0101);
    // Continuing, the clock counts whole steps from the landing point and lands again.
    EXPECT_EQ(run_to(*m, 0.0151), gas ? 25 : 50);
    EXPECT_NEAR(m->time(), 0.0151, 1e-15);
    fmt::print("{}: landed at {:.17g} s and {:.17g} s\n", gas ? "CFD-DEM" : "DEM alone", 0.0101, m->time());
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fluidbed
