#pragma once
// VTK XML writers for ParaView: ImageData (.vti) for cell fields, UnstructuredGrid (.vtu) of vertices for
// particles. Written without the VTK library: appended binary data, little-endian, UInt64 block headers,
// zlib-compressed in the block layout of vtkZLibDataCompressor; values keep every bit (full double precision).
#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/particle_arrays.hpp"
#include "io/pvd.hpp"

namespace fluidbed {

/// The shape of an ImageData grid in either dimension: cells, cell size and low corner per axis (2D: n[2] = 1,
/// written as a collapsed z extent).
struct VtiGrid {
  int dimension = 2;
  std::array<int, 3> n{0, 0, 1};
  std::array<double, 3> h{0.0, 0.0, 0.0};       ///< m
  std::array<double, 3> origin{0.0, 0.0, 0.0};  ///< m
  std::size_t cells() const {
    return static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) * static_cast<std::size_t>(n[2]);
  }
};

/// One CellData array as contiguous component arrays of grid.cells() values (axis 0 fastest): `count` = 1 a
/// scalar; 2 or 3 a vector, written with 3 components (z = 0 for 2). Pointers must outlive the write_vti call.
struct VtiComponents {
  std::string name;
  std::array<const double*, 3> c{};
  int count = 1;
};

/// Write an ImageData file of cell-centred arrays on `grid` in its dimension (3D: WholeExtent 0 nx 0 ny 0 nz),
/// FieldData TimeValue = `time`. Atomic; throws Error(BadInput) when the file cannot be written and
/// std::invalid_argument for an array without its components.
void write_vti(const std::filesystem::path& path, const VtiGrid& grid, double time,
               const std::vector<VtiComponents>& cell_data);

/// Write an UnstructuredGrid of one VTK_VERTEX per particle of `particles` (a particle_arrays() view of a store),
/// sorted by particle id. Point arrays: id (Int64), species (Int32), diameter (Float64, m), velocity (Float64 x3,
/// z = 0 in 2D, m/s), angular_velocity (2D: Float64 scalar, spin about z, rad/s, anticlockwise positive; 3D:
/// Float64 x 3), layer (Int32); FieldData TimeValue = `time`. Atomic; throws Error(BadInput) when the file cannot be
/// written.
void write_vtu(const std::filesystem::path& path, double time, const ParticleArrays& particles);

/// The field frames of a run: `<out_dir>/fields/NNNNNN.vti` listed in `<out_dir>/fields.pvd`.
/// With `restart_time`, the existing collection is kept up to that time and numbering continues after it.
class FieldSeries {
 public:
  explicit FieldSeries(const std::filesystem::path& out_dir, std::optional<double> restart_time = std::nullopt);
  /// Write one frame and list it in the .pvd; returns its frame number (for files of the same instant, such as
  /// tracers/NNNNNN.csv).
  std::size_t write(double time, const VtiGrid& grid, const std::vector<VtiComponents>& cell_data);
  const PvdCollection& collection() const { return pvd_; }

 private:
  std::filesystem::path out_dir_;
  PvdCollection pvd_;
};

/// The particle frames of a run: `<out_dir>/particles/NNNNNN.vtu` listed in `<out_dir>/particles.pvd`, and
/// optionally `particles/NNNNNN.csv` with the same number. Restart as FieldSeries.
class ParticleSeries {
 public:
  explicit ParticleSeries(const std::filesystem::path& out_dir, std::optional<double> restart_time = std::nullopt);
  /// Write one frame (and its CSV when `with_csv`); returns its frame number.
  std::size_t write(double time, const ParticleArrays& particles, bool with_csv = false);
  const PvdCollection& collection() const { return pvd_; }

 private:
  std::filesystem::path out_dir_;
  PvdCollection pvd_;
};

}  // namespace fluidbed
