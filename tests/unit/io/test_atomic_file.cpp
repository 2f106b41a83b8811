#include <gtest/gtest.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "test_helpers.hpp"

namespace fluidbed {
namespace {

using test::slurp;
using test::temp_files_in;

TEST(AtomicFile, WritesStringAndLeavesNoTemporary) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto path = dir / "a.txt";
  write_file_atomic(path, std::string("first\n"));
  EXPECT_EQ(slurp(path), "first\n");
  write_file_atomic(path, std::string("second, longer\n"));
  EXPECT_EQ(slurp(path), "second, longer\n");
  EXPECT_EQ(temp_files_in(dir), 0);
}

TEST(AtomicFile, AtomicOnlyWriteReplacesTheFileWholeToo) {
  // Sync::Atomic skips the fsyncs (output frames) but keeps the temporary-and-rename protocol.
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto path = dir / "frame.vti";
  write_file_atomic(path, std::string("frame 1\n"), Sync::Atomic);
  EXPECT_EQ(slurp(path), "frame 1\n");
  write_file_atomic(path, [](std::ostream& out) { out << "frame " << 2 << '\n'; }, Sync::Atomic);
  EXPECT_EQ(slurp(path), "frame 2\n");
  EXPECT_EQ(temp_files_in(dir), 0);
}

TEST(AtomicFile, WritesThroughStreamCallback) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto path = dir / "b.txt";
  write_file_atomic(path, [](std::ostream& out) { out << "x=" << 42 << '\n'; });
  EXPECT_EQ(slurp(path), "x=42\n");
  EXPECT_EQ(temp_files_in(dir), 0);
}

TEST(AtomicFile, ThrowingWriterLeavesOldFileIntact) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto path = dir / "c.txt";
  write_file_atomic(path, std::string("old content\n"));
  EXPECT_THROW(write_file_atomic(path,
                                 [](std::ostream& out) {
                                   out << "half of the new";
                                   throw std::runtime_error("writer failed mid-way");
                                 }),
               std::runtime_error);
  EXPECT_EQ(slurp(path), "old content\n");
  EXPECT_EQ(temp_files_in(dir), 0);
}

TEST(AtomicFile, UnwritableTargetIsBadInputNamingThePath) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto path = dir / "missing-folder" / "d.txt";
  try {
    write_file_atomic(path, std::string("x"));
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_EQ(e.exit_code(), 2);
    const std::string msg = e.what();
    EXPECT_NE(msg.find("cannot write " + path.string() + ": "), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file"), std::string::npos) << msg;
  }
}

TEST(AtomicFile, WriteErrorsAreBadInputWithTheirPath) {
  const test::ScratchDir scratch;
  const auto path = scratch.path / "missing-folder" / "d.txt";
  try {
    write_file_atomic(path, std::string("x"));
    FAIL() << "expected a WriteError";
  } catch (const WriteError& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_EQ(e.path(), path);
    EXPECT_EQ(e.error_number(), ENOENT);
  }
}

TEST(AtomicFile, DiskSpaceNoteOnlyForAFullDisk) {
  // What a user needs to size the space to free: the file's size and what is left on that file system.
  const test::ScratchDir scratch;
  const std::string note = disk_space_note(scratch.path / "f.h5", 2500000, ENOSPC);
  EXPECT_EQ(note.rfind("; the file needs about 2.5 MB and ", 0), 0u) << note;
  EXPECT_NE(note.find(" free on " + scratch.path.string()), std::string::npos) << note;
  EXPECT_EQ(disk_space_note(scratch.path / "f.h5", 0, EDQUOT).rfind("; ", 0), 0u);
  EXPECT_EQ(disk_space_note(scratch.path / "f.h5", 100, EACCES), "");
}

TEST(AtomicFile, TempPathIsBesideTargetWithPid) {
  const std::filesystem::path p = "/some/dir/fields.pvd";
  EXPECT_EQ(temp_path_for(p), std::filesystem::path("/some/dir/fields.pvd.tmp." + std::to_string(::getpid())));
}

TEST(EnsureDirectory, CreatesNestedFolders) {
  const test::ScratchDir scratch;
  const auto dir = scratch.path / "a" / "b" / "c";
  ensure_directory(dir);
  EXPECT_TRUE(std::filesystem::is_directory(dir));
  ensure_directory(dir);  // existing folder: no error
}

TEST(EnsureDirectory, FileInTheWayIsBadInput) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto file = dir / "plain";
  test::spit(file, "x");
  try {
    ensure_directory(file / "sub");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_NE(std::string(e.what()).find("cannot write " + (file / "sub").string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(ensure_directory(file), Error);
}

}  // namespace
}  // namespace fluidbed
