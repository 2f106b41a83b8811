#pragma once
// Minimal reader of the VTK XML files we write (raw appended data, UInt64 headers), to check them from C++
// without the VTK library.
#include <gtest/gtest.h>

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

struct VtkParsed {
  std::string header;  ///< XML before the appended data
  std::map<std::string, VtkArrayInfo> arrays;
  std::string appended;  ///< bytes after the '_' marker

  /// Raw payload of array `name`, checked against its UInt64 byte count.
  template <class T>
  std::vector<T> values(const std::string& name) const {
    const auto it = arrays.find(name);
    if (it == arrays.end()) {
      ADD_FAILURE() << "no array " << name;
      return {};
    }
    std::uint64_t bytes = 0;
    std::memcpy(&bytes, appended.data() + it->second.offset, sizeof bytes);
    if (bytes % sizeof(T) != 0 || it->second.offset + 8 + bytes > appended.size()) {
      ADD_FAILURE() << "bad block size for " << name;
      return {};
    }
    std::vector<T> out(bytes / sizeof(T));
    if (bytes > 0) std::memcpy(out.data(), appended.data() + it->second.offset + 8, bytes);
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
