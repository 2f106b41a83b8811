#pragma once
// The checkpoints of an output folder: which one a restart takes (`--restart latest`), which ones rotation
// deletes, and whether a checkpoint continues the same simulation as the case it is restarted with.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fluidbed {

class Hdf5File;

/// A checkpoint file of checkpoints/: t<time>.h5 (periodic or on a stop), final.h5, failed-t<time>.h5.
struct CheckpointFile {
  std::filesystem::path path;
  std::filesystem::file_time_type written{};  ///< modification time: "newest" is the one written last
};

/// Checkpoint files of `dir` (checkpoints/), newest written first; temporaries (*.tmp.<pid>) are not listed.
std::vector<CheckpointFile> list_checkpoints(const std::filesystem::path& dir);

/// What `--restart latest` chose: the checkpoint of the latest simulated time that passes Hdf5File::verify(), and
/// the ones it skipped with the reason (later ones that fail verify(), and any whose time cannot be read).
struct LatestCheckpoint {
  std::filesystem::path path;                ///< empty when none passed
  std::vector<std::string> skipped;          ///< "<file>: <reason>"
};

/// The valid checkpoint of `dir` with the latest simulated time (the root attribute `time`; equal times by name,
/// the greater first), whatever the files' modification times (failed-*.h5, the state a run failed in, is not a
/// candidate).
LatestCheckpoint find_latest_checkpoint(const std::filesystem::path& dir);

/// Keep the `keep` newest periodic checkpoints t<time>.h5 of `dir`, deleting older ones; `just_written` (which
/// is complete: rotation runs after its commit) is never deleted. Returns the deleted files.
std::vector<std::filesystem::path> rotate_checkpoints(const std::filesystem::path& dir,
                                                      const std::filesystem::path& just_written, int keep);

/// One key whose value differs between the case a checkpoint was written with and the case of the restart.
struct CaseDifference {
  std::string key;         ///< "species[0].diameter"
  std::string checkpoint;  ///< value in the checkpoint's case ("(not set)" when absent)
  std::string current;     ///< value in the restart's case
};

/// Keys that change the simulation (everything but run control, output, analysis and the initial placement
/// that the checkpoint replaces) whose values differ between two resolved case TOML texts.
std::vector<CaseDifference> simulation_differences(const std::string& checkpoint_toml, const std::string& case_toml);

/// Whether `key` is allowed to differ by one of the `--allow-changed` entries: the key itself, or a section or
/// table above it ("inlet" allows "inlet.jet[0].velocity").
bool allowed_change(const std::string& key, const std::vector<std::string>& allowed);

}  // namespace fluidbed
