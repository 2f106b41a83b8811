#pragma once
// The run driver: owns the output folder, steps a model, writes outputs and checkpoints, shows progress, and
// stops cleanly on a signal, a stop file or a wall-time limit.
#include <optional>
#include <string>

#include "io/case_loader.hpp"

namespace fluidbed {

struct RunOptions {
  std::string out_dir;                 ///< default out/<case name>
  std::optional<double> end_time;      ///< overrides case.end_time
  int threads = 0;                     ///< 0: OpenMP default
  std::string restart;                 ///< checkpoint to continue from
  bool quiet = false;
  std::optional<double> max_wall_time; ///< s; overrides case.max_wall_time
};

/// Exit codes of the contract: 0 done, 130 interrupted with a checkpoint. Bad input and simulation failures
/// are thrown as Error (exit 2 and 3); a failed run writes a final checkpoint before it throws.
int run_case(const LoadedCase& loaded, const RunOptions& options);

}  // namespace fluidbed
