#include "io/vtk_writer.hpp"

#include <fmt/format.h>

#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <span>
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

// Collects the XML header and each array's compressed appended data. One DataArray's appended block, with
// header_type="UInt64" and compressor="vtkZLibDataCompressor" (VTK XML file format, "compressed data"): UInt64
// number of blocks, UInt64 uncompressed block size, UInt64 uncompressed size of the last block (0 when it is full),
// one UInt64 compressed size per block, then the zlib streams of the blocks one after the other. A DataArray's
// offset counts from the first byte after the '_' marker, so the header can only be written once every array is
// compressed. The values are gathered one block at a time straight from the caller's arrays and only the
// compressed blocks are kept, so a frame needs about half its raw size in memory, not three copies of it
// (docs/performance.md, section 21).
class VtkFile {
 public:
  std::string xml;

  /// An array of `count` values of T; fill(first, n, dst) writes values first .. first + n - 1 to dst. It is
  /// called from several threads at once, for different blocks.
  template <class T, class Fill>
  void data_array(std::string_view type, std::string_view name, int components, std::size_t count,
                  const Fill& fill) {
    // Names go into an XML attribute unescaped; ParaView also expects them printable.
    if (name.empty() || name.find_first_of("\"<>&\n") != std::string_view::npos) {
      throw std::invalid_argument("VTK array name '" + std::string(name) + "' is empty or has XML characters");
    }
    static_assert(kBlockBytes % sizeof(T) == 0, "a block holds whole values");
    xml += fmt::format(R"(        <DataArray type="{}" Name="{}" NumberOfComponents="{}" format="appended" offset=")",
                       type, name, components);
    pieces_.push_back(std::move(xml));
    xml = "\"/>\n";
    Array& a = arrays_.emplace_back();
    const std::size_t bytes = count * sizeof(T);
    const std::size_t n_blocks = (bytes + kBlockBytes - 1) / kBlockBytes;
    constexpr std::size_t kPerBlock = kBlockBytes / sizeof(T);
    a.blocks.resize(n_blocks);
    std::vector<int> status(n_blocks, Z_OK);
    const auto nb = static_cast<std::ptrdiff_t>(n_blocks);
    // Each block is compressed on its own, so the bytes written do not depend on the thread count.
#pragma omp parallel if (n_blocks > 1)
    {
      std::vector<T> raw(kPerBlock);
      std::vector<Bytef> packed(compressBound(static_cast<uLong>(kBlockBytes)));
#pragma omp for schedule(dynamic)
      for (std::ptrdiff_t k = 0; k < nb; ++k) {
        const auto b = static_cast<std::size_t>(k);
        const std::size_t first = b * kPerBlock, n = std::min(kPerBlock, count - first);
        fill(first, n, raw.data());
        uLongf len = static_cast<uLongf>(packed.size());
        status[b] = compress2(packed.data(), &len, reinterpret_cast<const Bytef*>(raw.data()),
                              static_cast<uLong>(n * sizeof(T)), kZlibLevel);
        a.blocks[b].assign(reinterpret_cast<const char*>(packed.data()), len);
      }
    }
    for (const int st : status) {
      // compressBound sizes the output, so only memory can run out.
      if (st != Z_OK) throw std::runtime_error(fmt::format("zlib compression of a VTK frame failed (code {})", st));
    }
    std::vector<std::uint64_t> header{n_blocks, kBlockBytes, bytes % kBlockBytes};
    for (const std::string& block : a.blocks) header.push_back(block.size());
    a.header.assign(reinterpret_cast<const char*>(header.data()), header.size() * sizeof(std::uint64_t));
  }

  /// An array of `count` contiguous values.
  template <class T>
  void data_array(std::string_view type, std::string_view name, int components, const T* values, std::size_t count) {
    data_array<T>(type, name, components, count,
                  [values](std::size_t first, std::size_t n, T* dst) { std::copy_n(values + first, n, dst); });
  }

  void time_value(double time) {
    xml += "    <FieldData>\n";
    xml += fmt::format(
        R"(      <DataArray type="Float64" Name="TimeValue" NumberOfTuples="1" format="ascii">{:.17g}</DataArray>)"
        "\n",
        time);
    xml += "    </FieldData>\n";
  }

  /// Write the file: the XML with the offsets, then the arrays' blocks as they are held.
  void write(const std::filesystem::path& path, std::string_view type) const {
    std::string head;
    head += "<?xml version=\"1.0\"?>\n";
    head += fmt::format(
        R"(<VTKFile type="{}" version="1.0" byte_order="LittleEndian" header_type="UInt64" )"
        R"(compressor="vtkZLibDataCompressor">)"
        "\n",
        type);
    std::size_t offset = 0;
    for (std::size_t a = 0; a < arrays_.size(); ++a) {
      head += pieces_[a];
      head += std::to_string(offset);
      offset += arrays_[a].header.size();
      for (const std::string& block : arrays_[a].blocks) offset += block.size();
    }
    head += xml;
    head += "  <AppendedData encoding=\"raw\">\n   _";
    std::vector<std::string_view> parts{head};
    for (const Array& a : arrays_) {
      parts.push_back(a.header);
      for (const std::string& block : a.blocks) parts.push_back(block);
    }
    parts.push_back("\n  </AppendedData>\n</VTKFile>\n");
    write_file_atomic(path, parts, Sync::Atomic);
  }

 private:
  struct Array {
    std::string header;               // the UInt64 block header
    std::vector<std::string> blocks;  // the zlib stream of each block
  };
  std::vector<std::string> pieces_;  // XML before each array's offset value
  std::vector<Array> arrays_;
};

}  // namespace

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
      file.data_array("Float64", a.name, 1, a.c[0], cells);
    } else {
      // Vectors always have 3 components in VTK; a 2D vector's z is 0.
      const auto components = static_cast<std::size_t>(a.count);
      file.data_array<double>("Float64", a.name, 3, 3 * cells, [&a, components](std::size_t first, std::size_t n, double* dst) {
        for (std::size_t f = first; f < first + n; ++f) {
          const std::size_t c = f % 3;
          *dst++ = c < components ? a.c[c][f / 3] : 0.0;
        }
      });
    }
  }
  file.xml += "      </CellData>\n";
  file.xml += "    </Piece>\n  </ImageData>\n";
  file.write(path, "ImageData");
}

void write_vtu(const std::filesystem::path& path, double time, const ParticleArrays& particles) {
  const bool three_d = particles.dimension == 3;
  const std::vector<std::size_t> order = particles.order_by_id();
  const std::size_t n = order.size();
  const auto axes = static_cast<std::size_t>(three_d ? 3 : 2);
  const ParticleArrays& p = particles;

  // Each array is gathered in id order block by block (VtkFile::data_array), from the particles' own arrays.
  // A vector of 3 components per particle, `axes` of them set (a 2D point's z is 0).
  auto vector3 = [&order, axes](const std::array<std::span<const double>, 3>& v) {
    return [&order, &v, axes](std::size_t first, std::size_t count, double* dst) {
      for (std::size_t f = first; f < first + count; ++f) {
        const std::size_t c = f % 3;
        *dst++ = c < axes ? v[c][order[f / 3]] : 0.0;
      }
    };
  };
  auto gathered = [&order](auto value) {
    return [&order, value](std::size_t first, std::size_t count, auto* dst) {
      for (std::size_t k = first; k < first + count; ++k) *dst++ = value(order[k]);
    };
  };
  auto index = [](std::int64_t shift) {
    return [shift](std::size_t first, std::size_t count, std::int64_t* dst) {
      for (std::size_t k = first; k < first + count; ++k) *dst++ = static_cast<std::int64_t>(k) + shift;
    };
  };

  VtkFile file;
  file.xml += "  <UnstructuredGrid>\n";
  file.time_value(time);
  file.xml += fmt::format(R"(    <Piece NumberOfPoints="{}" NumberOfCells="{}">)"
                          "\n",
                          n, n);
  file.xml += "      <Points>\n";
  file.data_array<double>("Float64", "Points", 3, 3 * n, vector3(p.x));
  file.xml += "      </Points>\n      <Cells>\n";
  file.data_array<std::int64_t>("Int64", "connectivity", 1, n, index(0));
  file.data_array<std::int64_t>("Int64", "offsets", 1, n, index(1));
  file.data_array<std::uint8_t>("UInt8", "types", 1, n, [](std::size_t, std::size_t count, std::uint8_t* dst) {
    std::fill_n(dst, count, std::uint8_t{1});  // VTK_VERTEX
  });
  file.xml += "      </Cells>\n      <PointData>\n";
  file.data_array<std::int64_t>("Int64", "id", 1, n, gathered([&p](std::size_t s) { return p.id[s]; }));
  file.data_array<std::int32_t>("Int32", "species", 1, n, gathered([&p](std::size_t s) { return p.species[s]; }));
  file.data_array<double>("Float64", "diameter", 1, n, gathered([&p](std::size_t s) { return 2.0 * p.radius[s]; }));
  file.data_array<double>("Float64", "velocity", 3, 3 * n, vector3(p.v));
  if (three_d) {
    file.data_array<double>("Float64", "angular_velocity", 3, 3 * n, vector3(p.omega));
  } else {
    file.data_array<double>("Float64", "angular_velocity", 1, n, gathered([&p](std::size_t s) { return p.omega[2][s]; }));
  }
  file.data_array<std::int32_t>("Int32", "layer", 1, n, gathered([&p](std::size_t s) {
    return p.layer.empty() ? std::int32_t{0} : p.layer[s];
  }));
  file.xml += "      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n";
  file.write(path, "UnstructuredGrid");
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

ParticleSeries::ParticleSeries(const std::filesystem::path& out_dir, std::optional<double> restart_time)
    : out_dir_(out_dir), pvd_(open_series(out_dir, "particles", restart_time)) {}

std::size_t ParticleSeries::write(double time, const ParticleArrays& particles, bool with_csv) {
  const std::size_t index = pvd_.next_index();
  const std::string file = frame_file_name("particles", index, "vtu");
  write_vtu(out_dir_ / file, time, particles);
  if (with_csv) write_particles_csv(out_dir_ / frame_file_name("particles", index, "csv"), particles);
  pvd_.add(time, file);
  return index;
}

}  // namespace fluidbed
