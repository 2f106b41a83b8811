#include "run/checkpoint_set.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <system_error>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/error.hpp"
#include "io/hdf5_file.hpp"

namespace fluidbed {

namespace fs = std::filesystem;

namespace {

bool is_temporary(const fs::path& p) { return p.filename().string().find(".tmp.") != std::string::npos; }

bool is_periodic(const fs::path& p) {
  const std::string name = p.filename().string();
  return p.extension() == ".h5" && name.size() > 4 && name.front() == 't' && !is_temporary(p);
}

// Every leaf of a TOML table as "a.b[2].c" -> its TOML text; an array of plain values is one leaf.
void flatten(const toml::table& table, const std::string& prefix, std::map<std::string, std::string>& out);

// Numbers in their shortest round-trip form (0.004, not toml++'s 0.0040000000000000001), the rest as TOML.
std::string leaf_text(const toml::node& node) {
  if (node.is_floating_point()) return fmt::format("{}", *node.value<double>());
  if (const auto* a = node.as_array()) {
    std::string out = "[";
    for (std::size_t k = 0; k < a->size(); ++k) out += (k ? ", " : "") + leaf_text(*a->get(k));
    return out + "]";
  }
  std::ostringstream s;
  node.visit([&](const auto& n) { s << n; });
  return s.str();
}

void flatten_node(const toml::node& node, const std::string& path, std::map<std::string, std::string>& out) {
  if (const auto* t = node.as_table()) {
    flatten(*t, path + ".", out);
  } else if (const auto* a = node.as_array(); a && !a->empty() && a->is_array_of_tables()) {
    for (std::size_t k = 0; k < a->size(); ++k) flatten_node(*a->get(k), path + "[" + std::to_string(k) + "]", out);
  } else {
    out[path] = leaf_text(node);
  }
}

void flatten(const toml::table& table, const std::string& prefix, std::map<std::string, std::string>& out) {
  for (const auto& [key, node] : table) flatten_node(node, prefix + std::string(key.str()), out);
}

std::map<std::string, std::string> leaves(const std::string& text, const std::string& what) {
  std::map<std::string, std::string> out;
  try {
    flatten(toml::parse(text), "", out);
  } catch (const toml::parse_error& e) {
    throw_input_error(what + ": the case it holds cannot be read: " + std::string(e.description()));
  }
  return out;
}

// Keys that do not change how the state evolves: run control, outputs, analysis, and how the initial state was
// made (the checkpoint replaces it). Everything else, including keys added later, counts as physics.
bool changes_simulation(const std::string& key) {
  static const char* const run_only[] = {"case.name", "case.description", "case.end_time", "case.max_wall_time",
                                         "dem.max_overlap_fraction"};
  // parallel.*: how the run is split over ranks, which changes no result (docs/parallel.md).
  static const char* const sections[] = {"output.", "bubble.", "settle.", "particles.", "averages.", "parallel."};
  for (const char* k : run_only) {
    if (key == k) return false;
  }
  for (const char* s : sections) {
    if (key.rfind(s, 0) == 0) return false;
  }
  return true;
}

}  // namespace

std::vector<CheckpointFile> list_checkpoints(const fs::path& dir) {
  std::vector<CheckpointFile> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file(ec) || e.path().extension() != ".h5" || is_temporary(e.path())) continue;
    files.push_back({e.path(), e.last_write_time(ec)});
  }
  // Newest written first; equal times (coarse clocks) by name, so the order is reproducible.
  std::sort(files.begin(), files.end(), [](const CheckpointFile& a, const CheckpointFile& b) {
    return a.written != b.written ? a.written > b.written : a.path.filename() > b.path.filename();
  });
  return files;
}

LatestCheckpoint find_latest_checkpoint(const fs::path& dir) {
  LatestCheckpoint r;
  // The simulated time each checkpoint holds (its root attribute `time`, which final.h5's name lacks): file times
  // follow a copy of the folder (cp -r), not the run.
  struct Candidate {
    double time;
    fs::path path;
  };
  std::vector<Candidate> candidates;
  for (const CheckpointFile& c : list_checkpoints(dir)) {
    if (c.path.filename().string().rfind("failed-", 0) == 0) continue;
    try {
      const double t = Hdf5File::open(c.path).attribute_double("/", "time");
      if (!std::isfinite(t)) throw_input_error(fmt::format("{}: corrupt: time {} is not a number", c.path.string(), t));
      candidates.push_back({t, c.path});
    } catch (const Error& e) {
      r.skipped.push_back(e.what());
    }
  }
  // Latest simulated time first; equal times (a run that ends on a checkpoint time) by name, so the pick is the
  // same whatever order the files were written or copied in.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.time != b.time ? a.time > b.time : a.path.filename() > b.path.filename();
  });
  for (const Candidate& c : candidates) {
    try {
      Hdf5File::open(c.path).verify();
      r.path = c.path;
      return r;
    } catch (const Error& e) {
      r.skipped.push_back(e.what());
    }
  }
  return r;
}

std::vector<fs::path> rotate_checkpoints(const fs::path& dir, const fs::path& just_written, int keep) {
  std::vector<fs::path> deleted;
  int kept = 0;
  std::error_code ec;
  for (const CheckpointFile& c : list_checkpoints(dir)) {
    if (!is_periodic(c.path)) continue;
    if (fs::equivalent(c.path, just_written, ec) || ++kept <= keep - 1) continue;
    if (fs::remove(c.path, ec)) deleted.push_back(c.path);
  }
  return deleted;
}

std::vector<CaseDifference> simulation_differences(const std::string& checkpoint_toml, const std::string& case_toml) {
  const auto before = leaves(checkpoint_toml, "the checkpoint");
  const auto now = leaves(case_toml, "the case");
  std::vector<CaseDifference> diffs;
  auto value = [](const std::map<std::string, std::string>& m, const std::string& k) {
    const auto it = m.find(k);
    return it == m.end() ? std::string("(not set)") : it->second;
  };
  std::map<std::string, int> keys;
  for (const auto& [k, v] : before) keys[k] = 0;
  for (const auto& [k, v] : now) keys[k] = 0;
  // Keys that later versions write into the resolved case, with the value that is what a checkpoint without them
  // ran: such a checkpoint is not a different simulation.
  static const std::map<std::string, std::string> kAddedLater{{"case.dimension", "2"}};
  for (const auto& [k, unused] : keys) {
    if (!changes_simulation(k)) continue;
    const std::string a = value(before, k), b = value(now, k);
    const auto added = kAddedLater.find(k);
    if (a == "(not set)" && added != kAddedLater.end() && added->second == b) continue;
    if (a != b) diffs.push_back({k, a, b});
  }
  return diffs;
}

bool allowed_change(const std::string& key, const std::vector<std::string>& allowed) {
  for (const std::string& a : allowed) {
    if (a.empty()) continue;
    if (key == a) return true;
    // A section or table above the key: "inlet" or "inlet.jet[0]" for "inlet.jet[0].velocity".
    if (key.rfind(a, 0) == 0 && (key[a.size()] == '.' || key[a.size()] == '[')) return true;
  }
  return false;
}

}  // namespace fluidbed
