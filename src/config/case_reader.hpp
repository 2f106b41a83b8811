#pragma once
// Typed access to a TOML case file with the checks every key needs: type, range, unit, default. Every key the
// program reads is registered as it is read, so that unknown keys are reported (with the nearest known key),
// the fully resolved case can be written back, and docs/case-format.md lists exactly what is read.
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>

namespace fluidbed {

/// What the reader knows of one key, as read.
struct KeyInfo {
  std::string path;     ///< dotted path; arrays of tables as "species[].diameter"
  std::string type;     ///< "number", "integer", "boolean", "string", "array of numbers"
  std::string unit;
  std::string doc;
  std::string range;    ///< human-readable allowed range
  std::string default_text;  ///< "" when the key is required
};

/// Allowed interval of a numeric key; unset ends are open.
struct KeyRange {
  std::optional<double> min, max;
  bool min_exclusive = false, max_exclusive = false;
};

class CaseReader {
 public:
  /// Parse `path`; a missing, unreadable or malformed file is a bad-input error naming file, line and column.
  explicit CaseReader(const std::string& path);
  /// Parse TOML text directly (tests, fuzzing); `name` stands for the file in messages.
  CaseReader(const std::string& text, const std::string& name);

  /// Apply `section.key=value` from the command line: value parsed as TOML, or as a string if it is not TOML.
  /// SECTION.ARRAY[i].KEY changes an entry the case already has; a whole array is given as a TOML array
  /// (`species=[{diameter = 0.003}]`). Anything else (an index past the end, a key under a value, a value for a
  /// section) is a bad-input error naming the override.
  void set_override(const std::string& assignment);

  using Range = KeyRange;
  static Range positive() { return Range{0.0, std::nullopt, true, false}; }
  static Range non_negative() { return Range{0.0, std::nullopt, false, false}; }
  static Range between(double lo, double hi) { return Range{lo, hi, false, false}; }

  double number(const std::string& path, double def, const std::string& unit, const std::string& doc,
                Range range = {});
  double required_number(const std::string& path, const std::string& unit, const std::string& doc, Range range = {});
  std::int64_t integer(const std::string& path, std::int64_t def, const std::string& doc, Range range = {});
  bool boolean(const std::string& path, bool def, const std::string& doc);
  std::string string(const std::string& path, const std::string& def, const std::string& doc,
                     const std::vector<std::string>& allowed = {});
  std::string required_string(const std::string& path, const std::string& doc);
  std::vector<double> numbers(const std::string& path, const std::vector<double>& def, const std::string& unit,
                              const std::string& doc, std::size_t size = 0);
  /// An array of min_size to max_size numbers (gravity: 2 in 2D, 3 in 3D).
  std::vector<double> numbers(const std::string& path, const std::vector<double>& def, const std::string& unit,
                              const std::string& doc, std::size_t min_size, std::size_t max_size);
  /// An array of strings, each one of `allowed` (when given) and none twice (periodic axes, outflow sides).
  std::vector<std::string> strings(const std::string& path, const std::vector<std::string>& def, const std::string& doc,
                                   const std::vector<std::string>& allowed = {});
  /// Number of tables in an array of tables (e.g. [[species]]); its keys are read as "name[i].key".
  std::size_t table_count(const std::string& path, const std::string& doc);
  bool has(const std::string& path) const;

  /// The default of `path` as the key table shows it, for a default derived from other keys ("t_c / 20").
  void describe_default(const std::string& path, const std::string& text);
  /// Read a key given under its old name `old_path` as `new_path` (both plain dotted paths); both given is an error.
  void alias(const std::string& old_path, const std::string& new_path);

  /// A bad-input error at `path`, naming file and line.
  [[noreturn]] void fail(const std::string& path, const std::string& message) const;

  /// Report the first key that was never read, with the nearest known key as a suggestion.
  void reject_unknown_keys() const;

  /// The case with every key that was read, defaults filled in, as TOML text.
  std::string resolved_toml() const;
  const std::vector<KeyInfo>& keys() const { return keys_; }
  const std::string& file_name() const { return name_; }

 private:
  const toml::node* find(const std::string& path) const;
  std::string where(const std::string& path) const;
  void record(const std::string& path, const std::string& type, const std::string& unit, const std::string& doc,
              const std::string& range, const std::string& def);
  void check_range(const std::string& path, double v, const Range& r) const;

  std::string name_;
  toml::table table_;
  toml::table resolved_;
  std::vector<KeyInfo> keys_;
  std::map<std::string, std::size_t> key_index_;
  std::map<std::string, std::string> overrides_;  // path -> where it came from
  std::map<std::string, std::string> moved_;      // new path -> where the old name was given
  std::set<std::string> read_;                    // indexed paths that were read
};

/// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace fluidbed
