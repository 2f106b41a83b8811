#pragma once
// CSV time series (monitor.csv, bubble.csv, tracers) that survive a kill and continue after a restart,
// and the particle CSV format (2D: id,x,y,vx,vy,omega,species; 3D: id,x,y,z,vx,vy,vz,omega_x,omega_y,omega_z,species;
// either with a last column diameter where particles have their own sizes) written by runs and read by case files.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/domain.hpp"
#include "io/atomic_file.hpp"
#include "io/particle_arrays.hpp"

namespace fluidbed {

/// Append-only CSV of numbers, the first column being the time in s. Each row is one write() of a whole line,
/// so a killed run leaves only whole lines behind.
class CsvWriter {
 public:
  /// Create (or replace) `path` with the header `columns`. Throws Error(BadInput, "cannot write <path>: ...").
  CsvWriter(std::filesystem::path path, std::vector<std::string> columns);

  /// Continue `path` after a restart at `restart_time`: keep the rows with time <= restart_time (rewritten
  /// atomically, a trailing partial line dropped) and append after them. A missing file starts a new one.
  /// Throws Error(BadInput, "<file>: ...") when the header differs from `columns` or a kept row's time is
  /// not a number.
  static CsvWriter resume(std::filesystem::path path, std::vector<std::string> columns, double restart_time);

  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  CsvWriter(CsvWriter&& other) noexcept;
  CsvWriter& operator=(CsvWriter&& other) noexcept;
  ~CsvWriter();

  /// Append one row: values at full precision ({:.17g}), an empty cell for std::nullopt. The count must match
  /// the header (std::invalid_argument otherwise). Throws WriteError when the write fails (disk full); a row
  /// that fails part-way is cut off again, so the file holds whole rows only.
  void row(std::span<const std::optional<double>> values);
  void row(std::initializer_list<std::optional<double>> values) { row(std::span(values.begin(), values.size())); }

  /// Append one formatted line (no newline) whose first value is the time, for series with text columns
  /// (bubbles.csv); its comma count must match the header. Same guarantees as row().
  void line(const std::string& text);

  const std::vector<std::string>& columns() const { return columns_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  int fd_ = -1;

  CsvWriter(std::filesystem::path path, std::vector<std::string> columns, const std::string& initial_content);
  void write_line(const std::string& line);
};

/// One line of a particle CSV file. A 2D file has no z, vz, omega_x, omega_y (they read as 0).
struct ParticleCsvRow {
  std::int64_t id = 0;
  double x = 0.0, y = 0.0;    ///< m
  double vx = 0.0, vy = 0.0;  ///< m/s
  double omega = 0.0;         ///< rad/s, spin about z, anticlockwise positive (3D: omega_z)
  std::int32_t species = 0;
  double z = 0.0;             ///< m (3D)
  double vz = 0.0;            ///< m/s (3D)
  double omega_x = 0.0, omega_y = 0.0;  ///< rad/s, spin about x and y (3D)
  double diameter = 0.0;      ///< m; 0 in a file without the diameter column: the species' diameter
};

/// The exact header of a particle CSV file: 2D, and 3D.
inline constexpr const char* particle_csv_header = "id,x,y,vx,vy,omega,species";
inline constexpr const char* particle_csv_header_3d = "id,x,y,z,vx,vy,vz,omega_x,omega_y,omega_z,species";
/// The header of a particle CSV file of `dimension` (2 or 3).
inline const char* particle_csv_header_of(int dimension) {
  return dimension == 3 ? particle_csv_header_3d : particle_csv_header;
}
/// The optional last column of a particle CSV file: each particle's own diameter, m.
inline constexpr const char* particle_csv_diameter_column = "diameter";

/// Write `particles` (a particle_arrays() view of a store, in its dimension) sorted by id at full precision,
/// atomically. Throws Error(BadInput) when it cannot write.
void write_particles_csv(const std::filesystem::path& path, const ParticleArrays& particles,
                         Sync sync = Sync::Durable);

/// Read and validate a particle CSV file of `dimension` (rows in file order), with or without the last column
/// diameter. Throws Error(BadInput, "<file>: row R, column C: ...") on the first problem, R being the line number
/// (the header is row 1): wrong header (a file of the other dimension is named as such), missing or extra values, a
/// value that is not a finite number, a non-integer or negative id, a non-integer or negative species, a diameter
/// that is not positive, a duplicate id, no particle rows.
std::vector<ParticleCsvRow> read_particles_csv(const std::filesystem::path& path, int dimension = 2);

/// The checks of a particle file against its case: species defined (`n_species`), centres inside the domain
/// (x, y, and z in 3D). Throws Error(BadInput, "<file>: row R, ...").
void check_particle_rows(const std::vector<ParticleCsvRow>& rows, const std::string& file, const DomainConfig& domain,
                         std::size_t n_species);

}  // namespace fluidbed
