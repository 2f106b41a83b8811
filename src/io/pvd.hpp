#pragma once
// ParaView collection (.pvd): the time index of a series of .vti/.vtu files, rewritten atomically after each
// frame so that it always lists whole files, and resumable after a restart.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace fluidbed {

struct PvdEntry {
  double time = 0.0;  ///< s
  std::string file;   ///< relative to the folder of the .pvd, e.g. "fields/000012.vti"
};

class PvdCollection {
 public:
  /// A new, empty collection; nothing is written until the first add(). An existing file is replaced then.
  explicit PvdCollection(std::filesystem::path pvd_path);

  /// Continue the collection of a restarted run: load `pvd_path` (a missing file gives an empty collection),
  /// drop entries with time > `restart_time` and rewrite the file. Throws Error(BadInput, "<file>: ...")
  /// when the file exists but is not a collection written by us.
  static PvdCollection resume(std::filesystem::path pvd_path, double restart_time);

  /// Append a frame and rewrite the .pvd atomically. A time equal to the last entry's replaces that entry;
  /// an earlier time is a programming error (std::invalid_argument).
  void add(double time, const std::string& relative_file);

  const std::vector<PvdEntry>& entries() const { return entries_; }
  const std::filesystem::path& path() const { return path_; }
  /// Index for the next frame's file name: one past the largest NNNNNN among the entries (0 when empty).
  std::size_t next_index() const;

 private:
  std::filesystem::path path_;
  std::vector<PvdEntry> entries_;

  void write() const;
};

/// Frame file name relative to the .pvd folder: frame_file_name("fields", 12, "vti") == "fields/000012.vti".
std::string frame_file_name(const std::string& folder, std::size_t index, const std::string& extension);

/// Parse the entries of a .pvd file. Throws Error(BadInput, "<file>: ...").
std::vector<PvdEntry> read_pvd(const std::filesystem::path& pvd_path);

}  // namespace fluidbed
