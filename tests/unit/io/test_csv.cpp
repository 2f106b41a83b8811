#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/csv.hpp"
#include "sample_series.hpp"
#include "test_helpers.hpp"

namespace fluidbed {
namespace {

const std::vector<std::string> monitor_columns = {"time_s", "kinetic_energy_J", "attached"};

TEST(CsvWriter, HeaderRowsFullPrecisionAndEmptyOptionals) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  CsvWriter w(dir / "m.csv", monitor_columns);
  EXPECT_EQ(test::slurp(dir / "m.csv"), "time_s,kinetic_energy_J,attached\n");
  const double third = 0.1 / 3.0;
  w.row({0.0, third, 1.0});
  w.row({third, -0.0, std::nullopt});
  w.row({0.5, std::numeric_limits<double>::denorm_min(), 0.0});
  // No close or flush call: each row is on disk as soon as row() returns.
  EXPECT_EQ(test::slurp(dir / "m.csv"),
            "time_s,kinetic_energy_J,attached\n"
            "0,0.033333333333333333,1\n"
            "0.033333333333333333,-0,\n"
            "0.5,4.9406564584124654e-324,0\n");
  double back = 0.0;
  const std::string s = "0.033333333333333333";
  std::from_chars(s.data(), s.data() + s.size(), back);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(back), std::bit_cast<std::uint64_t>(third));
}

TEST(CsvWriter, WrongValueCountIsAProgrammingError) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  CsvWriter w(dir / "m.csv", monitor_columns);
  EXPECT_THROW(w.row({1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(w.row({1.0, 2.0, 3.0, 4.0}), std::invalid_argument);
  EXPECT_EQ(test::slurp(dir / "m.csv"), "time_s,kinetic_energy_J,attached\n");
}

TEST(CsvWriter, ResumeDropsRowsAfterRestartTimeAndPartialLine) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  // As a killed run leaves it: the last line cut short.
  test::spit(dir / "m.csv",
             "time_s,kinetic_energy_J,attached\n0,1,1\n0.25,2,\n0.5,3,0\n0.75,4,0\n1,5,0\n1.25,6");
  {
    CsvWriter w = CsvWriter::resume(dir / "m.csv", monitor_columns, 0.5);
    EXPECT_EQ(test::slurp(dir / "m.csv"), "time_s,kinetic_energy_J,attached\n0,1,1\n0.25,2,\n0.5,3,0\n");
    w.row({0.625, 3.5, 1.0});
  }
  EXPECT_EQ(test::slurp(dir / "m.csv"), "time_s,kinetic_energy_J,attached\n0,1,1\n0.25,2,\n0.5,3,0\n0.625,3.5,1\n");
  EXPECT_EQ(test::temp_files_in(dir), 0);
}

TEST(CsvWriter, ResumeWithoutFileStartsNew) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  CsvWriter w = CsvWriter::resume(dir / "b.csv", monitor_columns, 2.0);
  w.row({2.5, 1.0, 0.0});
  EXPECT_EQ(test::slurp(dir / "b.csv"), "time_s,kinetic_energy_J,attached\n2.5,1,0\n");
}

TEST(CsvWriter, ResumeWithOtherHeaderIsBadInput) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  test::spit(dir / "m.csv", "time_s,other\n0,1\n");
  try {
    (void)CsvWriter::resume(dir / "m.csv", monitor_columns, 1.0);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_NE(std::string(e.what()).find((dir / "m.csv").string() + ": row 1"), std::string::npos) << e.what();
  }
  EXPECT_EQ(test::slurp(dir / "m.csv"), "time_s,other\n0,1\n");  // left as it was
}

TEST(CsvWriter, MovedWriterKeepsAppending) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  CsvWriter a(dir / "m.csv", {"time_s"});
  CsvWriter b = std::move(a);
  b.row({1.0});
  EXPECT_EQ(test::slurp(dir / "m.csv"), "time_s\n1\n");
}

TEST(ParticlesCsv, WritesSortedByIdAndReadsBackBitExact) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  ParticleStore<2> p = test::sample_particles(0.1 / 3.0);
  p.vx[2] = -0.0;
  p.omega[0] = 1e-300;
  write_particles_csv(dir / "p.csv", particle_arrays(p));
  const std::string text = test::slurp(dir / "p.csv");
  EXPECT_EQ(text.substr(0, text.find('\n')), "id,x,y,vx,vy,omega,species");
  const auto rows = read_particles_csv(dir / "p.csv");
  ASSERT_EQ(rows.size(), p.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k].id, static_cast<std::int64_t>(k));
    const std::size_t s = static_cast<std::size_t>(std::find(p.id.begin(), p.id.end(), rows[k].id) - p.id.begin());
    EXPECT_EQ(std::bit_cast<std::uint64_t>(rows[k].x), std::bit_cast<std::uint64_t>(p.x[s]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(rows[k].y), std::bit_cast<std::uint64_t>(p.y[s]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(rows[k].vx), std::bit_cast<std::uint64_t>(p.vx[s]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(rows[k].vy), std::bit_cast<std::uint64_t>(p.vy[s]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(rows[k].omega), std::bit_cast<std::uint64_t>(p.omega[s]));
    EXPECT_EQ(rows[k].species, p.species[s]);
  }
}

TEST(ParticlesCsv, AcceptsWindowsLineEndsByteOrderMarkAndSpaces) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  test::spit(dir / "p.csv", "\xEF\xBB\xBFid,x,y,vx,vy,omega,species\r\n 7 , 0.1,0.2,0,0,0,1\r\n\r\n");
  const auto rows = read_particles_csv(dir / "p.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].id, 7);
  EXPECT_EQ(rows[0].x, 0.1);
  EXPECT_EQ(rows[0].species, 1);
}

TEST(ParticlesCsv, MissingFileIsBadInput) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  try {
    read_particles_csv(dir / "none.csv");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_NE(std::string(e.what()).find((dir / "none.csv").string() + ": cannot read"), std::string::npos);
  }
}

// 3D particle files: the header with z, vz and the spin vector, every value back bit for bit, sorted by id.
TEST(ParticlesCsv, ThreeDimensionalRoundTripIsBitExact) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  test::SampleParticles3d p = test::sample_particles_3d(0.1 / 3.0);
  p.v[2][1] = -0.0;
  p.omega[0][3] = 1e-300;
  write_particles_csv(dir / "p.csv", p.view());
  const std::string text = test::slurp(dir / "p.csv");
  EXPECT_EQ(text.substr(0, text.find('\n')), "id,x,y,z,vx,vy,vz,omega_x,omega_y,omega_z,species");
  const auto rows = read_particles_csv(dir / "p.csv", 3);
  ASSERT_EQ(rows.size(), p.id.size());
  auto same = [](double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); };
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k].id, static_cast<std::int64_t>(k));
    const auto s = static_cast<std::size_t>(std::find(p.id.begin(), p.id.end(), rows[k].id) - p.id.begin());
    EXPECT_TRUE(same(rows[k].x, p.x[0][s]) && same(rows[k].y, p.x[1][s]) && same(rows[k].z, p.x[2][s])) << k;
    EXPECT_TRUE(same(rows[k].vx, p.v[0][s]) && same(rows[k].vy, p.v[1][s]) && same(rows[k].vz, p.v[2][s])) << k;
    EXPECT_TRUE(same(rows[k].omega_x, p.omega[0][s]) && same(rows[k].omega_y, p.omega[1][s]) &&
                same(rows[k].omega, p.omega[2][s])) << k;
    EXPECT_EQ(rows[k].species, p.species[s]);
  }
  // A file of one dimension is refused, by name, by a case of the other.
  for (const auto& [dim, file] : {std::pair{2, "p.csv"}, std::pair{3, "q.csv"}}) {
    if (dim == 3) write_particles_csv(dir / file, particle_arrays(test::sample_particles(0.0)));
    try {
      read_particles_csv(dir / file, dim);
      ADD_FAILURE() << "accepted " << file << " as " << dim << "D";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(fmt::format("row 1, column 1: a {}D particle file", 5 - dim)),
                std::string::npos) << e.what();
    }
  }
  // Centres outside the box, in z too, are refused against the case's domain.
  DomainConfig box{3, 0.1, 0.1, 0.02, {0.0, -9.81, 0.0}};  // z up to 0.012 m
  EXPECT_NO_THROW(check_particle_rows(rows, "p.csv", box, 2));
  box.depth = 0.01;
  EXPECT_THROW(check_particle_rows(rows, "p.csv", box, 2), Error);
}

struct BadCsv {
  const char* label;
  const char* content;
  const char* expected;  ///< substring of the message after "<file>: "
};

class ParticlesCsvRejects : public ::testing::TestWithParam<BadCsv> {};

TEST_P(ParticlesCsvRejects, NamesRowAndColumn) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto path = dir / "p.csv";
  test::spit(path, GetParam().content);
  try {
    read_particles_csv(path);
    FAIL() << "accepted: " << GetParam().content;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path.string() + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find(GetParam().expected), std::string::npos) << msg;
  }
}

#define HEADER "id,x,y,vx,vy,omega,species\n"
INSTANTIATE_TEST_SUITE_P(
    Cases, ParticlesCsvRejects,
    ::testing::Values(
        BadCsv{"EmptyFile", "", "row 1, column 1: empty file"},
        BadCsv{"WrongHeaderName", "id,x,z,vx,vy,omega,species\n1,0,0,0,0,0,0\n", "row 1, column 3: header 'z' where 'y'"},
        BadCsv{"HeaderMissingColumn", "id,x,y,vx,vy,omega\n1,0,0,0,0,0\n", "row 1, column 7: missing header column 'species'"},
        BadCsv{"HeaderExtraColumn", "id,x,y,vx,vy,omega,species,layer\n", "row 1, column 8: extra header column 'layer'"},
        BadCsv{"NoRows", HEADER, "row 2, column 1: no particle rows"},
        BadCsv{"MissingColumn", HEADER "1,0,0,0,0,0\n", "row 2, column 7: missing value for 'species'"},
        BadCsv{"ExtraColumn", HEADER "1,0,0,0,0,0,0\n2,0,0,0,0,0,0,9\n", "row 3, column 8: extra value '9'"},
        BadCsv{"NotANumber", HEADER "1,0.1,abc,0,0,0,0\n", "row 2, column 3: y 'abc' is not a number"},
        BadCsv{"TrailingGarbage", HEADER "1,0.5m,0,0,0,0,0\n", "row 2, column 2: x '0.5m' is not a number"},
        BadCsv{"NaN", HEADER "1,0,0,nan,0,0,0\n", "row 2, column 4: vx 'nan' is not finite"},
        BadCsv{"Infinity", HEADER "1,0,0,0,0,-inf,0\n", "row 2, column 6: omega '-inf' is not finite"},
        BadCsv{"OutOfRange", HEADER "1,0,0,0,1e400,0,0\n", "row 2, column 5: vy '1e400' is out of the range"},
        BadCsv{"EmptyCell", HEADER "1,,0,0,0,0,0\n", "row 2, column 2: empty value for 'x'"},
        BadCsv{"DuplicateId", HEADER "1,0,0,0,0,0,0\n2,0,0,0,0,0,0\n1,0,0,0,0,0,0\n",
               "row 4, column 1: duplicate id 1 (first in row 2)"},
        BadCsv{"FractionalId", HEADER "1.5,0,0,0,0,0,0\n", "row 2, column 1: id '1.5' is not an integer"},
        BadCsv{"NegativeId", HEADER "-3,0,0,0,0,0,0\n", "row 2, column 1: id -3 is outside"},
        BadCsv{"NegativeSpecies", HEADER "1,0,0,0,0,0,-1\n", "row 2, column 7: species -1 is outside"},
        BadCsv{"FractionalSpecies", HEADER "1,0,0,0,0,0,0.5\n", "row 2, column 7: species '0.5' is not an integer"},
        BadCsv{"BlankLineInside", HEADER "1,0,0,0,0,0,0\n\n2,0,0,0,0,0,0\n", "row 3, column 1: empty row"}),
    [](const ::testing::TestParamInfo<BadCsv>& info) { return std::string(info.param.label); });
#undef HEADER

}  // namespace
}  // namespace fluidbed
