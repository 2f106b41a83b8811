#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fmt/format.h>
#include <sstream>
#include <string>
#include <system_error>

#include "core/error.hpp"

namespace fluidbed {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& reason) {
  throw WriteError(path, "cannot write " + path.string() + ": " + reason);
}

std::string errno_text(int err) { return std::strerror(err); }

// A failed system call on `path` while writing `bytes` bytes: the reason, and the space note when it is a full disk.
[[noreturn]] void fail_errno(const std::filesystem::path& path, int err, std::uintmax_t bytes) {
  throw WriteError(path, "cannot write " + path.string() + ": " + errno_text(err) + disk_space_note(path, bytes, err),
                   err);
}

std::string size_text(std::uintmax_t bytes) {
  const double b = static_cast<double>(bytes);
  if (b < 1e6) return fmt::format("{:.3g} kB", b / 1e3);
  if (b < 1e9) return fmt::format("{:.3g} MB", b / 1e6);
  return fmt::format("{:.3g} GB", b / 1e9);
}

// Best effort: the rename is already atomic; syncing the folder makes it survive a power loss.
void sync_directory(const std::filesystem::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

// `total`: the size of the whole file, for the disk-space note.
void write_all(int fd, std::string_view content, const std::filesystem::path& target,
               const std::filesystem::path& temp, std::size_t total) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      ::unlink(temp.c_str());
      fail_errno(target, err, total);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

}  // namespace

std::string disk_space_note(const std::filesystem::path& path, std::uintmax_t bytes_needed, int error_number) {
  if (error_number != ENOSPC && error_number != EDQUOT) return {};
  const std::filesystem::path dir = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  const std::string need = bytes_needed > 0 ? fmt::format("; the file needs about {}", size_text(bytes_needed)) : "";
  struct statvfs fs {};
  if (::statvfs(dir.c_str(), &fs) != 0) return need;
  const std::uintmax_t free_bytes = static_cast<std::uintmax_t>(fs.f_bavail) * fs.f_frsize;
  return fmt::format("{}{}{} free on {}", need, need.empty() ? "; " : " and ", size_text(free_bytes), dir.string());
}

std::filesystem::path temp_path_for(const std::filesystem::path& path) {
  std::filesystem::path temp = path;
  temp += ".tmp." + std::to_string(static_cast<long long>(::getpid()));
  return temp;
}

void commit_temp_file(const std::filesystem::path& temp, const std::filesystem::path& target) {
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(temp, ec);
  const int fd = ::open(temp.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    ::unlink(temp.c_str());
    fail_errno(target, err, ec ? 0 : bytes);
  }
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    ::unlink(temp.c_str());
    fail_errno(target, err, ec ? 0 : bytes);
  }
  ::close(fd);
  if (::rename(temp.c_str(), target.c_str()) != 0) {
    const int err = errno;
    ::unlink(temp.c_str());
    fail_errno(target, err, ec ? 0 : bytes);
  }
  sync_directory(target.parent_path());
}

void write_file_atomic(const std::filesystem::path& path, std::string_view content, Sync sync) {
  write_file_atomic(path, std::span<const std::string_view>(&content, 1), sync);
}

void write_file_atomic(const std::filesystem::path& path, std::span<const std::string_view> pieces, Sync sync) {
  if (path.empty()) fail(path, "empty file name");
  std::size_t total = 0;
  for (const std::string_view piece : pieces) total += piece.size();
  const std::filesystem::path temp = temp_path_for(path);
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail_errno(path, errno, total);
  for (const std::string_view piece : pieces) write_all(fd, piece, path, temp, total);
  if (sync == Sync::Durable && ::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    ::unlink(temp.c_str());
    fail_errno(path, err, total);
  }
  // close() reports deferred write errors on some file systems (NFS).
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(temp.c_str());
    fail_errno(path, err, total);
  }
  if (::rename(temp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(temp.c_str());
    fail_errno(path, err, total);
  }
  if (sync == Sync::Durable) sync_directory(path.parent_path());
}

void write_file_atomic(const std::filesystem::path& path, const std::function<void(std::ostream&)>& writer,
                       Sync sync) {
  // Buffer in memory so that a throwing writer leaves no trace on disk; output files are a few MB at most.
  std::ostringstream buffer;
  writer(buffer);
  if (!buffer) fail(path, "the content could not be formatted");
  write_file_atomic(path, buffer.view(), sync);
}

void ensure_directory(const std::filesystem::path& dir) {
  if (dir.empty()) return;
  std::error_code ec;
  const auto status = std::filesystem::status(dir, ec);
  if (std::filesystem::exists(status)) {
    if (!std::filesystem::is_directory(status)) fail(dir, "exists and is not a folder");
  } else {
    std::filesystem::create_directories(dir, ec);
    if (ec) fail(dir, "cannot create the folder: " + ec.message());
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) fail(dir, "the folder is not writable: " + errno_text(errno));
}

}  // namespace fluidbed
