#include "config/case_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "core/error.hpp"

namespace fluidbed {

namespace {

std::string strip_indices(const std::string& path) {
  static const std::regex idx(R"(\[[0-9]+\])");
  return std::regex_replace(path, idx, "[]");
}

std::string format_number(double v) { return fmt::format("{}", v); }

std::string node_type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date or time";
  }
}

/// Split "a.b[2].c" into {"a", "b", "[2]", "c"}.
std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> out;
  std::string cur;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const char c = path[i];
    if (c == '.') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else if (c == '[') {
      if (!cur.empty()) out.push_back(cur);
      cur = "[";
    } else if (c == ']') {
      out.push_back(cur + "]");
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

/// Set `value` at `path` in `root`, creating tables and arrays of tables on the way.
template <class V>
void insert_at(toml::table& root, const std::string& path, V&& value) {
  const auto parts = split_path(path);
  toml::node* cur = &root;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const bool last = k + 1 == parts.size();
    const std::string& part = parts[k];
    // Only paths the loader reads come here; a section given as a value in the case (domain = 1) is refused.
    const auto refuse = [&] {
      std::string owner;
      for (std::size_t j = 0; j < k; ++j) owner += (j && parts[j].front() != '[' ? "." : "") + parts[j];
      throw_input_error(fmt::format("{}: '{}' must be a {} to hold it", path, owner,
                                    part.front() == '[' ? "array of tables" : "section (a table)"));
    };
    if (part.front() == '[') {
      auto* arr = cur->as_array();
      if (!arr) refuse();
      const auto idx = static_cast<std::size_t>(std::stoul(part.substr(1, part.size() - 2)));
      while (arr->size() <= idx) arr->push_back(toml::table{});
      cur = arr->get(idx);
      continue;
    }
    auto* tbl = cur->as_table();
    if (!tbl) refuse();
    const bool next_is_index = !last && parts[k + 1].front() == '[';
    if (last) {
      tbl->insert_or_assign(part, std::forward<V>(value));
      return;
    }
    if (!tbl->contains(part)) {
      if (next_is_index) {
        tbl->insert(part, toml::array{});
      } else {
        tbl->insert(part, toml::table{});
      }
    }
    cur = tbl->get(part);
  }
}

void collect_leaves(const toml::node& node, const std::string& prefix, std::vector<std::string>& out) {
  if (const auto* t = node.as_table()) {
    for (const auto& [k, v] : *t) {
      collect_leaves(v, prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str()), out);
    }
  } else if (const auto* a = node.as_array(); a && a->is_array_of_tables() && !a->empty()) {
    for (std::size_t i = 0; i < a->size(); ++i) collect_leaves(*a->get(i), prefix + fmt::format("[{}]", i), out);
  } else {
    out.push_back(prefix);
  }
}

std::string range_text(const CaseReader::Range& r) {
  std::string s;
  if (r.min) s += fmt::format("{} {}", r.min_exclusive ? ">" : ">=", *r.min);
  if (r.max) s += fmt::format("{}{} {}", s.empty() ? "" : ", ", r.max_exclusive ? "<" : "<=", *r.max);
  return s;
}

}  // namespace

namespace {
// Case files are ASCII: anything else is rejected before the TOML parser sees it (it also keeps non-ASCII bytes away
// from a known defect of the Debian toml++ 3.3 whitespace check).
void require_ascii(const std::string& text, const std::string& name) {
  std::size_t line = 1, col = 1;
  for (unsigned char c : text) {
    if (c >= 0x80) throw_input_error(fmt::format("{}:{}:{}: non-ASCII character; case files are ASCII", name, line, col));
    if (c == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
}
}  // namespace

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

CaseReader::CaseReader(const std::string& path) : name_(path) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!std::filesystem::is_regular_file(path, ec) || !in) throw_input_error(fmt::format("{}: cannot read the case file (missing or unreadable)", path));
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw_input_error(fmt::format("{}: cannot read the case file", path));
  require_ascii(ss.str(), path);
  try {
    table_ = toml::parse(std::string_view{ss.str()}, std::string{path});
  } catch (const toml::parse_error& e) {
    throw_input_error(fmt::format("{}:{}:{}: TOML syntax error: {}", path, e.source().begin.line,
                                  e.source().begin.column, e.description()));
  }
}

CaseReader::CaseReader(const std::string& text, const std::string& name) : name_(name) {
  require_ascii(text, name);
  try {
    table_ = toml::parse(std::string_view{text}, std::string{name});
  } catch (const toml::parse_error& e) {
    throw_input_error(fmt::format("{}:{}:{}: TOML syntax error: {}", name, e.source().begin.line,
                                  e.source().begin.column, e.description()));
  }
}

namespace {

std::string kind_of(const toml::node& n) {
  if (const auto* a = n.as_array()) return a->is_array_of_tables() && !a->empty() ? "an array of tables" : "an array";
  return node_type_name(n);
}

// "a.b[2].c" from the first `count` parts of split_path.
std::string join_parts(const std::vector<std::string>& parts, std::size_t count) {
  std::string s;
  for (std::size_t k = 0; k < count; ++k) s += (k && parts[k].front() != '[' ? "." : "") + parts[k];
  return s;
}

}  // namespace

void CaseReader::set_override(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw_input_error(fmt::format("--set {}: expected SECTION.KEY=VALUE", assignment));
  }
  require_ascii(assignment, "--set");
  std::string key = assignment.substr(0, eq);
  std::string value = assignment.substr(eq + 1);
  key.erase(std::remove_if(key.begin(), key.end(), [](unsigned char c) { return std::isspace(c); }), key.end());
  static const std::regex key_re(R"([A-Za-z_][A-Za-z0-9_]*(\[[0-9]+\])*(\.[A-Za-z_][A-Za-z0-9_]*(\[[0-9]+\])*)*)");
  if (!std::regex_match(key, key_re)) {
    throw_input_error(fmt::format("--set {}: '{}' is not a valid key path (SECTION.KEY, or SECTION.ARRAY[INDEX].KEY)",
                                  assignment, key));
  }
  if (std::all_of(value.begin(), value.end(), [](unsigned char c) { return std::isspace(c); })) {
    throw_input_error(fmt::format("--set {}: no value after '='", assignment));
  }
  toml::table parsed;
  try {
    parsed = toml::parse(std::string_view{"v = " + value}, std::string{"--set"});
  } catch (const toml::parse_error&) {
    parsed = toml::table{{"v", value}};  // a bare word is taken as a string
  }
  const toml::node& v = *parsed.get("v");
  const auto bad = [&](const std::string& why) { throw_input_error(fmt::format("--set {}: {}", assignment, why)); };

  // Walk the case's own tree. An override changes what the file holds; it never creates an entry of an array
  // (that would silently add a species or a jet): arrays are extended in the file or given whole.
  const auto parts = split_path(key);
  // The node reached by parts[0..k) must take parts[k]: a key needs a table, an index an array.
  const auto require_kind = [&](const toml::node& n, std::size_t k) {
    const std::string here = join_parts(parts, k);
    const std::string& next = parts[k];
    if (next.front() == '[' && !n.is_array()) {
      bad(fmt::format("'{}' is {}, not an array: it takes no index {}", here, kind_of(n), next));
    }
    if (next.front() != '[' && !n.is_table()) {
      if (n.is_array()) bad(fmt::format("'{}' is {}: name one entry, as in {}[0].{}", here, kind_of(n), here, next));
      bad(fmt::format("'{}' is {}, not a section: it has no key '{}'", here, kind_of(n), next));
    }
  };
  toml::node* cur = &table_;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const bool last = k + 1 == parts.size();
    const std::string& part = parts[k];
    const std::string here = join_parts(parts, k + 1);
    if (part.front() == '[') {
      toml::array& arr = *cur->as_array();  // require_kind made sure
      const std::string digits = part.substr(1, part.size() - 2);
      const std::string owner = join_parts(parts, k);
      std::size_t idx = 0;
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), idx);
      if (ec != std::errc{} || end != digits.data() + digits.size() || idx >= arr.size()) {
        bad(fmt::format("'{}' has {} entr{} ({}); --set changes existing entries only: add the entry to the case "
                        "file, or give the whole array (--set '{}=[...]')",
                        owner, arr.size(), arr.size() == 1 ? "y" : "ies",
                        arr.empty()       ? std::string("none")
                        : arr.size() == 1 ? owner + "[0]"
                                          : fmt::format("{}[0] to {}[{}]", owner, owner, arr.size() - 1),
                        owner));
      }
      if (last) {
        if (arr.get(idx)->is_table() && !v.is_table()) {
          bad(fmt::format("'{}' is a table; set one of its keys ({}.KEY=VALUE) or give a table ({}={{KEY = VALUE}})",
                          here, here, here));
        }
        arr.replace(arr.cbegin() + static_cast<std::ptrdiff_t>(idx), v);
        break;
      }
      cur = arr.get(idx);
      require_kind(*cur, k + 1);
      continue;
    }
    toml::table& tbl = *cur->as_table();  // require_kind made sure
    toml::node* existing = tbl.get(part);
    if (last) {
      if (existing && existing->is_table() && !v.is_table()) {
        bad(fmt::format("'{}' is a section (a table of keys); set one of its keys: {}.KEY=VALUE", here, here));
      }
      if (existing && existing->is_array_of_tables() && !existing->as_array()->empty() && !v.is_array()) {
        bad(fmt::format("'{}' is an array of tables; set a key of one entry ({}[0].KEY=VALUE) or give the whole "
                        "array ({}=[{{KEY = VALUE}}, ...])", here, here, here));
      }
      tbl.insert_or_assign(part, v);
      break;
    }
    if (!existing) {
      if (parts[k + 1].front() == '[') {
        bad(fmt::format("the case has no '{}', so there is no {}{} to change; add it to the case file, or give the "
                        "whole array (--set '{}=[...]')", here, here, parts[k + 1], here));
      }
      tbl.insert(part, toml::table{});
      existing = tbl.get(part);
    }
    require_kind(*existing, k + 1);
    cur = existing;
  }
  overrides_[key] = "--set " + assignment;
}

const toml::node* CaseReader::find(const std::string& path) const {
  return table_.at_path(path).node();
}

bool CaseReader::has(const std::string& path) const { return find(path) != nullptr; }

std::string CaseReader::where(const std::string& path) const {
  // The override that set this key, or a section or array above it (--set 'species=[{diameter = 0.003}]').
  for (const auto& [key, origin] : overrides_) {
    if (path.compare(0, key.size(), key) == 0 &&
        (path.size() == key.size() || path[key.size()] == '.' || path[key.size()] == '[')) {
      return origin;
    }
  }
  if (auto it = moved_.find(path); it != moved_.end()) return it->second;
  const toml::node* n = find(path);
  if (n && n->source().begin.line > 0) {
    return fmt::format("{}:{}:{}", name_, n->source().begin.line, n->source().begin.column);
  }
  return name_;
}

void CaseReader::describe_default(const std::string& path, const std::string& text) {
  if (auto it = key_index_.find(strip_indices(path)); it != key_index_.end()) keys_[it->second].default_text = text;
}

void CaseReader::alias(const std::string& old_path, const std::string& new_path) {
  const toml::node* old_node = find(old_path);
  if (!old_node) return;
  if (find(new_path)) fail(old_path, fmt::format("is the old name of {}; give only {}", new_path, new_path));
  const std::string origin = fmt::format("{} ({})", where(old_path), old_path);
  try {
    insert_at(table_, new_path, *old_node);
  } catch (const Error& e) {
    throw_input_error(fmt::format("{}: {}", where(old_path), e.what()));
  }
  const auto dot = old_path.rfind('.');
  toml::table* parent = dot == std::string::npos ? &table_ : table_.at_path(old_path.substr(0, dot)).as_table();
  parent->erase(old_path.substr(dot == std::string::npos ? 0 : dot + 1));
  moved_[new_path] = origin;
}

void CaseReader::fail(const std::string& path, const std::string& message) const {
  throw_input_error(fmt::format("{}: {}: {}", where(path), path, message));
}

void CaseReader::record(const std::string& path, const std::string& type, const std::string& unit,
                        const std::string& doc, const std::string& range, const std::string& def) {
  const std::string generic = strip_indices(path);
  if (key_index_.count(generic) == 0) {
    key_index_[generic] = keys_.size();
    keys_.push_back(KeyInfo{generic, type, unit, doc, range, def});
  }
  read_.insert(path);
}

void CaseReader::check_range(const std::string& path, double v, const Range& r) const {
  const bool low = r.min && (r.min_exclusive ? !(v > *r.min) : !(v >= *r.min));
  const bool high = r.max && (r.max_exclusive ? !(v < *r.max) : !(v <= *r.max));
  if (!std::isfinite(v) || low || high) {
    fail(path, fmt::format("{} is out of range: must be {}", format_number(v), range_text(r).empty() ? "finite" : range_text(r)));
  }
}

double CaseReader::number(const std::string& path, double def, const std::string& unit, const std::string& doc,
                          Range range) {
  record(path, "number", unit, doc, range_text(range), format_number(def));
  double v = def;
  if (const toml::node* n = find(path)) {
    if (auto d = n->value<double>(); d && (n->is_floating_point() || n->is_integer())) {
      v = *d;
    } else {
      fail(path, fmt::format("expected a number{}, got {}", unit.empty() ? "" : " in " + unit, node_type_name(*n)));
    }
  }
  check_range(path, v, range);
  insert_at(resolved_, path, v);
  return v;
}

double CaseReader::required_number(const std::string& path, const std::string& unit, const std::string& doc,
                                   Range range) {
  if (!find(path)) {
    record(path, "number", unit, doc, range_text(range), "");
    throw_input_error(fmt::format("{}: missing required value {} ({}{})", name_, path, doc, unit.empty() ? "" : ", " + unit));
  }
  const double v = number(path, 0.0, unit, doc, range);
  keys_[key_index_[strip_indices(path)]].default_text = "";
  return v;
}

std::int64_t CaseReader::integer(const std::string& path, std::int64_t def, const std::string& doc, Range range) {
  record(path, "integer", "", doc, range_text(range), fmt::format("{}", def));
  std::int64_t v = def;
  if (const toml::node* n = find(path)) {
    if (const auto* i = n->as_integer()) {
      v = i->get();
    } else {
      fail(path, fmt::format("expected an integer, got {}", node_type_name(*n)));
    }
  }
  check_range(path, static_cast<double>(v), range);
  insert_at(resolved_, path, v);
  return v;
}

bool CaseReader::boolean(const std::string& path, bool def, const std::string& doc) {
  record(path, "boolean", "", doc, "true or false", def ? "true" : "false");
  bool v = def;
  if (const toml::node* n = find(path)) {
    if (const auto* b = n->as_boolean()) {
      v = b->get();
    } else {
      fail(path, fmt::format("expected true or false, got {}", node_type_name(*n)));
    }
  }
  insert_at(resolved_, path, v);
  return v;
}

std::string CaseReader::string(const std::string& path, const std::string& def, const std::string& doc,
                               const std::vector<std::string>& allowed) {
  std::string range;
  for (const auto& a : allowed) range += (range.empty() ? "" : ", ") + ("\"" + a + "\"");
  record(path, "string", "", doc, range, "\"" + def + "\"");
  std::string v = def;
  if (const toml::node* n = find(path)) {
    if (const auto* s = n->as_string()) {
      v = s->get();
    } else {
      fail(path, fmt::format("expected a string, got {}", node_type_name(*n)));
    }
  }
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), v) == allowed.end()) {
    fail(path, fmt::format("\"{}\" is not one of {}", v, range));
  }
  insert_at(resolved_, path, v);
  return v;
}

std::string CaseReader::required_string(const std::string& path, const std::string& doc) {
  if (!find(path)) {
    record(path, "string", "", doc, "", "");
    throw_input_error(fmt::format("{}: missing required value {} ({})", name_, path, doc));
  }
  const std::string v = string(path, "", doc);
  keys_[key_index_[strip_indices(path)]].default_text = "";
  return v;
}

std::vector<double> CaseReader::numbers(const std::string& path, const std::vector<double>& def,
                                        const std::string& unit, const std::string& doc, std::size_t size) {
  return numbers(path, def, unit, doc, size, size);
}

std::vector<double> CaseReader::numbers(const std::string& path, const std::vector<double>& def,
                                        const std::string& unit, const std::string& doc, std::size_t min_size,
                                        std::size_t max_size) {
  std::string def_text = "[";
  for (std::size_t i = 0; i < def.size(); ++i) def_text += (i ? ", " : "") + format_number(def[i]);
  def_text += "]";
  const std::string sizes = min_size == 0 && max_size == 0 ? std::string()
                            : min_size == max_size ? fmt::format("{} values", min_size)
                                                   : fmt::format("{} or {} values", min_size, max_size);
  record(path, "array of numbers", unit, doc, sizes, def_text);
  std::vector<double> v = def;
  if (const toml::node* n = find(path)) {
    const auto* a = n->as_array();
    if (!a) fail(path, fmt::format("expected an array of numbers, got {}", node_type_name(*n)));
    v.clear();
    for (const auto& e : *a) {
      auto d = e.value<double>();
      if (!d || !(e.is_floating_point() || e.is_integer()) || !std::isfinite(*d)) {
        fail(path, "expected an array of finite numbers");
      }
      v.push_back(*d);
    }
    if (max_size && (v.size() < min_size || v.size() > max_size)) {
      fail(path, fmt::format("expected {}, got {}", sizes, v.size()));
    }
  }
  toml::array arr;
  for (double x : v) arr.push_back(x);
  insert_at(resolved_, path, arr);
  return v;
}

std::vector<std::string> CaseReader::strings(const std::string& path, const std::vector<std::string>& def,
                                             const std::string& doc, const std::vector<std::string>& allowed) {
  std::string range;
  for (const auto& a : allowed) range += (range.empty() ? "" : ", ") + ("\"" + a + "\"");
  std::string def_text = "[";
  for (std::size_t i = 0; i < def.size(); ++i) def_text += (i ? ", \"" : "\"") + def[i] + "\"";
  def_text += "]";
  record(path, "array of strings", "", doc, range.empty() ? range : "each of " + range, def_text);
  std::vector<std::string> v = def;
  if (const toml::node* n = find(path)) {
    const auto* a = n->as_array();
    if (!a) fail(path, fmt::format("expected an array of strings, got {}", node_type_name(*n)));
    v.clear();
    for (const auto& e : *a) {
      const auto* s = e.as_string();
      if (!s) fail(path, fmt::format("expected an array of strings, got an element of type {}", node_type_name(e)));
      const std::string x = s->get();
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), x) == allowed.end()) {
        fail(path, fmt::format("\"{}\" is not one of {}", x, range));
      }
      if (std::find(v.begin(), v.end(), x) != v.end()) fail(path, fmt::format("\"{}\" is given twice", x));
      v.push_back(x);
    }
  }
  toml::array arr;
  for (const std::string& x : v) arr.push_back(x);
  insert_at(resolved_, path, arr);
  return v;
}

std::size_t CaseReader::table_count(const std::string& path, const std::string& doc) {
  record(path, "array of tables", "", doc, "", "");
  read_.insert(path);
  const toml::node* n = find(path);
  if (!n) return 0;
  const auto* a = n->as_array();
  if (!a || (!a->empty() && !a->is_array_of_tables())) {
    fail(path, fmt::format("expected an array of tables ([[{}]]), got {}", path, node_type_name(*n)));
  }
  if (!resolved_.contains(path) && path.find('.') == std::string::npos) resolved_.insert(path, toml::array{});
  return a->size();
}

void CaseReader::reject_unknown_keys() const {
  std::vector<std::string> leaves;
  collect_leaves(table_, "", leaves);
  for (const auto& leaf : leaves) {
    if (read_.count(leaf)) continue;
    const std::string generic = strip_indices(leaf);
    std::string best;
    std::size_t best_d = std::string::npos;
    for (const auto& k : keys_) {
      if (k.type == "array of tables") continue;
      const std::size_t d = edit_distance(generic, k.path);
      if (d < best_d) {
        best_d = d;
        best = k.path;
      }
    }
    std::string hint;
    if (!best.empty() && best_d <= std::max<std::size_t>(3, generic.size() / 3)) {
      hint = fmt::format("; did you mean '{}'?", best);
    }
    throw_input_error(fmt::format("{}: unknown key '{}'{}", where(leaf), leaf, hint));
  }
}

std::string CaseReader::resolved_toml() const {
  std::stringstream ss;
  ss << "# Fully resolved case: every key fluidbed read, defaults filled in.\n" << resolved_ << "\n";
  return ss.str();
}

}  // namespace fluidbed
