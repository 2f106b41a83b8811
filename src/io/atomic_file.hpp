#pragma once
// Whole-file atomic writes: a reader (ParaView, a post script, a restart) never sees a half-written file,
// and a run killed mid-write leaves the previous version in place.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string_view>

namespace fluidbed {

/// Temporary name used while `path` is being written: `path.tmp.<pid>` in the same folder (same file system,
/// so the final rename is atomic).
std::filesystem::path temp_path_for(const std::filesystem::path& path);

/// Write `content` to `path` atomically: temporary file, fsync, rename over the target, fsync of the folder.
/// Throws Error(BadInput, "cannot write <path>: <reason>"); on failure the target is untouched and no
/// temporary file is left behind.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// As above, with the content produced by `writer` into a stream. If `writer` throws, its exception propagates
/// and nothing is written.
void write_file_atomic(const std::filesystem::path& path, const std::function<void(std::ostream&)>& writer);

/// fsync an existing file and rename it over `target` atomically, then fsync the folder. For writers that
/// produce the temporary file themselves (HDF5). Throws as write_file_atomic; removes `temp` on failure.
void commit_temp_file(const std::filesystem::path& temp, const std::filesystem::path& target);

/// Create `dir` and its parents if missing and check that files can be created in it.
/// Throws Error(BadInput, "cannot write <dir>: <reason>").
void ensure_directory(const std::filesystem::path& dir);

}  // namespace fluidbed
