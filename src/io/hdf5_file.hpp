#pragma once
// Thin RAII wrapper over the HDF5 C API for checkpoints: 1D datasets of double/int64/int32, scalar attributes,
// groups. Data are stored in the file's native little-endian IEEE/two's-complement types and read back without
// conversion, so every bit (denormals, signed zeros) survives a round trip. <hdf5.h> stays out of this header.
// Integrity: files use the HDF5 1.10 format, whose metadata (superblock, object headers with their attributes,
// group and chunk indexes) carry checksums, and every non-empty dataset is chunked with the Fletcher32 filter,
// so verify() detects a changed byte anywhere that matters.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace fluidbed {

class Hdf5File {
 public:
  /// Start a new file. It is written as temp_path_for(path) and appears at `path` only on commit().
  /// Throws WriteError("cannot write <path>: ..."), as do the writing calls below.
  static Hdf5File create(const std::filesystem::path& path);
  /// Open an existing file read-only. Throws Error(BadInput, "<file>: ...") if it is missing or not HDF5.
  static Hdf5File open(const std::filesystem::path& path);

  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  Hdf5File(Hdf5File&& other) noexcept;
  Hdf5File& operator=(Hdf5File&& other) noexcept;
  /// Closes the file; a created file that was not committed is deleted, leaving any previous `path` intact.
  ~Hdf5File();

  /// Close, fsync and rename the temporary file over the target. The object is closed afterwards.
  void commit();

  /// Read every dataset and attribute of an opened file, checking the checksums. Throws Error(BadInput,
  /// "<file>: corrupt: dataset 'dem/x' fails its checksum (...)") naming the first object that fails, or one
  /// written without a checksum (not a checkpoint of this format).
  void verify() const;

  /// Create a group ("particles", or nested "a/b" with its parents).
  void create_group(const std::string& group);
  /// Whether a dataset or group of that path exists ("a/b/c").
  bool has(const std::string& name) const;

  /// Write a 1D dataset; parent groups are created as needed. Writing an existing name is an error.
  void write(const std::string& name, std::span<const double> data);
  void write(const std::string& name, std::span<const std::int64_t> data);
  void write(const std::string& name, std::span<const std::int32_t> data);
  /// Write a 1D dataset of `count` values made chunk by chunk: fill(first, n, dst) writes values first ..
  /// first + n - 1 to dst. An array converted on the way (a list's slots to int64, one component of a vector)
  /// then needs one chunk of memory, not a copy of the whole.
  void write(const std::string& name, std::size_t count,
             const std::function<void(std::size_t, std::size_t, double*)>& fill);
  void write(const std::string& name, std::size_t count,
             const std::function<void(std::size_t, std::size_t, std::int64_t*)>& fill);
  void write(const std::string& name, std::size_t count,
             const std::function<void(std::size_t, std::size_t, std::int32_t*)>& fill);

  /// Read a 1D dataset of exactly that element type. Throws Error(BadInput, "<file>: ...") when the dataset is
  /// missing, not 1D, or of another type.
  std::vector<double> read_double(const std::string& name) const;
  std::vector<std::int64_t> read_int64(const std::string& name) const;
  std::vector<std::int32_t> read_int32(const std::string& name) const;

  /// Scalar attributes on an object ("/" is the root group); an existing attribute of that name is replaced.
  void set_attribute(const std::string& object, const std::string& name, double value);
  void set_attribute(const std::string& object, const std::string& name, std::int64_t value);
  void set_attribute(const std::string& object, const std::string& name, int value) {
    set_attribute(object, name, static_cast<std::int64_t>(value));
  }
  void set_attribute(const std::string& object, const std::string& name, const std::string& value);
  void set_attribute(const std::string& object, const std::string& name, const char* value) {
    set_attribute(object, name, std::string(value));
  }

  /// Read a scalar attribute of exactly that type. Throws Error(BadInput, "<file>: ...").
  double attribute_double(const std::string& object, const std::string& name) const;
  std::int64_t attribute_int64(const std::string& object, const std::string& name) const;
  std::string attribute_string(const std::string& object, const std::string& name) const;
  bool has_attribute(const std::string& object, const std::string& name) const;

  /// The final path (for a created file, where commit() puts it).
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_;  ///< non-empty while a created file is uncommitted
  std::int64_t file_ = -1;      ///< hid_t
  std::uintmax_t bytes_ = 0;    ///< payload written so far, for the disk-space note of a failed write

  Hdf5File() = default;
  void close() noexcept;
  [[noreturn]] void fail(const std::string& what) const;
  std::int64_t checked_file() const;
};

}  // namespace fluidbed
