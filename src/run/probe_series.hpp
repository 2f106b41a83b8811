#pragma once
// probes.csv of a run (issue 15, item 4): the case's probes sampled from the model's fields, one row per sample,
// continued after a restart (docs/output-format.md).
#include <filesystem>
#include <optional>
#include <vector>

#include "analysis/probes.hpp"
#include "io/csv.hpp"
#include "io/particle_arrays.hpp"
#include "models/model_run.hpp"

namespace fluidbed {

/// probes.csv: time_s, then probe_columns() of the case's probes.
class ProbeSeries {
 public:
  /// New file `path`, or (restart) the file cut after `t_cut`. `solids`: the model has a solids velocity field.
  ProbeSeries(const std::filesystem::path& path, const std::vector<ProbeSpec>& probes, int dimension, bool solids,
              bool restart, double t_cut);
  /// One row at time t; `particles` (null for none) feed the probes of the particles' tops.
  void sample(double t, const FieldView& fv, const ParticleArrays* particles = nullptr);
  /// Whether a probe reads the particles (then the runner gathers them for every row).
  bool reads_particles() const;

 private:
  std::vector<ProbeSpec> probes_;
  int dim_;
  std::optional<CsvWriter> csv_;
  std::vector<double> tops_;  ///< the particles' tops of the row being sampled
};

}  // namespace fluidbed
