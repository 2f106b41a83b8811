#include <gtest/gtest.h>

#include <stdexcept>

#include "core/error.hpp"
#include "io/pvd.hpp"
#include "test_helpers.hpp"

namespace fluidbed {
namespace {

TEST(Pvd, FrameFileNameHasSixDigits) {
  EXPECT_EQ(frame_file_name("fields", 12, "vti"), "fields/000012.vti");
  EXPECT_EQ(frame_file_name("particles", 0, "vtu"), "particles/000000.vtu");
  EXPECT_EQ(frame_file_name("particles", 1234567, "vtu"), "particles/1234567.vtu");
}

TEST(Pvd, EveryAddRewritesTheIndexWithExactTimes) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  PvdCollection c(dir / "fields.pvd");
  EXPECT_FALSE(std::filesystem::exists(dir / "fields.pvd"));  // nothing before the first frame
  const double t1 = 0.1 / 3.0;
  c.add(0.0, "fields/000000.vti");
  EXPECT_EQ(read_pvd(dir / "fields.pvd").size(), 1u);
  c.add(t1, "fields/000001.vti");
  const auto e = read_pvd(dir / "fields.pvd");
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].time, 0.0);
  EXPECT_EQ(e[1].time, t1);  // {:.17g} round-trips a double exactly
  EXPECT_EQ(e[1].file, "fields/000001.vti");
  EXPECT_EQ(c.next_index(), 2u);
  EXPECT_EQ(test::temp_files_in(dir), 0);
  const std::string text = test::slurp(dir / "fields.pvd");
  EXPECT_NE(text.find(R"(<VTKFile type="Collection")"), std::string::npos);
  EXPECT_NE(text.find(R"(file="fields/000001.vti")"), std::string::npos);
}

TEST(Pvd, SameTimeReplacesEarlierTimeIsRejected) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  PvdCollection c(dir / "p.pvd");
  c.add(0.5, "particles/000000.vtu");
  c.add(0.5, "particles/000001.vtu");
  ASSERT_EQ(c.entries().size(), 1u);
  EXPECT_EQ(c.entries()[0].file, "particles/000001.vtu");
  EXPECT_THROW(c.add(0.25, "particles/000002.vtu"), std::invalid_argument);
  EXPECT_EQ(read_pvd(dir / "p.pvd").size(), 1u);
}

TEST(Pvd, ResumeDropsLaterEntriesAndAppends) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  {
    PvdCollection c(dir / "fields.pvd");
    for (int k = 0; k < 5; ++k) c.add(0.025 * k, frame_file_name("fields", static_cast<std::size_t>(k), "vti"));
  }
  // Restart from a checkpoint at t = 0.05: frames at 0.075 and 0.1 belong to the abandoned future.
  PvdCollection c = PvdCollection::resume(dir / "fields.pvd", 0.05);
  ASSERT_EQ(c.entries().size(), 3u);
  EXPECT_EQ(c.entries().back().time, 0.05);
  EXPECT_EQ(c.next_index(), 3u);
  EXPECT_EQ(read_pvd(dir / "fields.pvd").size(), 3u);  // rewritten at once, before any new frame
  c.add(0.06, frame_file_name("fields", c.next_index(), "vti"));
  const auto e = read_pvd(dir / "fields.pvd");
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[3].time, 0.06);
  EXPECT_EQ(e[3].file, "fields/000003.vti");
}

TEST(Pvd, ResumeWithoutFileStartsEmpty) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  PvdCollection c = PvdCollection::resume(dir / "fields.pvd", 1.0);
  EXPECT_TRUE(c.entries().empty());
  EXPECT_EQ(c.next_index(), 0u);
  EXPECT_FALSE(std::filesystem::exists(dir / "fields.pvd"));
}

TEST(Pvd, ResumeOfForeignOrBrokenFileIsBadInput) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  test::spit(dir / "a.pvd", "time,value\n0,1\n");
  test::spit(dir / "b.pvd",
             "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"abc\" file=\"x.vti\"/></Collection>"
             "</VTKFile>");
  test::spit(dir / "c.pvd", "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" file=\"x.vti\"/>");
  for (const char* name : {"a.pvd", "b.pvd", "c.pvd"}) {
    try {
      PvdCollection::resume(dir / name, 1.0);
      ADD_FAILURE() << name << ": expected an Error";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::BadInput);
      EXPECT_EQ(std::string(e.what()).rfind((dir / name).string() + ": ", 0), 0u) << e.what();
    }
  }
}

TEST(Pvd, FileNamesAreEscaped) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  PvdCollection c(dir / "x.pvd");
  c.add(1.0, "a&b/\"q\"<1>.vti");
  EXPECT_EQ(read_pvd(dir / "x.pvd").at(0).file, "a&b/\"q\"<1>.vti");
}

}  // namespace
}  // namespace fluidbed
