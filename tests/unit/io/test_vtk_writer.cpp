#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <stdexcept>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
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
  const VtiGrid grid = test::grid_2d(3, 2, 0.01, 0.02, 0.1, -0.05);
  std::vector<double> eps(6), u(6), v(6);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) {
      eps[static_cast<std::size_t>(i + 3 * j)] = 0.4 + i / 7.0 + j;
      u[static_cast<std::size_t>(i + 3 * j)] = -1e-300 * (i + 1);
      v[static_cast<std::size_t>(i + 3 * j)] = 1e300 * (j + 1);
    }
  }
  const double time = 0.1 / 3.0;
  write_vti(dir / "f.vti", grid, time, {test::scalar("voidage", eps), test::vector("gas_velocity", u, v)});
  EXPECT_EQ(test::temp_files_in(dir), 0);

  const auto parsed = parse_vtk(test::slurp(dir / "f.vti"));
  const std::string& h = parsed.header;
  EXPECT_NE(h.find(R"(<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64" )"
                   R"(compressor="vtkZLibDataCompressor">)"),
            std::string::npos)
      << h;
  EXPECT_TRUE(parsed.compressed);
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
  expect_same_bits(parsed.values<double>("voidage"), eps);
  const auto uvw = parsed.values<double>("gas_velocity");
  ASSERT_EQ(uvw.size(), 18u);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(uvw[3 * k], u[k]);
    EXPECT_EQ(uvw[3 * k + 1], v[k]);
    EXPECT_EQ(uvw[3 * k + 2], 0.0);
  }
}

TEST(VtkWriter, ArrayWithoutItsComponentsOrWithABadNameIsRejectedAndNothingWritten) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const VtiGrid grid = test::grid_2d(3, 2, 0.01, 0.02);
  const std::vector<double> good(6, 0.0);
  EXPECT_THROW(write_vti(dir / "f.vti", grid, 0.0, {test::scalar("a", good), {"b", {nullptr, nullptr, nullptr}, 1}}),
               std::invalid_argument);
  EXPECT_THROW(write_vti(dir / "f.vti", grid, 0.0, {{"u", {good.data(), nullptr, nullptr}, 2}}), std::invalid_argument);
  EXPECT_THROW(write_vti(dir / "f.vti", grid, 0.0, {{"u", {good.data(), good.data(), good.data()}, 4}}),
               std::invalid_argument);
  EXPECT_THROW(write_vti(dir / "f.vti", grid, 0.0, {test::scalar("a\"b", good)}), std::invalid_argument);
  EXPECT_THROW(write_vti(dir / "f.vti", grid, 0.0, {test::scalar("", good)}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "f.vti"));
  EXPECT_EQ(test::temp_files_in(dir), 0);
}

TEST(VtkWriter, UnstructuredGridSortedByIdWithoutTouchingStore) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const ParticleStore<2> store = test::sample_particles(0.25);
  const ParticleStore<2> before = store;
  write_vtu(dir / "p.vtu", 0.25, particle_arrays(store));
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
  write_vtu(dir / "p.vtu", 1.0, particle_arrays(ParticleStore<2>{}));
  const auto parsed = parse_vtk(test::slurp(dir / "p.vtu"));
  EXPECT_NE(parsed.header.find(R"(<Piece NumberOfPoints="0" NumberOfCells="0">)"), std::string::npos);
  EXPECT_TRUE(parsed.values<std::int64_t>("id").empty());
  // No blocks: VTK's own writer gives an empty array the same three-word header.
  const auto h = parsed.block_header("id");
  EXPECT_EQ(h.blocks, 0u);
  EXPECT_EQ(h.last_size, 0u);
}

// The appended data of every array: the block header of vtkZLibDataCompressor (UInt64 words), blocks of 64 KiB
// with the size of a partial last block, arrays packed one after the other from offset 0.
void expect_vtk_block_layout(const test::VtkParsed& parsed, std::size_t expected_arrays) {
  ASSERT_TRUE(parsed.compressed);
  ASSERT_EQ(parsed.arrays.size(), expected_arrays);
  std::vector<std::pair<std::size_t, std::string>> by_offset;
  for (const auto& [name, info] : parsed.arrays) by_offset.emplace_back(info.offset, name);
  std::sort(by_offset.begin(), by_offset.end());
  std::size_t next = 0;
  for (const auto& [offset, name] : by_offset) {
    EXPECT_EQ(offset, next) << name;
    const auto h = parsed.block_header(name);
    const std::string bytes = parsed.bytes(name);
    EXPECT_EQ(h.block_size, 65536u) << name;
    EXPECT_EQ(h.blocks, (bytes.size() + 65535) / 65536) << name;
    EXPECT_EQ(h.last_size, bytes.size() % 65536) << name;
    next = offset + h.bytes;
    for (const std::uint64_t c : h.compressed) next += c;
  }
  EXPECT_EQ(next + 3, parsed.appended.size());  // then "\n  " before </AppendedData>
}

TEST(VtkWriter, CompressedInVtkBlocksBitForBit) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  // 128 x 64 cells: a scalar array is exactly one full block, a vector array three.
  const VtiGrid grid = test::sample_large_grid();
  const auto f = test::sample_fields(0.25, grid);
  write_vti(dir / "f.vti", grid, 0.25,
            {test::scalar("voidage", f.voidage), test::vector("gas_velocity", f.ug, f.vg)});
  const auto vti = parse_vtk(test::slurp(dir / "f.vti"));
  expect_vtk_block_layout(vti, 2);
  EXPECT_EQ(vti.block_header("voidage").blocks, 1u);
  EXPECT_EQ(vti.block_header("voidage").last_size, 0u);
  EXPECT_EQ(vti.block_header("gas_velocity").blocks, 3u);
  expect_same_bits(vti.values<double>("voidage"), f.voidage);
  const auto uvw = vti.values<double>("gas_velocity");
  ASSERT_EQ(uvw.size(), 3 * grid.cells());
  for (std::size_t k = 0; k < grid.cells(); ++k) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(uvw[3 * k]), std::bit_cast<std::uint64_t>(f.ug[k]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(uvw[3 * k + 1]), std::bit_cast<std::uint64_t>(f.vg[k]));
  }

  // 20,000 particles: 480,000 bytes of points are 7 full blocks and a last one of 21,248 bytes.
  const ParticleStore<2> store = test::sample_particles(0.25, test::sample_large_particles);
  write_vtu(dir / "p.vtu", 0.25, particle_arrays(store));
  const std::string text = test::slurp(dir / "p.vtu");
  const auto vtu = parse_vtk(text);
  expect_vtk_block_layout(vtu, 10);
  const auto points = vtu.block_header("Points");
  EXPECT_EQ(points.blocks, 8u);
  EXPECT_EQ(points.last_size, 480000u - 7u * 65536u);
  const auto ids = vtu.values<std::int64_t>("id");
  const auto xyz = vtu.values<double>("Points");
  const auto spin = vtu.values<double>("angular_velocity");
  ASSERT_EQ(ids.size(), store.size());
  ASSERT_EQ(xyz.size(), 3 * store.size());
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::size_t s = store.size() - 1 - k;  // stored in decreasing id order
    ASSERT_EQ(ids[k], static_cast<std::int64_t>(k));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(xyz[3 * k]), std::bit_cast<std::uint64_t>(store.x[s]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(xyz[3 * k + 1]), std::bit_cast<std::uint64_t>(store.y[s]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(spin[k]), std::bit_cast<std::uint64_t>(store.omega[s]));
  }
  // Raw, the arrays of one particle take 97 bytes (points and velocity 24 each, id, connectivity, offsets,
  // diameter and spin 8 each, species and layer 4 each, type 1); compressed, the counters and the constant
  // arrays nearly vanish.
  EXPECT_LT(text.size(), 97u * store.size() * 7 / 10);
}

TEST(VtkWriter, CompressedBytesDoNotDependOnThreadCount) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const ParticleStore<2> store = test::sample_particles(0.5, test::sample_large_particles);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  write_vtu(dir / "one.vtu", 0.5, particle_arrays(store));
  omp_set_num_threads(4);
  write_vtu(dir / "four.vtu", 0.5, particle_arrays(store));
  omp_set_num_threads(threads);
  EXPECT_EQ(test::slurp(dir / "one.vtu"), test::slurp(dir / "four.vtu"));
}

TEST(VtkWriter, UnwritableFolderIsBadInput) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  EXPECT_THROW(write_vtu(dir / "nope" / "p.vtu", 0.0, particle_arrays(test::sample_particles(0.0))), Error);
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
  const VtiGrid grid = test::sample_grid();
  for (int k = 0; k < test::sample_frames; ++k) {
    const double t = test::sample_time(k);
    const auto f = test::sample_fields(t);
    const std::string vti = frame_file_name("fields", fields.next_index(), "vti");
    write_vti(dir / vti, grid, t,
              {test::scalar("voidage", f.voidage), test::scalar("pressure", f.pressure),
               test::vector("gas_velocity", f.ug, f.vg)});
    fields.add(t, vti);
    const std::string vtu = frame_file_name("particles", particles.next_index(), "vtu");
    write_vtu(dir / vtu, t, particle_arrays(test::sample_particles(t)));
    particles.add(t, vtu);
  }
  // Files of several compression blocks (a last block full and a last block partial) and an empty piece.
  const VtiGrid large = test::sample_large_grid();
  const auto lf = test::sample_fields(test::sample_time(1), large);
  write_vti(dir / "large.vti", large, test::sample_time(1),
            {test::scalar("voidage", lf.voidage), test::scalar("pressure", lf.pressure),
             test::vector("gas_velocity", lf.ug, lf.vg)});
  write_vtu(dir / "large.vtu", test::sample_time(1),
            particle_arrays(test::sample_particles(test::sample_time(1), test::sample_large_particles)));
  write_vtu(dir / "empty.vtu", 0.0, particle_arrays(ParticleStore<2>{}));
  const auto entries = read_pvd(dir / "fields.pvd");
  ASSERT_EQ(entries.size(), static_cast<std::size_t>(test::sample_frames));
  EXPECT_EQ(entries.back().file, "fields/000002.vti");
  for (const auto& e : read_pvd(dir / "particles.pvd")) EXPECT_TRUE(std::filesystem::exists(dir / e.file)) << e.file;
}

// 3D frames: an ImageData of nx x ny x nz cells with 3-component vectors, and spheres with z, vz and a spin
// vector; values exact (lossless zlib). Also written for tests/post/test_vtk_readback_3d.py (python-vtk).
TEST(VtkWriter, WritesSample3dForReadback) {
  const char* env = std::getenv("FLUIDBED_VTK_SAMPLE_DIR");
  const test::ScratchDir scratch;
  const std::filesystem::path dir = env != nullptr && *env != '\0' ? std::filesystem::path(env) : scratch.path;
  const double t = test::sample_time(2);
  const VtiGrid g = test::sample_grid_3d();
  const test::SampleFields3d f = test::sample_fields_3d(t);
  write_vti(dir / "3d.vti", g, t,
            {{"voidage", {f.voidage.data(), nullptr, nullptr}, 1},
             {"pressure", {f.pressure.data(), nullptr, nullptr}, 1},
             {"gas_velocity", {f.ug.data(), f.vg.data(), f.wg.data()}, 3}});
  const auto parsed = parse_vtk(test::slurp(dir / "3d.vti"));
  const std::string& h = parsed.header;
  EXPECT_NE(h.find(R"(WholeExtent="0 4 0 3 0 2")"), std::string::npos) << h;
  EXPECT_NE(h.find(R"(<Piece Extent="0 4 0 3 0 2">)"), std::string::npos) << h;
  EXPECT_NE(h.find(fmt::format(R"(Origin="{:.17g} {:.17g} {:.17g}")", 0.1, 0.0, 0.002)), std::string::npos) << h;
  EXPECT_NE(h.find(fmt::format(R"(Spacing="{:.17g} {:.17g} {:.17g}")", 0.0025, 0.005, 0.004)), std::string::npos) << h;
  expect_same_bits(parsed.values<double>("voidage"), f.voidage);
  const auto uvw = parsed.values<double>("gas_velocity");
  ASSERT_EQ(uvw.size(), 3 * g.cells());
  for (std::size_t k = 0; k < g.cells(); ++k) {
    EXPECT_EQ(uvw[3 * k], f.ug[k]);
    EXPECT_EQ(uvw[3 * k + 1], f.vg[k]);
    EXPECT_EQ(uvw[3 * k + 2], f.wg[k]);
  }

  const test::SampleParticles3d p = test::sample_particles_3d(t);
  write_vtu(dir / "3d.vtu", t, p.view());
  const auto pv = parse_vtk(test::slurp(dir / "3d.vtu"));
  EXPECT_EQ(pv.arrays.at("angular_velocity").components, 3);
  EXPECT_EQ(pv.arrays.at("velocity").components, 3);
  const auto pts = pv.values<double>("Points");
  const auto spin = pv.values<double>("angular_velocity");
  const auto ids = pv.values<std::int64_t>("id");
  ASSERT_EQ(ids.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    const auto slot = static_cast<std::size_t>(std::find(p.id.begin(), p.id.end(), static_cast<std::int64_t>(k)) - p.id.begin());
    EXPECT_EQ(ids[k], static_cast<std::int64_t>(k));  // sorted by id
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_EQ(pts[3 * k + a], p.x[a][slot]);
      EXPECT_EQ(spin[3 * k + a], p.omega[a][slot]);
    }
  }
}

// A 2D view of the store writes the same bytes as the store itself (the 2D frames did not change).
TEST(VtkWriter, TwoDimensionalViewGivesTheStoreBytes) {
  const test::ScratchDir scratch;
  const ParticleStore p = test::sample_particles(0.05);
  write_vtu(scratch.path / "a.vtu", 0.05, particle_arrays(p));
  write_vtu(scratch.path / "b.vtu", 0.05, particle_arrays(p));
  EXPECT_EQ(test::slurp(scratch.path / "a.vtu"), test::slurp(scratch.path / "b.vtu"));
}

}  // namespace
}  // namespace fluidbed

namespace fluidbed {
namespace {

TEST(VtkSeries, NumbersFramesAndContinuesAfterRestart) {
  const test::ScratchDir scratch;
  const auto& out = scratch.path / "run";
  const VtiGrid grid = test::sample_grid();
  {
    FieldSeries fields(out);
    ParticleSeries particles(out);
    for (int k = 0; k < 4; ++k) {
      const double t = 0.1 * k;
      const auto f = test::sample_fields(t);
      EXPECT_EQ(fields.write(t, grid, {test::scalar("voidage", f.voidage)}), static_cast<std::size_t>(k));
      EXPECT_EQ(particles.write(t, particle_arrays(test::sample_particles(t)), k % 2 == 0), static_cast<std::size_t>(k));
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
  EXPECT_EQ(fields.write(0.15, grid, {test::scalar("voidage", f.voidage)}), 2u);
  EXPECT_EQ(particles.write(0.15, particle_arrays(test::sample_particles(0.15))), 2u);
  const auto e = read_pvd(out / "fields.pvd");
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[2].time, 0.15);
  EXPECT_EQ(e[2].file, "fields/000002.vti");
  EXPECT_NE(test::slurp(out / "fields" / "000002.vti").find(">0.14999999999999999<"), std::string::npos);
  EXPECT_EQ(read_pvd(out / "particles.pvd").size(), 3u);
}

}  // namespace
}  // namespace fluidbed
