#pragma once
// Minimal reader of the VTK XML files we write (appended data, UInt64 headers, raw or zlib-compressed in the
// block layout of vtkZLibDataCompressor), to check them from C++ without the VTK library.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace fluidbed::test {

struct VtkArrayInfo {
  std::string type;
  int components = 1;
  std::size_t offset = 0;
};

/// The UInt64 header of one compressed array: block count, uncompressed block size, uncompressed size of the
/// last block (0: full), the compressed size of each block; `bytes` is the header's own length.
struct VtkBlockHeader {
  std::uint64_t blocks = 0, block_size = 0, last_size = 0;
  std::vector<std::uint64_t> compressed;
  std::size_t bytes = 0;
};

struct VtkParsed {
  std::string header;  ///< XML before the appended data
  std::map<std::string, VtkArrayInfo> arrays;
  std::string appended;  ///< bytes after the '_' marker
  bool compressed = false;  ///< the file declares compressor="vtkZLibDataCompressor"

  VtkBlockHeader block_header(const std::string& name) const {
    VtkBlockHeader h;
    const std::size_t at = arrays.at(name).offset;
    auto word = [&](std::size_t k) {
      std::uint64_t w = 0;
      if (at + 8 * (k + 1) > appended.size()) {
        ADD_FAILURE() << "block header of " << name << " runs past the data";
        return w;
      }
      std::memcpy(&w, appended.data() + at + 8 * k, sizeof w);
      return w;
    };
    h.blocks = word(0);
    h.block_size = word(1);
    h.last_size = word(2);
    if (h.blocks > appended.size()) {
      ADD_FAILURE() << "implausible block count for " << name;
      return h;
    }
    for (std::uint64_t b = 0; b < h.blocks; ++b) h.compressed.push_back(word(3 + b));
    h.bytes = 8 * (3 + h.blocks);
    return h;
  }

  /// The uncompressed bytes of array `name`, checked against the block sizes (compressed) or the UInt64 byte
  /// count (raw).
  std::string bytes(const std::string& name) const {
    const auto it = arrays.find(name);
    if (it == arrays.end()) {
      ADD_FAILURE() << "no array " << name;
      return {};
    }
    const std::size_t at = it->second.offset;
    if (!compressed) {
      std::uint64_t n = 0;
      std::memcpy(&n, appended.data() + at, sizeof n);
      if (at + 8 + n > appended.size()) {
        ADD_FAILURE() << "bad block size for " << name;
        return {};
      }
      return appended.substr(at + 8, n);
    }
    const VtkBlockHeader h = block_header(name);
    std::string out;
    std::size_t src = at + h.bytes;
    for (std::uint64_t b = 0; b < h.blocks; ++b) {
      const bool partial = b + 1 == h.blocks && h.last_size != 0;
      uLongf len = static_cast<uLongf>(partial ? h.last_size : h.block_size);
      if (src + h.compressed[b] > appended.size()) {
        ADD_FAILURE() << "block " << b << " of " << name << " runs past the data";
        return {};
      }
      std::string block(len, '\0');
      const int rc = uncompress(reinterpret_cast<Bytef*>(block.data()), &len,
                                reinterpret_cast<const Bytef*>(appended.data() + src), h.compressed[b]);
      const uLongf expected = static_cast<uLongf>(partial ? h.last_size : h.block_size);
      if (rc != Z_OK || len != expected) {
        ADD_FAILURE() << "block " << b << " of " << name << ": zlib code " << rc << ", " << len << " bytes";
        return {};
      }
      out += block;
      src += h.compressed[b];
    }
    return out;
  }

  template <class T>
  std::vector<T> values(const std::string& name) const {
    const std::string b = bytes(name);
    if (b.size() % sizeof(T) != 0) {
      ADD_FAILURE() << name << ": " << b.size() << " bytes is not a whole number of values";
      return {};
    }
    std::vector<T> out(b.size() / sizeof(T));
    if (!b.empty()) std::memcpy(out.data(), b.data(), b.size());
    return out;
  }
};

inline std::string attribute_of(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t p = tag.find(key);
  if (p == std::string::npos) return {};
  const std::size_t start = p + key.size();
  return tag.substr(start, tag.find('"', start) - start);
}

inline VtkParsed parse_vtk(const std::string& text) {
  VtkParsed out;
  const std::string marker = "<AppendedData encoding=\"raw\">";
  const std::size_t a = text.find(marker);
  if (a == std::string::npos) {
    ADD_FAILURE() << "no raw AppendedData";
    return out;
  }
  out.header = text.substr(0, a);
  const std::size_t root = out.header.find("<VTKFile");
  const std::string vtkfile = out.header.substr(root, out.header.find('>', root) - root);
  out.compressed = attribute_of(vtkfile, "compressor") == "vtkZLibDataCompressor";
  const std::size_t underscore = text.find('_', a + marker.size());
  const std::size_t tail = text.rfind("</AppendedData>");
  out.appended = text.substr(underscore + 1, tail - underscore - 1);
  std::size_t pos = 0;
  while ((pos = out.header.find("<DataArray", pos)) != std::string::npos) {
    const std::size_t end = out.header.find('>', pos);
    const std::string tag = out.header.substr(pos, end - pos);
    if (attribute_of(tag, "format") == "appended") {
      VtkArrayInfo info;
      info.type = attribute_of(tag, "type");
      info.components = std::stoi(attribute_of(tag, "NumberOfComponents"));
      info.offset = std::stoull(attribute_of(tag, "offset"));
      out.arrays[attribute_of(tag, "Name")] = info;
    }
    pos = end;
  }
  return out;
}

}  // namespace fluidbed::test
