#pragma once
// The run driver: owns the output folder, steps a model, writes outputs and checkpoints, shows progress, and
// stops cleanly on a signal, a stop file or a wall-time limit.
#include <optional>
#include <string>
#include <vector>

#include "config/case_loader.hpp"
#include "parallel/comm.hpp"

namespace fluidbed {

struct RunOptions {
  std::string out_dir;                 ///< default out/<case name>
  std::optional<double> end_time;      ///< --end-time (already applied to the loaded case; kept for the continue command)
  int threads = 0;                     ///< 0: OpenMP default
  std::string restart;                 ///< checkpoint to continue from, or "latest" (the newest valid one of out_dir)
  bool quiet = false;
  std::optional<double> max_wall_time; ///< s; overrides case.max_wall_time
  std::vector<std::string> sets;       ///< the --set overrides as given (already applied; for the continue command)
  bool overwrite = false;              ///< a new run may replace the results in out_dir
  std::vector<std::string> allow_changed;  ///< keys (or sections) a restart may change against its checkpoint
  /// The processes of the run (null: one). On several ranks every rank runs run_case with the same options; rank 0
  /// writes the folder, the log and the progress, and every decision (stop, failure) is taken by all together.
  const Comm* comm = nullptr;
};

/// Exit codes of the contract: 0 done, 130 interrupted with a checkpoint. Bad input and simulation failures
/// are thrown as Error (exit 2 and 3); a failed run writes a final checkpoint before it throws, and a failed
/// write (disk full) is a simulation failure that keeps the last complete checkpoint.
int run_case(const LoadedCase& loaded, const RunOptions& options);

/// How long a rank that has met a failure waits for the others to meet it too before it ends the run for all
/// (Comm::all_arrive_within, Comm::abort), s: ranks that fail together (a verdict reached collectively) arrive
/// within a step of each other. 30 s, or FLUIDBED_FAILURE_WAIT (the tests shorten it).
double failure_verdict_seconds();

}  // namespace fluidbed
