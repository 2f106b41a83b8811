#pragma once
// The every-bubble outputs of a run (issue 15, item 1): BubblePopulation fed with the model's voidage at every
// frame, its rows appended to bubbles.csv, bubble_events.csv and bubble_frames.csv as they come, its state in the
// checkpoint so a restart continues the same ids and velocities (docs/output-format.md).
#include <array>
#include <filesystem>
#include <optional>

#include "analysis/bubble_population.hpp"
#include "io/csv.hpp"
#include "io/hdf5_file.hpp"
#include "models/model_run.hpp"

namespace fluidbed {

/// bubbles.csv, bubble_events.csv, bubble_frames.csv of one run, 2D or 3D.
class BubbleSeries {
 public:
  /// New files in `out`, or (restart) the files cut after `t_cut` and the population restored from `checkpoint`
  /// (a checkpoint without it starts a fresh population: ids from 0 again).
  BubbleSeries(const std::filesystem::path& out, int dimension, const PopulationConfig& config, bool restart,
               double t_cut, const Hdf5File* checkpoint);

  /// One sample at time t of the fields' voidage; appends its rows.
  void observe(double t, const FieldView& fv);
  /// The population's state into group "bubbles" of `f`.
  void save(Hdf5File& f) const;

  /// The files it writes.
  static constexpr std::array<const char*, 3> kFiles{"bubbles.csv", "bubble_events.csv", "bubble_frames.csv"};

 private:
  int dim_;
  std::optional<BubblePopulation<2>> pop2_;
  std::optional<BubblePopulation<3>> pop3_;
  std::optional<CsvWriter> bubbles_, events_, frames_;
};

}  // namespace fluidbed
