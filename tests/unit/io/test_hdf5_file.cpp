#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <functional>
#include <limits>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include "core/error.hpp"
#include "io/hdf5_file.hpp"
#include "test_helpers.hpp"

namespace fluidbed {
namespace {

using dlim = std::numeric_limits<double>;

// Checkpoints must restart bit-identically, so equality here is of the bit patterns, not of the values.
std::vector<std::uint64_t> bits(const std::vector<double>& v) {
  std::vector<std::uint64_t> b;
  for (const double x : v) b.push_back(std::bit_cast<std::uint64_t>(x));
  return b;
}

const std::vector<double> awkward_doubles = {0.0,
                                             -0.0,
                                             dlim::denorm_min(),
                                             -dlim::denorm_min(),
                                             1e-310,
                                             dlim::min(),
                                             dlim::max(),
                                             -dlim::max(),
                                             dlim::infinity(),
                                             -dlim::infinity(),
                                             std::bit_cast<double>(std::uint64_t{0x7ff8000000000123}),  // NaN payload
                                             0.1 / 3.0,
                                             6.02214076e23};

std::string expect_bad_input(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    return e.what();
  }
  ADD_FAILURE() << "expected an Error";
  return {};
}

TEST(Hdf5File, DatasetsRoundTripBitExact) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto path = dir / "c.h5";
  const std::vector<std::int64_t> i64 = {0, -1, 1, std::numeric_limits<std::int64_t>::min(),
                                         std::numeric_limits<std::int64_t>::max()};
  const std::vector<std::int32_t> i32 = {0, -1, std::numeric_limits<std::int32_t>::min(),
                                         std::numeric_limits<std::int32_t>::max()};
  {
    Hdf5File f = Hdf5File::create(path);
    f.write("doubles", awkward_doubles);
    f.write("particles/id", i64);
    f.write("particles/species", i32);
    f.write("empty", std::vector<double>{});
    f.create_group("gas/fields");
    f.write("gas/fields/p", std::vector<double>{1.0, 2.0});
    f.commit();
  }
  Hdf5File f = Hdf5File::open(path);
  EXPECT_EQ(bits(f.read_double("doubles")), bits(awkward_doubles));
  EXPECT_EQ(f.read_int64("particles/id"), i64);
  EXPECT_EQ(f.read_int32("particles/species"), i32);
  EXPECT_TRUE(f.read_double("empty").empty());
  EXPECT_EQ(f.read_double("gas/fields/p"), (std::vector<double>{1.0, 2.0}));
  EXPECT_TRUE(f.has("particles"));
  EXPECT_TRUE(f.has("gas/fields"));
  EXPECT_FALSE(f.has("gas/nothing/here"));
  EXPECT_FALSE(f.has("nothing"));
}

TEST(Hdf5File, AttributesRoundTripOnRootAndGroups) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto path = dir / "c.h5";
  {
    Hdf5File f = Hdf5File::create(path);
    f.set_attribute("/", "time", 0.1 / 3.0);
    f.set_attribute("/", "minus_zero", -0.0);
    f.set_attribute("/", "tiny", dlim::denorm_min());
    f.set_attribute("/", "step", std::int64_t{9007199254740993});  // 2^53 + 1: not representable as double
    f.set_attribute("/", "version", 3);
    f.set_attribute("/", "case", "gera1998/dem.toml");
    f.set_attribute("/", "empty", "");
    f.set_attribute("/", "case", std::string("replaced"));
    f.create_group("particles");
    f.set_attribute("particles", "count", std::int64_t{22000});
    f.commit();
  }
  Hdf5File f = Hdf5File::open(path);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(f.attribute_double("/", "time")), std::bit_cast<std::uint64_t>(0.1 / 3.0));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(f.attribute_double("/", "minus_zero")), std::bit_cast<std::uint64_t>(-0.0));
  EXPECT_EQ(f.attribute_double("/", "tiny"), dlim::denorm_min());
  EXPECT_EQ(f.attribute_int64("/", "step"), 9007199254740993);
  EXPECT_EQ(f.attribute_int64("", "version"), 3);
  EXPECT_EQ(f.attribute_string("/", "case"), "replaced");
  EXPECT_EQ(f.attribute_string("/", "empty"), "");
  EXPECT_EQ(f.attribute_int64("particles", "count"), 22000);
  EXPECT_TRUE(f.has_attribute("/", "time"));
  EXPECT_FALSE(f.has_attribute("/", "nope"));
  EXPECT_FALSE(f.has_attribute("nogroup", "time"));
}

TEST(Hdf5File, FileAppearsOnlyOnCommit) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto path = dir / "c.h5";
  {
    Hdf5File f = Hdf5File::create(path);
    f.write("x", std::vector<double>{1.0});
    f.commit();
  }
  {
    Hdf5File f = Hdf5File::create(path);
    f.write("x", std::vector<double>{2.0});
    EXPECT_EQ(test::temp_files_in(dir), 1);
    // Dropped without commit, as when a run fails while writing its checkpoint.
  }
  EXPECT_EQ(test::temp_files_in(dir), 0);
  EXPECT_EQ(Hdf5File::open(path).read_double("x"), std::vector<double>{1.0});
  {
    Hdf5File f = Hdf5File::create(path);
    f.write("x", std::vector<double>{3.0});
    Hdf5File moved = std::move(f);
    moved.commit();
  }
  EXPECT_EQ(test::temp_files_in(dir), 0);
  EXPECT_EQ(Hdf5File::open(path).read_double("x"), std::vector<double>{3.0});
}

TEST(Hdf5File, ReadingErrorsNameTheFileAndPrintNothing) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  const auto path = dir / "c.h5";
  {
    Hdf5File f = Hdf5File::create(path);
    f.write("ids", std::vector<std::int64_t>{1, 2});
    f.write("x", std::vector<double>{1.0});
    f.set_attribute("/", "time", 1.0);
    f.commit();
  }
  test::spit(dir / "text.h5", "this is not HDF5\n");
  ::testing::internal::CaptureStderr();
  const std::string prefix = path.string() + ": ";
  EXPECT_EQ(expect_bad_input([&] { Hdf5File::open(dir / "missing.h5"); }),
            (dir / "missing.h5").string() + ": cannot open: no such file");
  EXPECT_EQ(expect_bad_input([&] { Hdf5File::open(dir / "text.h5"); }),
            (dir / "text.h5").string() + ": not an HDF5 file");
  Hdf5File f = Hdf5File::open(path);
  EXPECT_EQ(expect_bad_input([&] { f.read_double("velocity"); }), prefix + "no dataset 'velocity'");
  EXPECT_EQ(expect_bad_input([&] { f.read_double("a/b/c"); }), prefix + "no dataset 'a/b/c'");
  EXPECT_EQ(expect_bad_input([&] { f.read_double("ids"); }), prefix + "dataset 'ids' holds int64, expected float64");
  EXPECT_EQ(expect_bad_input([&] { f.read_int32("ids"); }), prefix + "dataset 'ids' holds int64, expected int32");
  EXPECT_EQ(expect_bad_input([&] { f.read_int64("x"); }), prefix + "dataset 'x' holds float64, expected int64");
  EXPECT_EQ(expect_bad_input([&] { f.attribute_double("/", "step"); }), prefix + "no attribute 'step' on '/'");
  EXPECT_EQ(expect_bad_input([&] { f.attribute_int64("/", "time"); }),
            prefix + "attribute 'time' on '/' holds float64, expected int64");
  EXPECT_EQ(expect_bad_input([&] { f.attribute_string("/", "time"); }),
            prefix + "attribute 'time' on '/' holds float64, expected a string");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(Hdf5File, TruncatedFileIsBadInputNotACrash) {
  const test::ScratchDir scratch;
  const auto path = scratch.path / "c.h5";
  {
    Hdf5File f = Hdf5File::create(path);
    f.write("x", std::vector<double>(4096, 1.5));
    f.set_attribute("/", "time", 2.0);
    f.commit();
  }
  const auto full = std::filesystem::file_size(path);
  for (const auto keep : {full / 2, std::uintmax_t{600}, std::uintmax_t{8}}) {
    std::filesystem::resize_file(path, keep);
    ::testing::internal::CaptureStderr();
    try {
      Hdf5File f = Hdf5File::open(path);
      (void)f.attribute_double("/", "time");
      (void)f.read_double("x");
      ADD_FAILURE() << "read a file truncated to " << keep << " of " << full << " bytes";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::BadInput);
      EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": ", 0), 0u) << e.what();
    }
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  }
}

TEST(Hdf5File, WritingErrorsAreBadInput) {
  const test::ScratchDir scratch;
  const auto& dir = scratch.path;
  ::testing::internal::CaptureStderr();
  const std::string msg = expect_bad_input([&] { Hdf5File::create(dir / "no" / "c.h5"); });
  EXPECT_EQ(msg.rfind("cannot write " + (dir / "no" / "c.h5").string() + ": ", 0), 0u) << msg;
  Hdf5File f = Hdf5File::create(dir / "c.h5");
  f.write("x", std::vector<double>{1.0});
  const std::string twice = expect_bad_input([&] { f.write("x", std::vector<double>{2.0}); });
  EXPECT_NE(twice.find("cannot create dataset 'x'"), std::string::npos) << twice;
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(test::temp_files_in(dir), 1);  // still open, uncommitted
}

// A file with a dataset whose values have a bit pattern found nowhere else, so a test can damage exactly it.
std::filesystem::path write_marked_file(const std::filesystem::path& dir) {
  const auto path = dir / "c.h5";
  Hdf5File f = Hdf5File::create(path);
  f.create_group("dem");
  f.write("dem/x", std::vector<double>(500, 0.123456789012345));
  f.write("dem/id", std::vector<std::int64_t>{1, 2, 3});
  f.write("dem/empty", std::vector<double>{});
  f.set_attribute("/", "case_toml", std::string("[case]\nname = \"marked-case-record\"\n"));
  f.set_attribute("dem", "time", 0.25);
  f.commit();
  return path;
}

std::vector<char> file_bytes(const std::filesystem::path& p) {
  const std::string s = test::slurp(p);
  return {s.begin(), s.end()};
}

void put_bytes(const std::filesystem::path& p, const std::vector<char>& bytes) {
  test::spit(p, std::string(bytes.begin(), bytes.end()));
}

std::size_t find_bytes(const std::vector<char>& data, const void* pattern, std::size_t n) {
  const char* c = static_cast<const char*>(pattern);
  const auto it = std::search(data.begin(), data.end(), c, c + n);
  return it == data.end() ? std::string::npos : static_cast<std::size_t>(it - data.begin());
}

TEST(Hdf5File, VerifyAcceptsAWholeFile) {
  const test::ScratchDir scratch;
  const auto path = write_marked_file(scratch.path);
  ::testing::internal::CaptureStderr();
  EXPECT_NO_THROW(Hdf5File::open(path).verify());
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(Hdf5File, VerifyNamesTheDatasetWhoseChecksumFails) {
  // One flipped bit in the payload: the checkpoint was loaded and failed the run steps later.
  const test::ScratchDir scratch;
  const auto path = write_marked_file(scratch.path);
  std::vector<char> data = file_bytes(path);
  const double marker = 0.123456789012345;
  const std::size_t at = find_bytes(data, &marker, sizeof marker);
  ASSERT_NE(at, std::string::npos);
  data[at + 8 * 250 + 2] ^= 0x10;
  put_bytes(path, data);
  ::testing::internal::CaptureStderr();
  const Hdf5File f = Hdf5File::open(path);
  const std::string msg = expect_bad_input([&] { f.verify(); });
  EXPECT_EQ(msg.rfind(path.string() + ": corrupt: dataset 'dem/x' fails its checksum", 0), 0u) << msg;
  const std::string read = expect_bad_input([&] { (void)f.read_double("dem/x"); });
  EXPECT_NE(read.find("dataset 'dem/x' cannot be read (corrupt"), std::string::npos) << read;
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// HDF5 1.10.8 leaks 56 bytes when it meets a bad checksum while iterating attributes; that is the library's, and
// LeakSanitizer (make asan) is told to ignore what is allocated while a damaged file is read.
#if defined(__SANITIZE_ADDRESS__)
struct LibraryLeaksIgnored {
  LibraryLeaksIgnored() { __lsan_disable(); }
  ~LibraryLeaksIgnored() { __lsan_enable(); }
};
#else
struct LibraryLeaksIgnored {};
#endif

// The 1.10 format's metadata checksums cover the superblock and the object headers holding the attributes.
void expect_refused_with_byte_flipped(bool in_superblock) {
  const test::ScratchDir scratch;
  const auto path = write_marked_file(scratch.path);
  std::vector<char> data = file_bytes(path);
  const std::string record = "marked-case-record";
  const std::size_t at = in_superblock ? 20 : find_bytes(data, record.data(), record.size()) + 3;
  ASSERT_LT(at, data.size());
  data[at] ^= 0x01;
  put_bytes(path, data);
  ::testing::internal::CaptureStderr();
  const std::string msg = expect_bad_input([&] {
    const LibraryLeaksIgnored ignored;
    (void)ignored;
    Hdf5File::open(path).verify();
  });
  EXPECT_EQ(msg.rfind(path.string() + ": ", 0), 0u) << "byte " << at << ": " << msg;
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(Hdf5File, VerifyRefusesADamagedSuperblock) { expect_refused_with_byte_flipped(true); }
TEST(Hdf5File, VerifyRefusesADamagedAttribute) { expect_refused_with_byte_flipped(false); }

}  // namespace
}  // namespace fluidbed
