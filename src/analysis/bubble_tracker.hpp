#pragma once
// Bubble analytics of the paper's Section 3 (Table 2): nose, rise velocity, gas velocity at the nose, throughflow,
// attachment to the jet, detachment and eruption. Works on plain cell-centred fields, so CFD-DEM and TFM share it.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/field2.hpp"
#include "core/grid2.hpp"

namespace fluidbed {

/// Settings of the bubble tracker; defaults are the paper's bed (Table 1) and bubble boundary (Section 3).
struct BubbleConfig {
  Grid2 grid;                    ///< grid of the fields passed to observe() (checked when nx > 0)
  double eps_threshold = 0.8;    ///< a cell belongs to a bubble when eps > this (paper, Section 3)
  double jet_x = 0.3;            ///< m, horizontal centre of the jet
  double jet_width = 0.02;       ///< m
  double min_area = 8.0e-4;      ///< m^2, smaller voids are not counted as bubbles (two 2 cm cells)
  double u_mf = 1.8;             ///< m/s, minimum fluidization velocity (Table 1), scales the throughflow
  double surface_eps = 0.7;      ///< a row whose mean eps is below this belongs to the bed (bed surface)
  int rise_velocity_samples = 3; ///< least-squares slope of the nose over this many samples (2: backward difference)
};

/// One observation; optional values are empty when there is no bubble (or, for velocities, too few samples).
struct BubbleSample {
  double time = 0.0;                              ///< s
  std::optional<double> nose_height;              ///< m
  std::optional<double> nose_x;                   ///< m, where the nose was sought
  std::optional<double> rise_velocity;            ///< m/s
  std::optional<double> nose_gas_velocity;        ///< m/s, interstitial, half a cell above the nose
  std::optional<double> throughflow_ratio;        ///< U_th / U_mf
  std::optional<double> area;                     ///< m^2
  std::optional<double> equivalent_diameter;      ///< m, sqrt(4 A / pi)
  std::optional<double> centroid_x, centroid_y;   ///< m
  std::optional<bool> attached;                   ///< touches the bottom cells above the jet
  std::optional<double> bed_height;               ///< m, top of the highest bed row; empty without a bed
  bool erupted = false;                           ///< the tracked bubble merged with the freeboard at this sample
  bool detached = false;                          ///< the tracked bubble left the jet at this sample
  int bubble_id = -1;                             ///< 0 for the first bubble tracked, 1 for the next...; -1 none
};

/// Follows one bubble at a time: the jet bubble, then, once it detached, the same region as it rises, until it
/// erupts at the bed surface; then the next bubble. Call observe() once per sample, times increasing.
class BubbleTracker {
 public:
  explicit BubbleTracker(const BubbleConfig& config);

  BubbleSample observe(double t, const Grid2& grid, const Field2& eps, const Field2& ug_cc, const Field2& vg_cc);

  /// Time of the first sample at which a bubble that had been attached was no longer attached.
  std::optional<double> detachment_time() const { return detachment_time_; }
  /// Time of the first eruption of a tracked bubble at the bed surface.
  std::optional<double> eruption_time() const { return eruption_time_; }
  const BubbleConfig& config() const { return config_; }

  /// Everything the tracker remembers between samples, for checkpoints (a restarted run samples the same).
  struct State {
    std::vector<std::uint8_t> tracked;
    bool tracking = false;
    bool was_attached = false;
    int bubble_count = 0;
    std::vector<double> nose_t, nose_h;
    std::optional<double> detachment_time, eruption_time;
  };
  State state() const {
    return {tracked_, tracking_, was_attached_, bubble_count_, nose_t_, nose_h_, detachment_time_, eruption_time_};
  }
  void restore(State s) {
    tracked_ = std::move(s.tracked);
    tracking_ = s.tracking;
    was_attached_ = s.was_attached;
    bubble_count_ = s.bubble_count;
    nose_t_ = std::move(s.nose_t);
    nose_h_ = std::move(s.nose_h);
    detachment_time_ = s.detachment_time;
    eruption_time_ = s.eruption_time;
  }

 private:
  BubbleConfig config_;
  std::vector<std::uint8_t> tracked_;  // cells of the tracked bubble at the previous sample
  bool tracking_ = false;
  bool was_attached_ = false;
  int bubble_count_ = 0;
  std::vector<double> nose_t_, nose_h_;  // nose history of the tracked bubble, for the rise velocity
  std::optional<double> detachment_time_, eruption_time_;
};

/// Sub-cell height where a vertical eps profile sampled at cell centres y_lo < y_hi crosses the threshold
/// (linear interpolation; exact for a linear profile).
double threshold_crossing(double y_lo, double eps_lo, double y_hi, double eps_hi, double threshold);

/// Bilinear interpolation of a cell-centred field at (x, y), clamped to the outermost cell centres.
double interpolate_cell_centred(const Grid2& grid, const Field2& f, double x, double y);

/// Connected regions (4-neighbours) of the cells where mask != 0; label -1 outside the mask, labels 0..n-1 in
/// order of the first cell met in i-fastest order. Returns the number of regions.
int label_regions(int nx, int ny, const std::vector<std::uint8_t>& mask, std::vector<int>& label);

/// bubble.csv header: the columns of docs/interface.md, then equivalent_diameter_m, bed_height_m, erupted,
/// bubble_id, nose_x_m.
std::string bubble_csv_header();
/// One bubble.csv line (no newline); empty values where the sample has none.
std::string bubble_csv_row(const BubbleSample& s);
/// The same row as numbers (empty optionals where there is no value), in bubble_csv_header() order.
std::vector<std::optional<double>> bubble_csv_values(const BubbleSample& s);

}  // namespace fluidbed
