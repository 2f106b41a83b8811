#include "io/pvd.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <utility>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace fluidbed {
namespace {

[[noreturn]] void bad(const std::filesystem::path& file, const std::string& what) {
  throw Error(ErrorKind::BadInput, file.string() + ": " + what);
}

// Value of attribute `name` inside one tag's text; false when absent or malformed.
bool attribute(std::string_view tag, std::string_view name, std::string& value) {
  std::size_t pos = 0;
  while ((pos = tag.find(name, pos)) != std::string_view::npos) {
    const bool starts_word = pos > 0 && std::isspace(static_cast<unsigned char>(tag[pos - 1]));
    std::size_t k = pos + name.size();
    while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
    if (starts_word && k < tag.size() && tag[k] == '=') {
      ++k;
      while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
      if (k >= tag.size() || (tag[k] != '"' && tag[k] != '\'')) return false;
      const char quote = tag[k];
      const std::size_t end = tag.find(quote, k + 1);
      if (end == std::string_view::npos) return false;
      value = std::string(tag.substr(k + 1, end - k - 1));
      return true;
    }
    pos += name.size();
  }
  return false;
}

// Largest run of trailing digits in the file stem ("fields/000012.vti" -> 12), or -1.
long long frame_number(const std::string& file) {
  const std::string stem = std::filesystem::path(file).stem().string();
  std::size_t start = stem.size();
  while (start > 0 && std::isdigit(static_cast<unsigned char>(stem[start - 1]))) --start;
  if (start == stem.size()) return -1;
  long long n = -1;
  std::from_chars(stem.data() + start, stem.data() + stem.size(), n);
  return n;
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string xml_unescape(const std::string& s) {
  static constexpr std::pair<std::string_view, char> entities[] = {
      {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
  std::string out;
  for (std::size_t k = 0; k < s.size(); ++k) {
    bool replaced = false;
    if (s[k] == '&') {
      for (const auto& [entity, c] : entities) {
        if (std::string_view(s).substr(k, entity.size()) == entity) {
          out += c;
          k += entity.size() - 1;
          replaced = true;
          break;
        }
      }
    }
    if (!replaced) out += s[k];
  }
  return out;
}

}  // namespace

std::string frame_file_name(const std::string& folder, std::size_t index, const std::string& extension) {
  return fmt::format("{}/{:06d}.{}", folder, index, extension);
}

std::vector<PvdEntry> read_pvd(const std::filesystem::path& pvd_path) {
  std::ifstream in(pvd_path, std::ios::binary);
  if (!in) bad(pvd_path, "cannot read the file");
  std::ostringstream text_stream;
  text_stream << in.rdbuf();
  const std::string text = text_stream.str();
  if (text.find("type=\"Collection\"") == std::string::npos || text.find("<Collection") == std::string::npos) {
    bad(pvd_path, "not a ParaView collection (no <Collection> element)");
  }
  if (text.find("</Collection>") == std::string::npos) bad(pvd_path, "truncated collection (no </Collection>)");

  std::vector<PvdEntry> entries;
  std::size_t pos = 0;
  while ((pos = text.find("<DataSet", pos)) != std::string::npos) {
    const std::size_t end = text.find('>', pos);
    if (end == std::string::npos) bad(pvd_path, "unterminated <DataSet> element");
    const std::string_view tag(text.data() + pos, end - pos);
    std::string time_text, file;
    if (!attribute(tag, "timestep", time_text)) bad(pvd_path, fmt::format("entry {}: no timestep", entries.size() + 1));
    if (!attribute(tag, "file", file) || file.empty()) {
      bad(pvd_path, fmt::format("entry {}: no file", entries.size() + 1));
    }
    double t = 0.0;
    const auto [ptr, ec] = std::from_chars(time_text.data(), time_text.data() + time_text.size(), t);
    if (ec != std::errc() || ptr != time_text.data() + time_text.size() || !std::isfinite(t)) {
      bad(pvd_path, fmt::format("entry {}: timestep '{}' is not a finite number", entries.size() + 1, time_text));
    }
    entries.push_back({t, xml_unescape(file)});
    pos = end;
  }
  return entries;
}

PvdCollection::PvdCollection(std::filesystem::path pvd_path) : path_(std::move(pvd_path)) {}

PvdCollection PvdCollection::resume(std::filesystem::path pvd_path, double restart_time) {
  PvdCollection c(std::move(pvd_path));
  std::error_code ec;
  if (!std::filesystem::exists(c.path_, ec)) return c;
  for (PvdEntry& e : read_pvd(c.path_)) {
    if (e.time <= restart_time) c.entries_.push_back(std::move(e));
  }
  c.write();
  return c;
}

void PvdCollection::add(double time, const std::string& relative_file) {
  if (!std::isfinite(time)) throw std::invalid_argument("PvdCollection::add: time is not finite");
  if (!entries_.empty()) {
    if (time < entries_.back().time) {
      throw std::invalid_argument(fmt::format("PvdCollection::add: time {} before the last entry's {}", time,
                                              entries_.back().time));
    }
    if (time == entries_.back().time) entries_.pop_back();
  }
  entries_.push_back({time, relative_file});
  write();
}

std::size_t PvdCollection::next_index() const {
  long long last = -1;
  for (const PvdEntry& e : entries_) last = std::max(last, frame_number(e.file));
  return static_cast<std::size_t>(last + 1);
}

void PvdCollection::write() const {
  std::string out = "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const PvdEntry& e : entries_) {
    out += fmt::format("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time,
                       xml_escape(e.file));
  }
  out += "  </Collection>\n</VTKFile>\n";
  write_file_atomic(path_, out, Sync::Atomic);
}

}  // namespace fluidbed
