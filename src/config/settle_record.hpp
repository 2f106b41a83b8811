#pragma once
// What a settled bed and a case's files are, from the case alone: the record that decides whether a settle cache
// stands for this bed (the DEM model writes and reads the cache; `check` says whether it will be reused), and the
// paths a case file names.
#include <filesystem>
#include <string>

#include "config/case_config.hpp"

namespace fluidbed {

/// What a settled bed depends on (particles, placement, contact law, time step, settling criteria), one
/// `key = value` line each at full precision: stored beside the settle cache as `<cache>.record` and compared
/// before the cache is reused, so a bed settled with other parameters is never taken for this one.
std::string settled_bed_record(const CaseConfig& config);

/// Where the record of the settle cache `cache` is kept.
std::filesystem::path settled_bed_record_path(const std::filesystem::path& cache);

/// Why the existing settle cache `cache` cannot stand for the bed of `config`: "" when its record matches, "no
/// record" when it has none, else the first differing line and the cache's ("key = v (the cache: key = w)").
std::string settle_cache_mismatch(const CaseConfig& config, const std::filesystem::path& cache);

/// A path of the case file (particles.file, settle.cache): absolute as given, else relative to the case's folder.
std::filesystem::path case_relative_path(const std::string& case_file, const std::string& path);

}  // namespace fluidbed
