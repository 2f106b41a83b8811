#pragma once
// Whole-file atomic writes: a reader (ParaView, a post script, a restart) never sees a half-written file,
// and a run killed mid-write leaves the previous version in place.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <span>
#include <string>
#include <string_view>

#include "core/error.hpp"

namespace fluidbed {

/// A file that could not be written (disk full, quota, I/O error). Its kind is BadInput, as for an unwritable
/// output folder named on the command line; the run driver turns one that happens during a run into a
/// simulation failure (exit 3) with its diagnosis. The message is "cannot write <path>: <reason>[; space note]".
class WriteError : public Error {
 public:
  WriteError(std::filesystem::path path, const std::string& message, int error_number = 0)
      : Error(ErrorKind::BadInput, message), path_(std::move(path)), errno_(error_number) {}
  const std::filesystem::path& path() const { return path_; }
  int error_number() const { return errno_; }  ///< errno of the failed call, 0 when not from a system call

 private:
  std::filesystem::path path_;
  int errno_;
};

/// "; the file needs about 1.2 MB and 0.3 MB are free on <folder>" for a write that failed with ENOSPC or
/// EDQUOT (empty for other errors): what a user needs to size the space to free.
std::string disk_space_note(const std::filesystem::path& path, std::uintmax_t bytes_needed, int error_number);

/// Temporary name used while `path` is being written: `path.tmp.<pid>` in the same folder (same file system,
/// so the final rename is atomic).
std::filesystem::path temp_path_for(const std::filesystem::path& path);

/// How far a write is protected. Both are atomic against a killed process (a reader sees the old or the new
/// file, never a part). Durable also survives a crash of the operating system (fsync of the file and folder);
/// Atomic leaves that to the kernel's write-back. Output frames use Atomic: a restart rewrites every frame after
/// its checkpoint, and 300 fsyncs per simulated second cost 10% of a TFM run's wall time.
enum class Sync { Durable, Atomic };

/// Write `content` to `path` atomically: temporary file, (fsync), rename over the target, (fsync of the folder).
/// Throws WriteError("cannot write <path>: <reason>"); on failure the target is untouched and no temporary file
/// is left behind.
void write_file_atomic(const std::filesystem::path& path, std::string_view content, Sync sync = Sync::Durable);

/// As above, the content being `pieces` one after the other: a large file (a particle frame) is written from its
/// parts without first being joined into one string.
void write_file_atomic(const std::filesystem::path& path, std::span<const std::string_view> pieces,
                       Sync sync = Sync::Durable);

/// As above, with the content produced by `writer` into a stream. If `writer` throws, its exception propagates
/// and nothing is written.
void write_file_atomic(const std::filesystem::path& path, const std::function<void(std::ostream&)>& writer,
                       Sync sync = Sync::Durable);

/// fsync an existing file and rename it over `target` atomically, then fsync the folder. For writers that
/// produce the temporary file themselves (HDF5). Throws as write_file_atomic; removes `temp` on failure.
void commit_temp_file(const std::filesystem::path& temp, const std::filesystem::path& target);

/// Create `dir` and its parents if missing and check that files can be created in it.
/// Throws Error(BadInput, "cannot write <dir>: <reason>").
void ensure_directory(const std::filesystem::path& dir);

}  // namespace fluidbed
