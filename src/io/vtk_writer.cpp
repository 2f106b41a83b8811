#include "io/vtk_writer.hpp"

#include <fmt/format.h>

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"

namespace fluidbed {
namespace {

// The files declare byte_order="LittleEndian" and we copy memory as is.
static_assert(std::endian::native == std::endian::little, "VTK writer assumes a little-endian host");

// Each array's appended data is compressed in independent blocks of this many uncompressed bytes, the layout of
// vtkZLibDataCompressor. Blocks are the unit of parallel work; larger blocks compress no better (a 22,000-particle
// frame: 47.2% of the raw size with 32 KiB blocks, 47.2% with 1 MiB).
constexpr std::size_t kBlockBytes = std::size_t{1} << 16;
// zlib level 1: a frame of full-precision doubles is mostly mantissa noise, so level 6 saves only 1% more
// (46.3% against 47.2% of the raw size) for 2.5 times the compression time.
constexpr int kZlibLevel = Z_BEST_SPEED;

// Collects the XML header and the appended data. One DataArray's appended block, with header_type="UInt64" and
// compressor="vtkZLibDataCompressor" (VTK XML file format, "compressed data"): UInt64 number of blocks, UInt64
// uncompressed block size, UInt64 uncompressed size of the last block (0 when it is full), one UInt64 compressed
// size per block, then the zlib streams of the blocks one after the other. A DataArray's offset counts from the
// first byte after the '_' marker, so the header can only be written once every array is compressed.
class VtkFile {
 public:
  std::string xml;

  template <class T>
  void data_array(std::string_view type, std::string_view name, int components, const std::vector<T>& values) {
    // Names go into an XML attribute unescaped; ParaView also expects them printable.
    if (name.empty() || name.find_first_of("\"<>&\n") != std::string_view::npos) {
      throw std::invalid_argument("VTK array name '" + std::string(name) + "' is empty or has XML characters");
    }
    xml += fmt::format(R"(        <DataArray type="{}" Name="{}" NumberOfComponents="{}" format="appended" offset=")",
                       type, name, components);
    pieces_.push_back(std::move(xml));
    xml = "\"/>\n";
    raw_.emplace_back(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }

  void time_value(double time) {
    xml += "    <FieldData>\n";
    xml += fmt::format(
        R"(      <DataArray type="Float64" Name="TimeValue" NumberOfTuples="1" format="ascii">{:.17g}</DataArray>)"
        "\n",
        time);
    xml += "    </FieldData>\n";
  }

  std::string finish(std::string_view type) const {
    const std::vector<std::string> blocks = compressed_blocks();
    std::string out;
    out += "<?xml version=\"1.0\"?>\n";
    out += fmt::format(
        R"(<VTKFile type="{}" version="1.0" byte_order="LittleEndian" header_type="UInt64" )"
        R"(compressor="vtkZLibDataCompressor">)"
        "\n",
        type);
    std::string appended;
    std::size_t block = 0;
    for (std::size_t a = 0; a < raw_.size(); ++a) {
      out += pieces_[a];
      out += std::to_string(appended.size());
      const std::size_t bytes = raw_[a].size();
      const std::size_t n_blocks = block_count(bytes);
      std::vector<std::uint64_t> header{n_blocks, kBlockBytes, bytes % kBlockBytes};
      for (std::size_t b = 0; b < n_blocks; ++b) header.push_back(blocks[block + b].size());
      appended.append(reinterpret_cast<const char*>(header.data()), header.size() * sizeof(std::uint64_t));
      for (std::size_t b = 0; b < n_blocks; ++b) appended += blocks[block + b];
      block += n_blocks;
    }
    out += xml;
    out += "  <AppendedData encoding=\"raw\">\n   _";
    out += appended;
    out += "\n  </AppendedData>\n</VTKFile>\n";
    return out;
  }

 private:
  std::vector<std::string> pieces_;       // XML before each array's offset value
  std::vector<std::string> raw_;          // each array's bytes, copied: a caller's vector may be a temporary

  static std::size_t block_count(std::size_t bytes) { return (bytes + kBlockBytes - 1) / kBlockBytes; }

  // The blocks of every array in file order, compressed in one parallel loop. Each block is compressed on its own,
  // so the bytes written do not depend on the thread count.
  std::vector<std::string> compressed_blocks() const {
    struct Job {
      const char* src;
      std::size_t len;
    };
    std::vector<Job> jobs;
    for (const std::string& r : raw_) {
      for (std::size_t b = 0; b < block_count(r.size()); ++b) {
        jobs.push_back({r.data() + b * kBlockBytes, std::min(kBlockBytes, r.size() - b * kBlockBytes)});
      }
    }
    std::vector<std::string> out(jobs.size());
    std::vector<int> status(jobs.size(), Z_OK);
    const auto n = static_cast<std::ptrdiff_t>(jobs.size());
#pragma omp parallel for schedule(dynamic)
    for (std::ptrdiff_t k = 0; k < n; ++k) {
      const Job& j = jobs[static_cast<std::size_t>(k)];
      std::string& dst = out[static_cast<std::size_t>(k)];
      uLongf dst_len = compressBound(static_cast<uLong>(j.len));
      dst.resize(dst_len);
      status[static_cast<std::size_t>(k)] = compress2(reinterpret_cast<Bytef*>(dst.data()), &dst_len,
                                                      reinterpret_cast<const Bytef*>(j.src), static_cast<uLong>(j.len),
                                                      kZlibLevel);
      dst.resize(dst_len);
    }
    for (const int st : status) {
      // compressBound sizes the output, so only memory can run out.
      if (st != Z_OK) throw std::runtime_error(fmt::format("zlib compression of a VTK frame failed (code {})", st));
    }
    return out;
  }
};

void check_shape(const Grid2& grid, const Field2* f, const std::string& name) {
  if (f == nullptr) throw std::invalid_argument("write_vti: array '" + name + "' has no field");
  if (f->nx != grid.nx || f->ny != grid.ny || f->size() != grid.cells()) {
    throw std::invalid_argument(fmt::format("write_vti: array '{}' is {} x {}, the grid {} x {}", name, f->nx,
                                            f->ny, grid.nx, grid.ny));
  }
}

}  // namespace

VtiGrid VtiGrid::of(const Grid2& g) {
  VtiGrid v;
  v.dimension = 2;
  v.n = {g.nx, g.ny, 1};
  v.h = {g.dx, g.dy, 0.0};
  v.origin = {g.x0, g.y0, 0.0};
  return v;
}

void write_vti(const std::filesystem::path& path, const VtiGrid& grid, double time,
               const std::vector<VtiComponents>& cell_data) {
  const std::size_t cells = grid.cells();
  VtkFile file;
  if (grid.dimension == 3) {
    file.xml += fmt::format(R"(  <ImageData WholeExtent="0 {} 0 {} 0 {}" Origin="{:.17g} {:.17g} {:.17g}" )"
                            R"(Spacing="{:.17g} {:.17g} {:.17g}">)"
                            "\n",
                            grid.n[0], grid.n[1], grid.n[2], grid.origin[0], grid.origin[1], grid.origin[2], grid.h[0],
                            grid.h[1], grid.h[2]);
    file.time_value(time);
    file.xml += fmt::format(R"(    <Piece Extent="0 {} 0 {} 0 {}">)"
                            "\n",
                            grid.n[0], grid.n[1], grid.n[2]);
  } else {
    // z spacing 1: VTK needs a positive spacing on the collapsed axis.
    file.xml += fmt::format(R"(  <ImageData WholeExtent="0 {} 0 {} 0 0" Origin="{:.17g} {:.17g} 0" Spacing="{:.17g} {:.17g} 1">)"
                            "\n",
                            grid.n[0], grid.n[1], grid.origin[0], grid.origin[1], grid.h[0], grid.h[1]);
    file.time_value(time);
    file.xml += fmt::format(R"(    <Piece Extent="0 {} 0 {} 0 0">)"
                            "\n",
                            grid.n[0], grid.n[1]);
  }
  file.xml += "      <CellData>\n";
  for (const VtiComponents& a : cell_data) {
    if (a.count != 1 && a.count != 2 && a.count != 3) {
      throw std::invalid_argument(fmt::format("write_vti: array '{}' has {} components (1, 2 or 3)", a.name, a.count));
    }
    for (int c = 0; c < a.count; ++c) {
      if (a.c[static_cast<std::size_t>(c)] == nullptr) {
        throw std::invalid_argument(fmt::format("write_vti: array '{}' lacks component {}", a.name, c));
      }
    }
    if (a.count == 1) {
      file.data_array("Float64", a.name, 1, std::vector<double>(a.c[0], a.c[0] + cells));
    } else {
      // Vectors always have 3 components in VTK; a 2D vector's z is 0.
      std::vector<double> xyz(3 * cells, 0.0);
      for (int c = 0; c < a.count; ++c) {
        const double* src = a.c[static_cast<std::size_t>(c)];
        for (std::size_t k = 0; k < cells; ++k) xyz[3 * k + static_cast<std::size_t>(c)] = src[k];
      }
      file.data_array("Float64", a.name, 3, xyz);
    }
  }
  file.xml += "      </CellData>\n";
  file.xml += "    </Piece>\n  </ImageData>\n";
  write_file_atomic(path, file.finish("ImageData"), Sync::Atomic);
}

void write_vti(const std::filesystem::path& path, const Grid2& grid, double time,
               const std::vector<VtiArray>& cell_data) {
  std::vector<VtiComponents> arrays;
  for (const VtiArray& a : cell_data) {
    check_shape(grid, a.x, a.name);
    if (a.y) check_shape(grid, a.y, a.name);
    arrays.push_back({a.name, {a.x->v.data(), a.y ? a.y->v.data() : nullptr, nullptr}, a.y ? 2 : 1});
  }
  write_vti(path, VtiGrid::of(grid), time, arrays);
}

void write_vtu(const std::filesystem::path& path, double time, const ParticleArrays& particles) {
  const bool three_d = particles.dimension == 3;
  const std::vector<std::size_t> order = particles.order_by_id();
  const std::size_t n = order.size();
  const int axes = three_d ? 3 : 2;

  std::vector<double> points(3 * n, 0.0), velocity(3 * n, 0.0), diameter(n), spin(three_d ? 3 * n : n);
  std::vector<std::int64_t> id(n), connectivity(n), offsets(n);
  std::vector<std::int32_t> species(n), layer(n, 0);
  std::vector<std::uint8_t> types(n, 1);  // VTK_VERTEX
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t p = order[k];
    for (int a = 0; a < axes; ++a) {
      const auto ua = static_cast<std::size_t>(a);
      points[3 * k + ua] = particles.x[ua][p];
      velocity[3 * k + ua] = particles.v[ua][p];
    }
    if (three_d) {
      for (std::size_t a = 0; a < 3; ++a) spin[3 * k + a] = particles.omega[a][p];
    } else {
      spin[k] = particles.omega[2][p];
    }
    diameter[k] = 2.0 * particles.radius[p];
    id[k] = particles.id[p];
    species[k] = particles.species[p];
    if (!particles.layer.empty()) layer[k] = particles.layer[p];
    connectivity[k] = static_cast<std::int64_t>(k);
    offsets[k] = static_cast<std::int64_t>(k + 1);
  }

  VtkFile file;
  file.xml += "  <UnstructuredGrid>\n";
  file.time_value(time);
  file.xml += fmt::format(R"(    <Piece NumberOfPoints="{}" NumberOfCells="{}">)"
                          "\n",
                          n, n);
  file.xml += "      <Points>\n";
  file.data_array("Float64", "Points", 3, points);
  file.xml += "      </Points>\n      <Cells>\n";
  file.data_array("Int64", "connectivity", 1, connectivity);
  file.data_array("Int64", "offsets", 1, offsets);
  file.data_array("UInt8", "types", 1, types);
  file.xml += "      </Cells>\n      <PointData>\n";
  file.data_array("Int64", "id", 1, id);
  file.data_array("Int32", "species", 1, species);
  file.data_array("Float64", "diameter", 1, diameter);
  file.data_array("Float64", "velocity", 3, velocity);
  file.data_array("Float64", "angular_velocity", three_d ? 3 : 1, spin);
  file.data_array("Int32", "layer", 1, layer);
  file.xml += "      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n";
  write_file_atomic(path, file.finish("UnstructuredGrid"), Sync::Atomic);
}

void write_vtu(const std::filesystem::path& path, double time, const ParticleStore<2>& particles) {
  write_vtu(path, time, particle_arrays(particles));
}

namespace {

PvdCollection open_series(const std::filesystem::path& out_dir, const std::string& name,
                          std::optional<double> restart_time) {
  ensure_directory(out_dir / name);
  const std::filesystem::path pvd = out_dir / (name + ".pvd");
  return restart_time ? PvdCollection::resume(pvd, *restart_time) : PvdCollection(pvd);
}

}  // namespace

FieldSeries::FieldSeries(const std::filesystem::path& out_dir, std::optional<double> restart_time)
    : out_dir_(out_dir), pvd_(open_series(out_dir, "fields", restart_time)) {}

std::size_t FieldSeries::write(double time, const VtiGrid& grid, const std::vector<VtiComponents>& cell_data) {
  const std::size_t index = pvd_.next_index();
  const std::string file = frame_file_name("fields", index, "vti");
  write_vti(out_dir_ / file, grid, time, cell_data);
  pvd_.add(time, file);
  return index;
}

std::size_t FieldSeries::write(double time, const Grid2& grid, const std::vector<VtiArray>& cell_data) {
  const std::size_t index = pvd_.next_index();
  const std::string file = frame_file_name("fields", index, "vti");
  write_vti(out_dir_ / file, grid, time, cell_data);
  pvd_.add(time, file);
  return index;
}

ParticleSeries::ParticleSeries(const std::filesystem::path& out_dir, std::optional<double> restart_time)
    : out_dir_(out_dir), pvd_(open_series(out_dir, "particles", restart_time)) {}

std::size_t ParticleSeries::write(double time, const ParticleStore<2>& particles, bool with_csv) {
  return write(time, particle_arrays(particles), with_csv);
}

std::size_t ParticleSeries::write(double time, const ParticleArrays& particles, bool with_csv) {
  const std::size_t index = pvd_.next_index();
  const std::string file = frame_file_name("particles", index, "vtu");
  write_vtu(out_dir_ / file, time, particles);
  if (with_csv) write_particles_csv(out_dir_ / frame_file_name("particles", index, "csv"), particles);
  pvd_.add(time, file);
  return index;
}

}  // namespace fluidbed
