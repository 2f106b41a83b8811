#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <stdexcept>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/pvd.hpp"
#include "io/vtk_writer.hpp"
#include "sample_series.hpp"
#include "test_helpers.hpp"
#include "vtk_parse.hpp"

namespace fluidbed {
namespace {

using test::parse_vtk;

// Binary output: every value must come back bit for bit, so the comparisons below are exact.
void expect_same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a[k]), std::bit_cast<std::uint64_t>(b[k])) << "index " << k;
  }
}

TEST(VtkWriter, ImageDataHeaderAndCellArrays) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const Grid2 grid{3, 2, 0.01, 0.02, 0.1, -0.05};
  Field2 eps(3, 2), u(3, 2), v(3, 2);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) {
      eps(i, j) = 0.4 + i / 7.0 + j;
      u(i, j) = -1e-300 * (i + 1);
      v(i, j) = 1e300 * (j + 1);
    }
  }
  const double time = 0.1 / 3.0;
  write_vti(dir / "f.vti", grid, time, {VtiArray::scalar("voidage", eps), VtiArray::vector("gas_velocity", u, v)});
  EXPECT_EQ(test::temp_files_in(dir), 0);

  const auto parsed = parse_vtk(test::slurp(dir / "f.vti"));
  const std::string& h = parsed.header;
  EXPECT_NE(h.find(R"(<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">)"),
            std::string::npos);
  EXPECT_NE(h.find(R"(WholeExtent="0 3 0 2 0 0")"), std::string::npos) << h;
  EXPECT_NE(h.find(R"(<Piece Extent="0 3 0 2 0 0">)"), std::string::npos) << h;
  EXPECT_NE(h.find(fmt::format(R"(Origin="{:.17g} {:.17g} 0")", 0.1, -0.05)), std::string::npos) << h;
  EXPECT_NE(h.find(fmt::format(R"(Spacing="{:.17g} {:.17g} 1")", 0.01, 0.02)), std::string::npos) << h;
  EXPECT_NE(h.find(fmt::format(R"(Name="TimeValue" NumberOfTuples="1" format="ascii">{:.17g}<)", time)),
            std::string::npos)
      << h;
  ASSERT_EQ(parsed.arrays.size(), 2u);
  EXPECT_EQ(parsed.arrays.at("voidage").type, "Float64");
  EXPECT_EQ(parsed.arrays.at("voidage").components, 1);
  EXPECT_EQ(parsed.arrays.at("gas_velocity").components, 3);
  expect_same_bits(parsed.values<double>("voidage"), eps.v);
  const auto uvw = parsed.values<double>("gas_velocity");
  ASSERT_EQ(uvw.size(), 18u);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(uvw[3 * k], u.v[k]);
    EXPECT_EQ(uvw[3 * k + 1], v.v[k]);
    EXPECT_EQ(uvw[3 * k + 2], 0.0);
  }
}

TEST(VtkWriter, FieldOfWrongShapeIsRejectedAndNothingWritten) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const Grid2 grid{3, 2, 0.01, 0.02, 0.0, 0.0};
  const Field2 good(3, 2), bad(2, 3);
  EXPECT_THROW(write_vti(dir / "f.vti", grid, 0.0, {VtiArray::scalar("a", good), VtiArray::scalar("b", bad)}),
               std::invalid_argument);
  EXPECT_THROW(write_vti(dir / "f.vti", grid, 0.0, {VtiArray::vector("u", good, bad)}), std::invalid_argument);
  EXPECT_THROW(write_vti(dir / "f.vti", grid, 0.0, {VtiArray::scalar("a\"b", good)}), std::invalid_argument);
  EXPECT_THROW(write_vti(dir / "f.vti", grid, 0.0, {VtiArray::scalar("", good)}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "f.vti"));
  EXPECT_EQ(test::temp_files_in(dir), 0);
}

TEST(VtkWriter, UnstructuredGridSortedByIdWithoutTouchingStore) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const ParticleStore store = test::sample_particles(0.25);
  const ParticleStore before = store;
  write_vtu(dir / "p.vtu", 0.25, store);
  EXPECT_EQ(store.id, before.id);  // the store's order is not changed

  const auto parsed = parse_vtk(test::slurp(dir / "p.vtu"));
  EXPECT_NE(parsed.header.find(R"(<VTKFile type="UnstructuredGrid")"), std::string::npos);
  EXPECT_NE(parsed.header.find(R"(<Piece NumberOfPoints="5" NumberOfCells="5">)"), std::string::npos);
  EXPECT_NE(parsed.header.find(R"(header_type="UInt64")"), std::string::npos);
  EXPECT_EQ(parsed.arrays.at("id").type, "Int64");
  EXPECT_EQ(parsed.arrays.at("species").type, "Int32");
  EXPECT_EQ(parsed.arrays.at("layer").type, "Int32");
  EXPECT_EQ(parsed.arrays.at("diameter").type, "Float64");
  EXPECT_EQ(parsed.arrays.at("velocity").components, 3);
  EXPECT_EQ(parsed.arrays.at("angular_velocity").components, 1);
  EXPECT_EQ(parsed.arrays.at("types").type, "UInt8");

  const auto ids = parsed.values<std::int64_t>("id");
  EXPECT_EQ(ids, (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
  const auto points = parsed.values<double>("Points");
  const auto vel = parsed.values<double>("velocity");
  const auto spin = parsed.values<double>("angular_velocity");
  const auto diameter = parsed.values<double>("diameter");
  const auto species = parsed.values<std::int32_t>("species");
  const auto layer = parsed.values<std::int32_t>("layer");
  ASSERT_EQ(points.size(), 15u);
  ASSERT_EQ(vel.size(), 15u);
  for (std::size_t k = 0; k < 5; ++k) {
    // Slot of id k in the (unsorted) store.
    const std::size_t s = static_cast<std::size_t>(std::find(store.id.begin(), store.id.end(), ids[k]) - store.id.begin());
    EXPECT_EQ(points[3 * k], store.x[s]);
    EXPECT_EQ(points[3 * k + 1], store.y[s]);
    EXPECT_EQ(points[3 * k + 2], 0.0);
    EXPECT_EQ(vel[3 * k], store.vx[s]);
    EXPECT_EQ(vel[3 * k + 1], store.vy[s]);
    EXPECT_EQ(vel[3 * k + 2], 0.0);
    EXPECT_EQ(spin[k], store.omega[s]);
    EXPECT_EQ(diameter[k], 2.0 * store.radius[s]);
    EXPECT_EQ(species[k], store.species[s]);
    EXPECT_EQ(layer[k], store.layer[s]);
  }
  EXPECT_EQ(parsed.values<std::int64_t>("connectivity"), (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(parsed.values<std::int64_t>("offsets"), (std::vector<std::int64_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(parsed.values<std::uint8_t>("types"), (std::vector<std::uint8_t>(5, 1)));
}

TEST(VtkWriter, EmptyParticleStoreGivesEmptyPiece) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  write_vtu(dir / "p.vtu", 1.0, ParticleStore{});
  const auto parsed = parse_vtk(test::slurp(dir / "p.vtu"));
  EXPECT_NE(parsed.header.find(R"(<Piece NumberOfPoints="0" NumberOfCells="0">)"), std::string::npos);
  EXPECT_TRUE(parsed.values<std::int64_t>("id").empty());
}

TEST(VtkWriter, UnwritableFolderIsBadInput) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  EXPECT_THROW(write_vtu(dir / "nope" / "p.vtu", 0.0, test::sample_particles(0.0)), Error);
}

// Writes the series that tests/post/test_vtk_readback.py reads with python-vtk: into $FLUIDBED_VTK_SAMPLE_DIR
// when set, else into a scratch folder (then it only checks that the series is complete).
TEST(VtkWriter, WritesSampleSeriesForReadback) {
  const char* env = std::getenv("FLUIDBED_VTK_SAMPLE_DIR");
  const test::ScratchDir scratch;
  const std::filesystem::path dir = env != nullptr && *env != '\0' ? std::filesystem::path(env) : scratch.path;
  ensure_directory(dir / "fields");
  ensure_directory(dir / "particles");
  PvdCollection fields(dir / "fields.pvd");
  PvdCollection particles(dir / "particles.pvd");
  const Grid2 grid = test::sample_grid();
  for (int k = 0; k < test::sample_frames; ++k) {
    const double t = test::sample_time(k);
    const auto f = test::sample_fields(t);
    const std::string vti = frame_file_name("fields", fields.next_index(), "vti");
    write_vti(dir / vti, grid, t,
              {VtiArray::scalar("voidage", f.voidage), VtiArray::scalar("pressure", f.pressure),
               VtiArray::vector("gas_velocity", f.ug, f.vg)});
    fields.add(t, vti);
    const std::string vtu = frame_file_name("particles", particles.next_index(), "vtu");
    write_vtu(dir / vtu, t, test::sample_particles(t));
    particles.add(t, vtu);
  }
  const auto entries = read_pvd(dir / "fields.pvd");
  ASSERT_EQ(entries.size(), static_cast<std::size_t>(test::sample_frames));
  EXPECT_EQ(entries.back().file, "fields/000002.vti");
  for (const auto& e : read_pvd(dir / "particles.pvd")) EXPECT_TRUE(std::filesystem::exists(dir / e.file)) << e.file;
}

}  // namespace
}  // namespace fluidbed

namespace fluidbed {
namespace {

TEST(VtkSeries, NumbersFramesAndContinuesAfterRestart) {
  const test::ScratchDir scratch;
  const auto& out = scratch.path / "run";
  const Grid2 grid = test::sample_grid();
  {
    FieldSeries fields(out);
    ParticleSeries particles(out);
    for (int k = 0; k < 4; ++k) {
      const double t = 0.1 * k;
      const auto f = test::sample_fields(t);
      EXPECT_EQ(fields.write(t, grid, {VtiArray::scalar("voidage", f.voidage)}), static_cast<std::size_t>(k));
      EXPECT_EQ(particles.write(t, test::sample_particles(t), k % 2 == 0), static_cast<std::size_t>(k));
    }
  }
  EXPECT_TRUE(std::filesystem::exists(out / "fields" / "000003.vti"));
  EXPECT_TRUE(std::filesystem::exists(out / "particles" / "000002.csv"));
  EXPECT_FALSE(std::filesystem::exists(out / "particles" / "000001.csv"));

  // Restart from a checkpoint at t = 0.1 (frame 1): frames 2 and 3 are dropped and then rewritten.
  FieldSeries fields(out, 0.1);
  ParticleSeries particles(out, 0.1);
  EXPECT_EQ(fields.collection().entries().size(), 2u);
  EXPECT_EQ(particles.collection().entries().size(), 2u);
  const auto f = test::sample_fields(0.15);
  EXPECT_EQ(fields.write(0.15, grid, {VtiArray::scalar("voidage", f.voidage)}), 2u);
  EXPECT_EQ(particles.write(0.15, test::sample_particles(0.15)), 2u);
  const auto e = read_pvd(out / "fields.pvd");
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[2].time, 0.15);
  EXPECT_EQ(e[2].file, "fields/000002.vti");
  EXPECT_NE(test::slurp(out / "fields" / "000002.vti").find(">0.14999999999999999<"), std::string::npos);
  EXPECT_EQ(read_pvd(out / "particles.pvd").size(), 3u);
}

}  // namespace
}  // namespace fluidbed
