#pragma once
// `fluidbed ensemble`: N realisations of one case, differing only in case.seed (the random packing), run as
// separate processes, at most `jobs` at a time (issue 15, item 6). Each member is a plain run folder
// DIR/seed-<seed>; DIR/ensemble.json lists them for `fluidbed report DIR` (mean and spread, docs/analysis.md).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace fluidbed {

struct EnsembleOptions {
  std::string case_file;
  std::string out_dir;               ///< default out/<case name>-ensemble
  int members = 8;                   ///< N
  int jobs = 2;                      ///< members running at once
  int threads = 1;                   ///< OpenMP threads per member
  std::optional<double> end_time;
  std::vector<std::string> sets;     ///< --set overrides for every member
  bool overwrite = false;
  bool quiet = false;
};

/// Seeds of the members: the case's seed, then seed + 1, ... (member k has seed + k).
std::vector<std::uint64_t> ensemble_seeds(std::uint64_t first, int members);

/// Runs the members (the program itself, `run`, via /proc/self/exe) and writes ensemble.json. Returns 0 when every
/// member ended with 0, else 3 naming the failed members (their folders keep their logs). Throws Error(BadInput)
/// for a bad case or options, before any member starts.
int run_ensemble(const EnsembleOptions& options);

}  // namespace fluidbed
