#pragma once
// The time averages of a run (issue 15, item 4): TimeAverage fed with the model's fields (and, for CFD-DEM, its
// particles) at the samples of the case's [averages] window; averages.vti, averages.csv and averages.json written
// when the window closes and at the end of the run; the sums in the checkpoint, so a restart gives the same
// averages bit for bit (docs/output-format.md, docs/analysis.md "Time averages").
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>

#include "analysis/time_average.hpp"
#include "io/hdf5_file.hpp"
#include "models/model_run.hpp"

namespace fluidbed {

/// The averages of one run, 2D or 3D, over one window.
class AverageSeries {
 public:
  /// A fresh average on the grid of `fv`, or (checkpoint given) the one saved in it. A checkpoint without
  /// averages, or with those of another window, starts a fresh one (`restored()` then says false) whose first
  /// sample is the first one due after `t_now`, the model time (the instant itself was observed before the
  /// checkpoint was written).
  AverageSeries(std::filesystem::path out, const AveragesConfig& config, const FieldView& fv,
                const Hdf5File* checkpoint, double t_now);

  /// Called after every model step at model time t, with the step's time-step slack `dt` (as the output
  /// schedules): adds a sample when one is due in the window, and writes the files once the window is over.
  void observe(double t, double dt, const FieldView& fv, const std::optional<ParticleArrays>& particles);
  /// Writes the files if any sample was taken (the end of the run: a window cut short is written as it stands).
  void finish();
  /// The sums and the sampling schedule into group "averages" of `f`.
  void save(Hdf5File& f) const;

  /// Whether observe(t, dt, ...) takes a sample (and so reads the particles).
  bool samples_at(double t, double dt) const { return !closed_ && due(t, dt); }
  bool restored() const { return restored_; }
  std::int64_t samples() const;
  /// The files it writes.
  static constexpr std::array<const char*, 3> kFiles{"averages.vti", "averages.csv", "averages.json"};

 private:
  void add(double t, const FieldView& fv, const std::optional<ParticleArrays>& particles);
  void write() const;
  template <int Dim>
  void write_dim(const TimeAverage<Dim>& avg) const;
  bool due(double t, double dt) const;
  double due_time() const { return config_.t_start + static_cast<double>(next_) * config_.interval; }

  std::filesystem::path out_;
  AveragesConfig config_;
  int dim_ = 2;
  std::optional<TimeAverage<2>> avg2_;
  std::optional<TimeAverage<3>> avg3_;
  std::int64_t next_ = 0;       ///< index of the next sample, due at t_start + next * interval
  double first_t_ = 0.0, last_t_ = 0.0;
  bool closed_ = false;         ///< the window is over and its files are written
  bool restored_ = false;
};

}  // namespace fluidbed
