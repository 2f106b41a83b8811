#include "io/hdf5_file.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <span>
#include <system_error>
#include <type_traits>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace fluidbed {
namespace {

static_assert(std::is_same_v<hid_t, std::int64_t>, "the header stores hid_t as std::int64_t");

// Closes an HDF5 identifier at scope exit.
class Handle {
 public:
  Handle(hid_t id, herr_t (*closer)(hid_t)) : id_(id), closer_(closer) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*closer_)(hid_t);
};

// Set when H5Fclose failed (a write failed: disk full). HDF5 cannot release such a file, and its own exit handler
// crashes trying again (HDF5 1.10.8), so ours shuts the library down only when every file closed.
std::atomic<bool> unclosed_file{false};

extern "C" void close_hdf5_at_exit() {
  if (!unclosed_file.load()) H5close();
}

// Our own messages replace HDF5's stack dump on stderr.
void silence_hdf5() {
  static const bool once = [] {
    H5dont_atexit();
    std::atexit(close_hdf5_at_exit);
    return true;
  }();
  (void)once;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

herr_t first_error(unsigned n, const H5E_error2_t* err, void* data) {
  if (n == 0 && err != nullptr && err->desc != nullptr) *static_cast<std::string*>(data) = err->desc;
  return 0;
}

// The most specific message on HDF5's error stack (where the failure was detected), then clear the stack.
std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, first_error, &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? std::string("HDF5 error") : "HDF5: " + reason;
}

// The errno HDF5's POSIX driver reports in its message ("..., errno = 28, error message = ..."), or 0.
int errno_in(const std::string& reason) {
  const std::size_t at = reason.find("errno = ");
  return at == std::string::npos ? 0 : std::atoi(reason.c_str() + at + 8);
}

// A failed system call as the user reads it ("No space left on device"), instead of the driver's dump of
// buffers and offsets; HDF5's own text otherwise.
std::string write_reason(const std::string& reason) {
  const int err = errno_in(reason);
  return err != 0 ? std::string(std::strerror(err)) : reason;
}

// The 1.10 file format: checksums on the superblock, object headers (and so attributes) and chunk indexes.
hid_t file_access_plist() {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl >= 0) {
    H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110);
    // No aggregation blocks: their unused tail is bytes no checksum covers.
    H5Pset_meta_block_size(fapl, 0);
    H5Pset_small_data_block_size(fapl, 0);
  }
  return fapl;
}

// Elements per chunk, each with its own Fletcher32 checksum: 512 KB of doubles, so that writing an array costs at
// most that much on top of it (HDF5 filters a copy of each chunk; docs/performance.md, section 21). Files written
// with the earlier 2^20 read the same: the chunk size is recorded in each dataset.
constexpr hsize_t kChunkElements = hsize_t{1} << 16;

std::string object_path(const std::string& object) { return object.empty() ? std::string("/") : object; }

template <class T>
struct Hdf5Type;
template <>
struct Hdf5Type<double> {
  static hid_t file() { return H5T_IEEE_F64LE; }
  static hid_t memory() { return H5T_NATIVE_DOUBLE; }
  static constexpr H5T_class_t type_class = H5T_FLOAT;
  static constexpr const char* name = "float64";
};
template <>
struct Hdf5Type<std::int64_t> {
  static hid_t file() { return H5T_STD_I64LE; }
  static hid_t memory() { return H5T_NATIVE_INT64; }
  static constexpr H5T_class_t type_class = H5T_INTEGER;
  static constexpr const char* name = "int64";
};
template <>
struct Hdf5Type<std::int32_t> {
  static hid_t file() { return H5T_STD_I32LE; }
  static hid_t memory() { return H5T_NATIVE_INT32; }
  static constexpr H5T_class_t type_class = H5T_INTEGER;
  static constexpr const char* name = "int32";
};

std::string describe_type(hid_t type) {
  const H5T_class_t c = H5Tget_class(type);
  const std::size_t size = H5Tget_size(type);
  switch (c) {
    case H5T_FLOAT: return "float" + std::to_string(8 * size);
    case H5T_INTEGER:
      return (H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(8 * size);
    case H5T_STRING: return "string";
    default: return "an unsupported type";
  }
}

// Exact match only: a silent HDF5 conversion (int -> double, float32 -> float64) would hide a format mismatch.
template <class T>
bool type_matches(hid_t type) {
  if (H5Tget_class(type) != Hdf5Type<T>::type_class || H5Tget_size(type) != sizeof(T)) return false;
  if constexpr (std::is_integral_v<T>) return H5Tget_sign(type) == H5T_SGN_2;
  return true;
}

hid_t link_creation_plist() {
  const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  if (lcpl >= 0) H5Pset_create_intermediate_group(lcpl, 1);
  return lcpl;
}

// Writes `count` values chunk by chunk: source(first, n, buffer) returns the values first .. first + n - 1,
// either in place (an array written as it is) or converted into `buffer` (n values), so a converted array costs one
// chunk of memory, not a copy of the whole.
template <class T>
void write_dataset(hid_t file, const std::string& name, std::size_t count,
                   const std::function<const T*(std::size_t, std::size_t, T*)>& source,
                   const std::function<void(const std::string&)>& fail) {
  const hsize_t dims[1] = {static_cast<hsize_t>(count)};
  Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
  if (!space.valid()) fail("cannot create the dataspace of '" + name + "'");
  Handle lcpl(link_creation_plist(), H5Pclose);
  // Chunked with a Fletcher32 checksum per chunk, which H5Dread checks; an empty dataset has no chunk to check.
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (!dcpl.valid()) fail("cannot create the properties of dataset '" + name + "'");
  const hsize_t chunk = std::min(dims[0], kChunkElements);
  if (count > 0) {
    const hsize_t chunk_dims[1] = {chunk};
    if (H5Pset_chunk(dcpl.get(), 1, chunk_dims) < 0 || H5Pset_fletcher32(dcpl.get()) < 0) {
      fail("cannot set the checksum of dataset '" + name + "'");
    }
  }
  Handle set(H5Dcreate2(file, name.c_str(), Hdf5Type<T>::file(), space.get(), lcpl.get(), dcpl.get(), H5P_DEFAULT),
             H5Dclose);
  if (!set.valid()) fail("cannot create dataset '" + name + "'");
  // One write per whole chunk, so HDF5 filters each chunk once and needs no chunk cache.
  std::vector<T> buffer;
  for (hsize_t first = 0; first < dims[0]; first += chunk) {
    const hsize_t n[1] = {std::min(chunk, dims[0] - first)};
    const hsize_t start[1] = {first};
    if (buffer.empty() && n[0] > 0) buffer.resize(static_cast<std::size_t>(chunk));
    const T* values = source(static_cast<std::size_t>(first), static_cast<std::size_t>(n[0]), buffer.data());
    Handle memory(H5Screate_simple(1, n, nullptr), H5Sclose);
    if (!memory.valid() ||
        H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, n, nullptr) < 0 ||
        H5Dwrite(set.get(), Hdf5Type<T>::memory(), memory.get(), space.get(), H5P_DEFAULT, values) < 0) {
      fail("cannot write dataset '" + name + "'");
    }
  }
}

template <class T>
void write_dataset(hid_t file, const std::string& name, std::span<const T> data,
                   const std::function<void(const std::string&)>& fail) {
  write_dataset<T>(
      file, name, data.size(), [data](std::size_t first, std::size_t, T*) { return data.data() + first; }, fail);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------

Hdf5File Hdf5File::create(const std::filesystem::path& path) {
  silence_hdf5();
  // HDF5's own message for a missing folder is long; say it plainly.
  const std::filesystem::path parent = path.parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
    throw Error(ErrorKind::BadInput, "cannot write " + path.string() + ": no folder " + parent.string());
  }
  Hdf5File f;
  f.path_ = path;
  f.temp_ = temp_path_for(path);
  Handle fapl(file_access_plist(), H5Pclose);
  f.file_ = H5Fcreate(f.temp_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (f.file_ < 0) {
    const std::string reason = hdf5_reason();
    ::unlink(f.temp_.c_str());
    f.temp_.clear();
    throw WriteError(path, "cannot write " + path.string() + ": " + write_reason(reason) +
                               disk_space_note(path, 0, errno_in(reason)), errno_in(reason));
  }
  return f;
}

Hdf5File Hdf5File::open(const std::filesystem::path& path) {
  silence_hdf5();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error(ErrorKind::BadInput, path.string() + ": cannot open: no such file");
  }
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    throw Error(ErrorKind::BadInput, path.string() + ": not an HDF5 file");
  }
  Hdf5File f;
  f.path_ = path;
  f.file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f.file_ < 0) throw Error(ErrorKind::BadInput, path.string() + ": cannot open: " + hdf5_reason());
  return f;
}

Hdf5File::Hdf5File(Hdf5File&& other) noexcept
    : path_(std::move(other.path_)), temp_(std::move(other.temp_)), file_(other.file_), bytes_(other.bytes_) {
  other.file_ = -1;
  other.temp_.clear();
}

Hdf5File& Hdf5File::operator=(Hdf5File&& other) noexcept {
  if (this != &other) {
    close();
    path_ = std::move(other.path_);
    temp_ = std::move(other.temp_);
    file_ = other.file_;
    bytes_ = other.bytes_;
    other.file_ = -1;
    other.temp_.clear();
  }
  return *this;
}

Hdf5File::~Hdf5File() { close(); }

void Hdf5File::close() noexcept {
  if (file_ >= 0 && H5Fclose(file_) < 0) unclosed_file.store(true);
  file_ = -1;
  if (!temp_.empty()) {
    ::unlink(temp_.c_str());
    temp_.clear();
  }
}

void Hdf5File::fail(const std::string& what) const {
  const std::string reason = hdf5_reason();
  if (!temp_.empty()) {
    const int err = errno_in(reason);
    throw WriteError(path_, "cannot write " + path_.string() + ": " + what + " (" + write_reason(reason) + ")" +
                                disk_space_note(path_, bytes_, err), err);
  }
  throw Error(ErrorKind::BadInput, path_.string() + ": " + what + " (" + reason + ")");
}

std::int64_t Hdf5File::checked_file() const {
  if (file_ < 0) throw Error(ErrorKind::BadInput, path_.string() + ": the HDF5 file is closed");
  return file_;
}

void Hdf5File::commit() {
  if (temp_.empty()) throw Error(ErrorKind::BadInput, path_.string() + ": not a file being written");
  const hid_t file = checked_file();
  file_ = -1;
  if (H5Fclose(file) < 0) {
    unclosed_file.store(true);
    const std::string reason = hdf5_reason();
    ::unlink(temp_.c_str());
    temp_.clear();
    const int err = errno_in(reason);
    throw WriteError(path_, "cannot write " + path_.string() + ": " + write_reason(reason) +
                                disk_space_note(path_, bytes_, err), err);
  }
  const std::filesystem::path temp = temp_;
  temp_.clear();
  commit_temp_file(temp, path_);
}

void Hdf5File::create_group(const std::string& group) {
  Handle lcpl(link_creation_plist(), H5Pclose);
  Handle g(H5Gcreate2(checked_file(), group.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail("cannot create group '" + group + "'");
}

bool Hdf5File::has(const std::string& name) const {
  const hid_t file = checked_file();
  if (name.empty() || name == "/") return true;
  // H5Lexists needs every parent to exist, so walk the path one component at a time.
  std::size_t pos = name.front() == '/' ? 1 : 0;
  while (pos <= name.size()) {
    const std::size_t slash = name.find('/', pos);
    const std::string prefix = name.substr(0, slash == std::string::npos ? name.size() : slash);
    const htri_t exists = H5Lexists(file, prefix.c_str(), H5P_DEFAULT);
    if (exists <= 0) {
      H5Eclear2(H5E_DEFAULT);
      return false;
    }
    if (slash == std::string::npos) break;
    pos = slash + 1;
  }
  return true;
}

void Hdf5File::write(const std::string& name, std::span<const double> data) {
  bytes_ += data.size() * sizeof(double);
  write_dataset(checked_file(), name, data, [this](const std::string& w) { fail(w); });
}
void Hdf5File::write(const std::string& name, std::span<const std::int64_t> data) {
  bytes_ += data.size() * sizeof(std::int64_t);
  write_dataset(checked_file(), name, data, [this](const std::string& w) { fail(w); });
}
void Hdf5File::write(const std::string& name, std::span<const std::int32_t> data) {
  bytes_ += data.size() * sizeof(std::int32_t);
  write_dataset(checked_file(), name, data, [this](const std::string& w) { fail(w); });
}

namespace {

template <class T>
std::function<const T*(std::size_t, std::size_t, T*)> filling(const std::function<void(std::size_t, std::size_t, T*)>& fill) {
  return [&fill](std::size_t first, std::size_t n, T* buffer) {
    fill(first, n, buffer);
    return static_cast<const T*>(buffer);
  };
}

}  // namespace

void Hdf5File::write(const std::string& name, std::size_t count,
                     const std::function<void(std::size_t, std::size_t, double*)>& fill) {
  bytes_ += count * sizeof(double);
  write_dataset<double>(checked_file(), name, count, filling(fill), [this](const std::string& w) { fail(w); });
}
void Hdf5File::write(const std::string& name, std::size_t count,
                     const std::function<void(std::size_t, std::size_t, std::int64_t*)>& fill) {
  bytes_ += count * sizeof(std::int64_t);
  write_dataset<std::int64_t>(checked_file(), name, count, filling(fill), [this](const std::string& w) { fail(w); });
}
void Hdf5File::write(const std::string& name, std::size_t count,
                     const std::function<void(std::size_t, std::size_t, std::int32_t*)>& fill) {
  bytes_ += count * sizeof(std::int32_t);
  write_dataset<std::int32_t>(checked_file(), name, count, filling(fill), [this](const std::string& w) { fail(w); });
}

namespace {

template <class T>
std::vector<T> read_dataset(hid_t file, const std::filesystem::path& path, const std::string& name) {
  auto bad = [&](const std::string& what) -> void {
    H5Eclear2(H5E_DEFAULT);
    throw Error(ErrorKind::BadInput, path.string() + ": dataset '" + name + "' " + what);
  };
  Handle set(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!set.valid()) bad("cannot be opened");
  Handle type(H5Dget_type(set.get()), H5Tclose);
  if (!type_matches<T>(type.get())) {
    bad("holds " + describe_type(type.get()) + ", expected " + Hdf5Type<T>::name);
  }
  Handle space(H5Dget_space(set.get()), H5Sclose);
  if (H5Sget_simple_extent_ndims(space.get()) != 1) bad("is not one-dimensional");
  hsize_t dims[1] = {0};
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  std::vector<T> data(static_cast<std::size_t>(dims[0]));
  if (!data.empty() && H5Dread(set.get(), Hdf5Type<T>::memory(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0) {
    const std::string reason = hdf5_reason();
    bad("cannot be read (corrupt: " + reason + ")");
  }
  return data;
}

}  // namespace

std::vector<double> Hdf5File::read_double(const std::string& name) const {
  if (!has(name)) throw Error(ErrorKind::BadInput, path_.string() + ": no dataset '" + name + "'");
  return read_dataset<double>(checked_file(), path_, name);
}
std::vector<std::int64_t> Hdf5File::read_int64(const std::string& name) const {
  if (!has(name)) throw Error(ErrorKind::BadInput, path_.string() + ": no dataset '" + name + "'");
  return read_dataset<std::int64_t>(checked_file(), path_, name);
}
std::vector<std::int32_t> Hdf5File::read_int32(const std::string& name) const {
  if (!has(name)) throw Error(ErrorKind::BadInput, path_.string() + ": no dataset '" + name + "'");
  return read_dataset<std::int32_t>(checked_file(), path_, name);
}

// ---------------------------------------------------------------------------------------------------------------
// Attributes

bool Hdf5File::has_attribute(const std::string& object, const std::string& name) const {
  const std::string obj = object_path(object);
  if (!has(obj)) return false;
  const htri_t exists = H5Aexists_by_name(checked_file(), obj.c_str(), name.c_str(), H5P_DEFAULT);
  if (exists < 0) H5Eclear2(H5E_DEFAULT);
  return exists > 0;
}

namespace {

void write_attribute(hid_t file, const std::string& object, const std::string& name, hid_t file_type,
                     hid_t memory_type, const void* value, const std::function<void(const std::string&)>& fail) {
  const std::string where = "attribute '" + name + "' on '" + object + "'";
  if (H5Aexists_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT) > 0 &&
      H5Adelete_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT) < 0) {
    fail("cannot replace " + where);
  }
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate_by_name(file, object.c_str(), name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  if (!attr.valid()) fail("cannot create " + where);
  if (H5Awrite(attr.get(), memory_type, value) < 0) fail("cannot write " + where);
}

}  // namespace

void Hdf5File::set_attribute(const std::string& object, const std::string& name, double value) {
  write_attribute(checked_file(), object_path(object), name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value,
                  [this](const std::string& w) { fail(w); });
}

void Hdf5File::set_attribute(const std::string& object, const std::string& name, std::int64_t value) {
  write_attribute(checked_file(), object_path(object), name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value,
                  [this](const std::string& w) { fail(w); });
}

void Hdf5File::set_attribute(const std::string& object, const std::string& name, const std::string& value) {
  // Fixed-length, null-padded: the stored length is the string's, so embedded text is kept exactly.
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!type.valid() || H5Tset_size(type.get(), std::max<std::size_t>(1, value.size())) < 0 ||
      H5Tset_strpad(type.get(), H5T_STR_NULLPAD) < 0) {
    fail("cannot make the string type of attribute '" + name + "'");
  }
  std::string padded = value;
  if (padded.empty()) padded.push_back('\0');
  write_attribute(checked_file(), object_path(object), name, type.get(), type.get(), padded.data(),
                  [this](const std::string& w) { fail(w); });
}

namespace {

// Opens attribute `name` of `object`, checked to exist; the caller checks its type.
hid_t open_attribute(const Hdf5File& f, hid_t file, const std::string& object, const std::string& name) {
  if (!f.has_attribute(object, name)) {
    throw Error(ErrorKind::BadInput, f.path().string() + ": no attribute '" + name + "' on '" + object + "'");
  }
  const hid_t attr = H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  if (attr < 0) {
    H5Eclear2(H5E_DEFAULT);
    throw Error(ErrorKind::BadInput,
                f.path().string() + ": attribute '" + name + "' on '" + object + "' cannot be opened");
  }
  return attr;
}

template <class T>
T read_scalar_attribute(const Hdf5File& f, hid_t file, const std::string& object, const std::string& name) {
  Handle attr(open_attribute(f, file, object, name), H5Aclose);
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  const std::string where = f.path().string() + ": attribute '" + name + "' on '" + object + "'";
  if (!type_matches<T>(type.get())) {
    throw Error(ErrorKind::BadInput, where + " holds " + describe_type(type.get()) + ", expected " + Hdf5Type<T>::name);
  }
  if (H5Sget_simple_extent_npoints(space.get()) != 1) throw Error(ErrorKind::BadInput, where + " is not a scalar");
  T value{};
  if (H5Aread(attr.get(), Hdf5Type<T>::memory(), &value) < 0) {
    H5Eclear2(H5E_DEFAULT);
    throw Error(ErrorKind::BadInput, where + " cannot be read");
  }
  return value;
}

}  // namespace

double Hdf5File::attribute_double(const std::string& object, const std::string& name) const {
  return read_scalar_attribute<double>(*this, checked_file(), object_path(object), name);
}

std::int64_t Hdf5File::attribute_int64(const std::string& object, const std::string& name) const {
  return read_scalar_attribute<std::int64_t>(*this, checked_file(), object_path(object), name);
}

std::string Hdf5File::attribute_string(const std::string& object, const std::string& name) const {
  const std::string obj = object_path(object);
  Handle attr(open_attribute(*this, checked_file(), obj, name), H5Aclose);
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  const std::string where = path_.string() + ": attribute '" + name + "' on '" + obj + "'";
  if (H5Tget_class(type.get()) != H5T_STRING) {
    throw Error(ErrorKind::BadInput, where + " holds " + describe_type(type.get()) + ", expected a string");
  }
  if (H5Tis_variable_str(type.get()) > 0) {
    throw Error(ErrorKind::BadInput, where + " is a variable-length string; fixed-length expected");
  }
  std::string value(H5Tget_size(type.get()), '\0');
  if (H5Aread(attr.get(), type.get(), value.data()) < 0) {
    H5Eclear2(H5E_DEFAULT);
    throw Error(ErrorKind::BadInput, where + " cannot be read");
  }
  while (!value.empty() && value.back() == '\0') value.pop_back();
  return value;
}

// ---------------------------------------------------------------------------------------------------------------
// Integrity

namespace {

struct VerifyState {
  std::string problem;  ///< first failure, "" while all is well
};

// Reads every attribute of `object` in its stored type: HDF5 checks the checksum of the header holding it.
herr_t verify_attribute(hid_t object, const char* name, const H5A_info_t* /*info*/, void* data) {
  auto& st = *static_cast<VerifyState*>(data);
  Handle attr(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  Handle type(attr.valid() ? H5Aget_type(attr.get()) : -1, H5Tclose);
  Handle space(attr.valid() ? H5Aget_space(attr.get()) : -1, H5Sclose);
  const hssize_t n = space.valid() ? H5Sget_simple_extent_npoints(space.get()) : -1;
  bool ok = attr.valid() && type.valid() && n >= 0 && H5Tis_variable_str(type.get()) <= 0;
  if (ok) {
    std::vector<unsigned char> buffer(static_cast<std::size_t>(n) * H5Tget_size(type.get()) + 1);
    ok = H5Aread(attr.get(), type.get(), buffer.data()) >= 0;
  }
  if (!ok) {
    st.problem = std::string("attribute '") + name + "' cannot be read (" + hdf5_reason() + ")";
    return 1;
  }
  return 0;
}

herr_t verify_object(hid_t root, const char* name, const H5O_info_t* info, void* data) {
  auto& st = *static_cast<VerifyState*>(data);
  const std::string where = std::string(name) == "." ? std::string("/") : std::string(name);
  Handle object(H5Oopen(root, name, H5P_DEFAULT), H5Oclose);
  if (!object.valid()) {
    st.problem = "object '" + where + "' cannot be opened (" + hdf5_reason() + ")";
    return 1;
  }
  hsize_t index = 0;
  if (H5Aiterate2(object.get(), H5_INDEX_NAME, H5_ITER_NATIVE, &index, verify_attribute, &st) != 0) {
    if (st.problem.empty()) {
      st.problem = "the attributes of '" + where + "' cannot be read (" + hdf5_reason() + ")";
    } else {
      st.problem += " on '" + where + "'";
    }
    return 1;
  }
  if (info->type != H5O_TYPE_DATASET) return 0;
  const std::string what = "dataset '" + where + "'";
  Handle type(H5Dget_type(object.get()), H5Tclose);
  Handle space(H5Dget_space(object.get()), H5Sclose);
  Handle dcpl(H5Dget_create_plist(object.get()), H5Pclose);
  const hssize_t n = space.valid() ? H5Sget_simple_extent_npoints(space.get()) : -1;
  if (!type.valid() || n < 0 || !dcpl.valid()) {
    st.problem = what + " cannot be opened (" + hdf5_reason() + ")";
    return 1;
  }
  if (n == 0) return 0;
  unsigned flags = 0;
  if (H5Pget_filter_by_id2(dcpl.get(), H5Z_FILTER_FLETCHER32, &flags, nullptr, nullptr, 0, nullptr, nullptr) < 0) {
    H5Eclear2(H5E_DEFAULT);
    st.problem = what + " has no checksum (not a checkpoint of this fluidbed version)";
    return 1;
  }
  std::vector<unsigned char> buffer(static_cast<std::size_t>(n) * H5Tget_size(type.get()));
  if (H5Dread(object.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0) {
    st.problem = what + " fails its checksum (" + hdf5_reason() + ")";
    return 1;
  }
  return 0;
}

}  // namespace

void Hdf5File::verify() const {
  VerifyState st;
  const herr_t rc = H5Ovisit2(checked_file(), H5_INDEX_NAME, H5_ITER_NATIVE, verify_object, &st, H5O_INFO_BASIC);
  if (rc != 0 || !st.problem.empty()) {
    if (st.problem.empty()) st.problem = "its objects cannot be listed (" + hdf5_reason() + ")";
    H5Eclear2(H5E_DEFAULT);
    throw Error(ErrorKind::BadInput, path_.string() + ": corrupt: " + st.problem);
  }
}

}  // namespace fluidbed
