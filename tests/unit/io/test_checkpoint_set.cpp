#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "run/checkpoint_set.hpp"
#include "io/hdf5_file.hpp"
#include "test_helpers.hpp"

namespace fluidbed {
namespace {

namespace fs = std::filesystem;

const char* const kCase = R"([case]
name = "bed"
end_time = 1.0
seed = 7
[contact]
stiffness = 800.0
[output]
interval = 0.01
[[species]]
diameter = 0.004
density = 2700.0
)";

std::string with(const std::string& from, const std::string& to) {
  std::string s = kCase;
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

TEST(SimulationDifferences, NoneForTheSameCase) { EXPECT_TRUE(simulation_differences(kCase, kCase).empty()); }

TEST(SimulationDifferences, NamesAChangedPhysicalKeyWithBothValues) {
  const auto d = simulation_differences(kCase, with("diameter = 0.004", "diameter = 0.0035"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].key, "species[0].diameter");
  EXPECT_EQ(d[0].checkpoint, "0.004");
  EXPECT_EQ(d[0].current, "0.0035");
  EXPECT_EQ(simulation_differences(kCase, with("stiffness = 800.0", "stiffness = 900.0"))[0].key, "contact.stiffness");
  // The seed drives seeded noise of some models during the run: it counts.
  EXPECT_EQ(simulation_differences(kCase, with("seed = 7", "seed = 8")).size(), 1u);
}

TEST(SimulationDifferences, RunControlAndOutputMayChange) {
  EXPECT_TRUE(simulation_differences(kCase, with("end_time = 1.0", "end_time = 2.0")).empty());
  EXPECT_TRUE(simulation_differences(kCase, with("interval = 0.01", "interval = 0.02")).empty());
  EXPECT_TRUE(simulation_differences(kCase, with("name = \"bed\"", "name = \"bed\"\ndescription = \"x\"")).empty());
}

TEST(SimulationDifferences, AKeyOnlyOneSideHasCounts) {
  const auto d = simulation_differences(kCase, with("stiffness = 800.0", "stiffness = 800.0\nfriction = 0.3"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].key, "contact.friction");
  EXPECT_EQ(d[0].checkpoint, "(not set)");
}

TEST(SimulationDifferences, ACheckpointFromBeforeTheDimensionKeyIsA2DRun) {
  // Checkpoints written before case.dimension existed were 2D runs: the key resolved as 2 is no change, 3 is.
  const std::string now2 = with("seed = 7", "seed = 7\ndimension = 2");
  EXPECT_TRUE(simulation_differences(kCase, now2).empty());
  const auto d = simulation_differences(kCase, with("seed = 7", "seed = 7\ndimension = 3"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].key, "case.dimension");
}

TEST(AllowedChange, KeySectionOrTableButNotAPrefixOfAName) {
  EXPECT_TRUE(allowed_change("contact.stiffness", {"contact.stiffness"}));
  EXPECT_TRUE(allowed_change("inlet.jet[0].velocity", {"inlet"}));
  EXPECT_TRUE(allowed_change("inlet.jet[0].velocity", {"inlet.jet"}));
  EXPECT_TRUE(allowed_change("inlet.jet[0].velocity", {"inlet.jet[0]"}));
  EXPECT_FALSE(allowed_change("inlet.velocity", {"inlet.vel"}));
  EXPECT_FALSE(allowed_change("contact.stiffness", {}));
  EXPECT_FALSE(allowed_change("contact.stiffness", {""}));
}

void write_checkpoint(const fs::path& path, double t) {
  Hdf5File f = Hdf5File::create(path);
  f.write("x", std::vector<double>(64, t));
  f.set_attribute("/", "time", t);
  f.commit();
}

// Modification times a test can order without sleeping.
void set_age(const fs::path& p, int seconds_ago) {
  fs::last_write_time(p, fs::file_time_type::clock::now() - std::chrono::seconds(seconds_ago));
}

TEST(Checkpoints, RotationKeepsTheNewestWrittenAndNeverTheJustWritten) {
  const test::ScratchDir scratch;
  const fs::path& dir = scratch.path;
  for (int k = 1; k <= 5; ++k) {
    write_checkpoint(dir / ("t0.0" + std::to_string(k) + "0000.h5"), 0.01 * k);
    set_age(dir / ("t0.0" + std::to_string(k) + "0000.h5"), 100 - k);
  }
  write_checkpoint(dir / "final.h5", 1.0);
  set_age(dir / "final.h5", 200);
  test::spit(dir / "t0.060000.h5.tmp.1", "partial");
  const auto deleted = rotate_checkpoints(dir, dir / "t0.050000.h5", 3);
  EXPECT_EQ(deleted.size(), 2u);
  EXPECT_FALSE(fs::exists(dir / "t0.010000.h5"));
  EXPECT_FALSE(fs::exists(dir / "t0.020000.h5"));
  for (const char* kept : {"t0.030000.h5", "t0.040000.h5", "t0.050000.h5", "final.h5", "t0.060000.h5.tmp.1"}) {
    EXPECT_TRUE(fs::exists(dir / kept)) << kept;
  }
  // keep = 1, and the just-written one older on the clock than another (a coarse clock): it stays.
  set_age(dir / "t0.050000.h5", 300);
  rotate_checkpoints(dir, dir / "t0.050000.h5", 1);
  EXPECT_TRUE(fs::exists(dir / "t0.050000.h5"));
  EXPECT_FALSE(fs::exists(dir / "t0.040000.h5"));
}

TEST(Checkpoints, LatestSkipsADamagedNewestAndFailedStates) {
  const test::ScratchDir scratch;
  const fs::path& dir = scratch.path;
  write_checkpoint(dir / "t0.010000.h5", 0.01);
  set_age(dir / "t0.010000.h5", 30);
  write_checkpoint(dir / "t0.020000.h5", 0.02);
  set_age(dir / "t0.020000.h5", 20);
  write_checkpoint(dir / "failed-t0.030000.h5", 0.03);
  set_age(dir / "failed-t0.030000.h5", 5);
  test::spit(dir / "t0.030000.h5.tmp.99", "half a checkpoint");
  EXPECT_EQ(find_latest_checkpoint(dir).path, dir / "t0.020000.h5");
  // Truncated newest (as a full disk leaves a file copied by hand): skipped with its reason.
  fs::resize_file(dir / "t0.020000.h5", fs::file_size(dir / "t0.020000.h5") / 2);
  set_age(dir / "t0.020000.h5", 20);
  ::testing::internal::CaptureStderr();
  const LatestCheckpoint latest = find_latest_checkpoint(dir);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(latest.path, dir / "t0.010000.h5");
  ASSERT_EQ(latest.skipped.size(), 1u);
  EXPECT_EQ(latest.skipped[0].rfind((dir / "t0.020000.h5").string() + ": ", 0), 0u) << latest.skipped[0];
  EXPECT_TRUE(find_latest_checkpoint(dir / "none").path.empty());
}

TEST(Checkpoints, LatestIsTheLatestSimulatedTimeWhateverTheFileTimes) {
  // A run folder copied with cp -r: the copies' modification times follow the copy, not the run (here t = 0.1917 s
  // written after t = 0.1998 s, and final.h5 the oldest on the clock).
  const test::ScratchDir scratch;
  const fs::path& dir = scratch.path;
  write_checkpoint(dir / "t0.199800.h5", 0.1998);
  set_age(dir / "t0.199800.h5", 50);
  write_checkpoint(dir / "t0.191700.h5", 0.1917);
  set_age(dir / "t0.191700.h5", 10);
  EXPECT_EQ(find_latest_checkpoint(dir).path, dir / "t0.199800.h5");
  write_checkpoint(dir / "final.h5", 0.2);
  set_age(dir / "final.h5", 90);
  EXPECT_EQ(find_latest_checkpoint(dir).path, dir / "final.h5");
  // A failed state is never a candidate, however late its time.
  write_checkpoint(dir / "failed-t0.250000.h5", 0.25);
  EXPECT_EQ(find_latest_checkpoint(dir).path, dir / "final.h5");
  // Equal simulated times (a run that ends at a checkpoint time): the same pick whichever was written last.
  write_checkpoint(dir / "t0.200000.h5", 0.2);
  set_age(dir / "t0.200000.h5", 95);
  const fs::path tie = find_latest_checkpoint(dir).path;
  set_age(dir / "t0.200000.h5", 5);
  EXPECT_EQ(find_latest_checkpoint(dir).path, tie);
  EXPECT_EQ(tie, dir / "t0.200000.h5");  // by name, the latest first, as list_checkpoints() orders equal times
  // The latest damaged: skipped with its reason, then the next latest in simulated time (not the newest file).
  for (const char* name : {"t0.200000.h5", "final.h5"}) {
    fs::resize_file(dir / name, fs::file_size(dir / name) / 2);
  }
  set_age(dir / "t0.191700.h5", 1);
  const LatestCheckpoint latest = find_latest_checkpoint(dir);
  EXPECT_EQ(latest.path, dir / "t0.199800.h5");
  EXPECT_EQ(latest.skipped.size(), 2u);
}

}  // namespace
}  // namespace fluidbed
