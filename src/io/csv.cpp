#include "io/csv.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <unordered_map>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace fluidbed {
namespace {

[[noreturn]] void cannot_write(const std::filesystem::path& path, const std::string& reason) {
  throw WriteError(path, "cannot write " + path.string() + ": " + reason);
}

std::string join(const std::vector<std::string>& cells) {
  std::string out;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (c > 0) out += ',';
    out += cells[c];
  }
  return out;
}

std::string read_whole_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorKind::BadInput, path.string() + ": cannot read: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Lines without their '\n' (and a Windows '\r'); `complete` says whether the text ended with a newline.
std::vector<std::string_view> split_lines(std::string_view text, bool& complete) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) {
      lines.push_back(text.substr(start));
      complete = false;
      return lines;
    }
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  complete = true;
  return lines;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_cells(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(',', start);
    if (end == std::string_view::npos) {
      cells.push_back(trim(line.substr(start)));
      return cells;
    }
    cells.push_back(trim(line.substr(start, end - start)));
    start = end + 1;
  }
}

bool parse_double(std::string_view s, double& value, std::errc& error) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  error = ec;
  return ec == std::errc() && ptr == s.data() + s.size();
}

std::string format_row(std::span<const std::optional<double>> values) {
  std::string line;
  for (std::size_t c = 0; c < values.size(); ++c) {
    if (c > 0) line += ',';
    if (values[c]) line += fmt::format("{:.17g}", *values[c]);
  }
  line += '\n';
  return line;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// CsvWriter

CsvWriter::CsvWriter(std::filesystem::path path, std::vector<std::string> columns)
    : CsvWriter(path, columns, join(columns) + "\n") {}

CsvWriter::CsvWriter(std::filesystem::path path, std::vector<std::string> columns, const std::string& initial_content)
    : path_(std::move(path)), columns_(std::move(columns)) {
  if (columns_.empty()) throw std::invalid_argument("CsvWriter: no columns");
  write_file_atomic(path_, initial_content);
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) cannot_write(path_, std::strerror(errno));
}

CsvWriter CsvWriter::resume(std::filesystem::path path, std::vector<std::string> columns, double restart_time) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return CsvWriter(std::move(path), std::move(columns));

  const std::string text = read_whole_file(path);
  bool complete = true;
  std::vector<std::string_view> lines = split_lines(text, complete);
  // A run killed during a write can only leave a partial last line; it is not data.
  if (!complete) lines.pop_back();
  const std::string header = join(columns);
  if (lines.empty() || lines.front() != header) {
    throw Error(ErrorKind::BadInput,
                fmt::format("{}: row 1: header '{}' does not match the expected '{}'", path.string(),
                            lines.empty() ? std::string_view() : lines.front(), header));
  }
  std::string kept = header + "\n";
  for (std::size_t r = 1; r < lines.size(); ++r) {
    if (trim(lines[r]).empty()) continue;
    const std::string_view first = trim(lines[r].substr(0, lines[r].find(',')));
    double t = 0.0;
    std::errc err{};
    if (!parse_double(first, t, err) || std::isnan(t)) {
      throw Error(ErrorKind::BadInput, fmt::format("{}: row {}, column 1: time '{}' is not a number",
                                                   path.string(), r + 1, first));
    }
    if (t <= restart_time) {
      kept += lines[r];
      kept += '\n';
    }
  }
  return CsvWriter(std::move(path), std::move(columns), kept);
}

CsvWriter::CsvWriter(CsvWriter&& other) noexcept
    : path_(std::move(other.path_)), columns_(std::move(other.columns_)), fd_(other.fd_) {
  other.fd_ = -1;
}

CsvWriter& CsvWriter::operator=(CsvWriter&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    columns_ = std::move(other.columns_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

CsvWriter::~CsvWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void CsvWriter::row(std::span<const std::optional<double>> values) {
  if (values.size() != columns_.size()) {
    throw std::invalid_argument(fmt::format("CsvWriter::row: {} values for {} columns of {}", values.size(),
                                            columns_.size(), path_.string()));
  }
  write_line(format_row(values));
}

void CsvWriter::line(const std::string& text) {
  if (std::count(text.begin(), text.end(), ',') + 1 != static_cast<std::ptrdiff_t>(columns_.size()) ||
      text.find('\n') != std::string::npos) {
    throw std::invalid_argument(fmt::format("CsvWriter::line: the line does not have the {} columns of {}",
                                            columns_.size(), path_.string()));
  }
  write_line(text + "\n");
}

void CsvWriter::write_line(const std::string& line) {
  if (fd_ < 0) cannot_write(path_, "the file is not open");
  // Where the file ends now: a write that fails part-way (disk full) is cut back to here, so the file keeps
  // whole rows only.
  struct stat before {};
  if (::fstat(fd_, &before) != 0) cannot_write(path_, std::strerror(errno));
  // One write() per line on an O_APPEND descriptor: the kernel's buffer receives whole lines, which is what a
  // killed process leaves on disk.
  std::size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      if (done > 0 && ::ftruncate(fd_, before.st_size) != 0) {
        throw WriteError(path_, fmt::format("cannot write {}: {}, and the partial row could not be removed: {}",
                                            path_.string(), std::strerror(err), std::strerror(errno)), err);
      }
      throw WriteError(path_, "cannot write " + path_.string() + ": " + std::strerror(err) +
                                  disk_space_note(path_, line.size(), err), err);
    }
    done += static_cast<std::size_t>(n);
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Particle CSV

std::vector<std::size_t> ParticleArrays::order_by_id() const {
  std::vector<std::size_t> order(size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
  return order;
}

void write_particles_csv(const std::filesystem::path& path, const ParticleArrays& p, Sync sync) {
  const bool three_d = p.dimension == 3;
  const bool sized = p.own_sizes && p.radius.size() == p.size();
  std::string out = std::string(particle_csv_header_of(p.dimension)) +
                    (sized ? std::string(",") + particle_csv_diameter_column : std::string()) + "\n";
  out.reserve(out.size() + p.size() * (three_d ? 240 : 140));
  for (const std::size_t k : p.order_by_id()) {
    if (sized) {
      // The same row, then the diameter.
      if (three_d) {
        out += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{},{:.17g}\n",
                           p.id[k], p.x[0][k], p.x[1][k], p.x[2][k], p.v[0][k], p.v[1][k], p.v[2][k], p.omega[0][k],
                           p.omega[1][k], p.omega[2][k], p.species[k], 2.0 * p.radius[k]);
      } else {
        out += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{},{:.17g}\n", p.id[k], p.x[0][k], p.x[1][k],
                           p.v[0][k], p.v[1][k], p.omega[2][k], p.species[k], 2.0 * p.radius[k]);
      }
      continue;
    }
    if (three_d) {
      out += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n", p.id[k],
                         p.x[0][k], p.x[1][k], p.x[2][k], p.v[0][k], p.v[1][k], p.v[2][k], p.omega[0][k],
                         p.omega[1][k], p.omega[2][k], p.species[k]);
    } else {
      out += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n", p.id[k], p.x[0][k], p.x[1][k], p.v[0][k],
                         p.v[1][k], p.omega[2][k], p.species[k]);
    }
  }
  write_file_atomic(path, out, sync);
}

void check_particle_rows(const std::vector<ParticleCsvRow>& rows, const std::string& file, const DomainConfig& domain,
                         std::size_t n_species) {
  const bool three_d = domain.dimension == 3;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const ParticleCsvRow& row = rows[r];
    if (row.species < 0 || static_cast<std::size_t>(row.species) >= n_species) {
      throw_input_error(fmt::format("{}: row {}, column species: species {} is not defined in the case (it has {})",
                                    file, r + 2, row.species, n_species));
    }
    const bool inside = row.x >= 0.0 && row.x <= domain.width && row.y >= 0.0 && row.y <= domain.height &&
                        (!three_d || (row.z >= 0.0 && row.z <= domain.depth));
    if (!inside) {
      throw_input_error(three_d ? fmt::format("{}: row {}, columns x,y,z: particle {} at ({}, {}, {}) m is not inside "
                                              "the {} x {} x {} m domain", file, r + 2, row.id, row.x, row.y, row.z,
                                              domain.width, domain.height, domain.depth)
                                : fmt::format("{}: row {}, columns x,y: particle {} at ({}, {}) m is not inside the "
                                              "{} x {} m domain", file, r + 2, row.id, row.x, row.y, domain.width,
                                              domain.height));
    }
  }
}

namespace {

// The columns a particle CSV file of one dimension has, and how a bad cell is reported (file, row, column).
struct ParticleCsvLayout {
  const char* const* names;
  std::size_t ncol;
  const char* header_text;
  std::string file;
  int dimension;

  [[noreturn]] void fail(std::size_t row, std::size_t column, const std::string& what) const {
    throw Error(ErrorKind::BadInput, fmt::format("{}: row {}, column {}: {}", file, row, column, what));
  }
  const char* name_of(std::size_t c) const { return c < ncol ? names[c] : particle_csv_diameter_column; }
};

ParticleCsvLayout particle_csv_layout(const std::filesystem::path& path, int dimension) {
  static constexpr const char* names2[] = {"id", "x", "y", "vx", "vy", "omega", "species"};
  static constexpr const char* names3[] = {"id", "x", "y", "z", "vx", "vy", "vz", "omega_x", "omega_y", "omega_z",
                                           "species"};
  const bool three_d = dimension == 3;
  return {three_d ? names3 : names2, three_d ? std::size(names3) : std::size(names2), particle_csv_header_of(dimension),
          path.string(), dimension};
}

// The header row, column by column; whether it has the optional last column of each particle's diameter.
bool check_particle_header(const ParticleCsvLayout& f, std::string_view line) {
  const std::vector<std::string_view> header = split_cells(line);
  const bool three_d = f.dimension == 3;
  {
    // A file of the other dimension, said as such rather than as a wrong column.
    std::string joined;
    for (std::size_t c = 0; c < header.size(); ++c) {
      if (c > 0) joined.push_back(',');
      joined.append(trim(header[c]));
    }
    if (joined == particle_csv_header_of(three_d ? 2 : 3)) {
      f.fail(1, 1, fmt::format("a {0}D particle file (header '{1}') for a {2}D case; a {2}D case reads '{3}'",
                               three_d ? 2 : 3, joined, f.dimension, f.header_text));
    }
  }
  const std::size_t ncol = f.ncol;
  const bool sized = header.size() == ncol + 1 && trim(header[ncol]) == particle_csv_diameter_column;
  for (std::size_t c = 0; c < std::max(header.size(), ncol) && !(sized && c == ncol); ++c) {
    if (c >= header.size()) {
      f.fail(1, c + 1, fmt::format("missing header column '{}' (expected '{}')", f.names[c], f.header_text));
    }
    if (c >= ncol) {
      f.fail(1, c + 1, fmt::format("extra header column '{}' (expected '{}')", header[c], f.header_text));
    }
    if (header[c] != f.names[c]) {
      f.fail(1, c + 1, fmt::format("header '{}' where '{}' is expected (the header must be '{}')", header[c],
                                   f.names[c], f.header_text));
    }
  }
  return sized;
}

// One particle row (row number r of the file), every value checked.
ParticleCsvRow parse_particle_row(const ParticleCsvLayout& f, std::string_view line, std::size_t r, bool sized) {
  const std::size_t ncol = f.ncol;
  const std::size_t nvalues = ncol + (sized ? 1 : 0);
  if (trim(line).empty()) f.fail(r, 1, "empty row");
  const std::vector<std::string_view> cells = split_cells(line);
  if (cells.size() < nvalues) {
    f.fail(r, cells.size() + 1,
           fmt::format("missing value for '{}' (the row has {} columns, {} expected)", f.name_of(cells.size()),
                       cells.size(), nvalues));
  }
  if (cells.size() > nvalues) {
    f.fail(r, nvalues + 1, fmt::format("extra value '{}' (the row has {} columns, {} expected)", cells[nvalues],
                                       cells.size(), nvalues));
  }
  for (std::size_t c = 0; c < nvalues; ++c) {
    if (cells[c].empty()) f.fail(r, c + 1, fmt::format("empty value for '{}'", f.name_of(c)));
  }
  auto parse_integer = [&](std::size_t c, std::int64_t lo, std::int64_t hi) {
    std::int64_t v = 0;
    const std::string_view s = cells[c];
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || ptr != s.data() + s.size()) {
      f.fail(r, c + 1, fmt::format("{} '{}' is not an integer", f.names[c], s));
    }
    if (v < lo || v > hi) f.fail(r, c + 1, fmt::format("{} {} is outside [{}, {}]", f.names[c], v, lo, hi));
    return v;
  };
  auto parse_real = [&](std::size_t c) {
    double v = 0.0;
    std::errc ec{};
    if (!parse_double(cells[c], v, ec)) {
      if (ec == std::errc::result_out_of_range) {
        f.fail(r, c + 1, fmt::format("{} '{}' is out of the range of a double", f.name_of(c), cells[c]));
      }
      f.fail(r, c + 1, fmt::format("{} '{}' is not a number", f.name_of(c), cells[c]));
    }
    if (!std::isfinite(v)) f.fail(r, c + 1, fmt::format("{} '{}' is not finite", f.name_of(c), cells[c]));
    return v;
  };
  ParticleCsvRow row;
  row.id = parse_integer(0, 0, std::numeric_limits<std::int64_t>::max());
  if (f.dimension == 3) {
    row.x = parse_real(1);
    row.y = parse_real(2);
    row.z = parse_real(3);
    row.vx = parse_real(4);
    row.vy = parse_real(5);
    row.vz = parse_real(6);
    row.omega_x = parse_real(7);
    row.omega_y = parse_real(8);
    row.omega = parse_real(9);
    row.species = static_cast<std::int32_t>(parse_integer(10, 0, std::numeric_limits<std::int32_t>::max()));
  } else {
    row.x = parse_real(1);
    row.y = parse_real(2);
    row.vx = parse_real(3);
    row.vy = parse_real(4);
    row.omega = parse_real(5);
    row.species = static_cast<std::int32_t>(parse_integer(6, 0, std::numeric_limits<std::int32_t>::max()));
  }
  if (sized) {
    row.diameter = parse_real(ncol);
    if (!(row.diameter > 0.0)) f.fail(r, ncol + 1, fmt::format("diameter {} is not positive (m)", cells[ncol]));
  }
  return row;
}

}  // namespace

std::vector<ParticleCsvRow> read_particles_csv(const std::filesystem::path& path, int dimension) {
  const ParticleCsvLayout layout = particle_csv_layout(path, dimension);
  const std::string text = read_whole_file(path);
  std::string_view body = text;
  if (body.starts_with("\xEF\xBB\xBF")) body.remove_prefix(3);  // UTF-8 byte order mark from spreadsheets
  bool complete = true;
  std::vector<std::string_view> lines = split_lines(body, complete);
  while (!lines.empty() && trim(lines.back()).empty()) lines.pop_back();
  if (lines.empty()) layout.fail(1, 1, fmt::format("empty file, expected the header '{}'", layout.header_text));
  const bool sized = check_particle_header(layout, lines.front());
  if (lines.size() == 1) layout.fail(2, 1, "no particle rows after the header");
  std::vector<ParticleCsvRow> rows;
  rows.reserve(lines.size() - 1);
  std::unordered_map<std::int64_t, std::size_t> first_row_of_id;
  first_row_of_id.reserve(lines.size());
  for (std::size_t l = 1; l < lines.size(); ++l) {
    const std::size_t r = l + 1;
    const ParticleCsvRow row = parse_particle_row(layout, lines[l], r, sized);
    const auto [it, inserted] = first_row_of_id.emplace(row.id, r);
    if (!inserted) layout.fail(r, 1, fmt::format("duplicate id {} (first in row {})", row.id, it->second));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace fluidbed
