#pragma once
// Bubble analytics of the paper's Section 3 (Table 2): nose, rise velocity, gas velocity at the nose, throughflow,
// attachment to the jet, detachment and eruption. Works on plain cell-centred fields (CellView), so CFD-DEM and TFM,
// 2D and 3D share it: bubbles are 4-connected regions of cells in 2D, 6-connected (face neighbours) in 3D.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "analysis/cell_view.hpp"
#include "core/index_box.hpp"
#include "fluid/gas_config.hpp"

namespace fluidbed {

/// Settings of the bubble tracker; defaults are the paper's bed (Table 1) and bubble boundary (Section 3).
struct BubbleConfig {
  /// Cells per axis of the fields passed to observe(), each checked where > 0 (axis 2 only in 3D); 0: any.
  Index<3> cells{};
  double eps_threshold = 0.8;    ///< a cell belongs to a bubble when eps > this (paper, Section 3)
  double jet_x = 0.3;            ///< m, horizontal centre of the jet
  double jet_width = 0.02;       ///< m
  double min_area = 8.0e-4;      ///< m^2, smaller voids are not counted as bubbles (two 2 cm cells)
  double u_mf = 1.8;             ///< m/s, minimum fluidization velocity (Table 1), scales the throughflow
  double surface_eps = 0.7;      ///< a row whose mean eps is below this belongs to the bed (bed surface)
  int rise_velocity_samples = 3; ///< least-squares slope of the nose over this many samples (2: backward difference)
  double gravity = 9.81;         ///< m/s^2, magnitude, for the single-bubble rise velocity of the theory
  // 3D only (the 2D tracker ignores them):
  double min_volume = 1.6e-5;    ///< m^3, smaller voids are not counted as bubbles (two 2 cm cubes)
  /// The jet's footprint on the bottom face: Slot spans the whole depth, Rectangle is jet_width x jet_depth, Disc
  /// has the diameter jet_width; all centred on (jet_x, jet_z).
  InletShape jet_shape = InletShape::Slot;
  std::optional<double> jet_z;   ///< m, depth of the jet centre and of the nose line; empty: mid-depth
  double jet_depth = 0.0;        ///< m, z extent of a Rectangle
};

/// One observation; optional values are empty when there is no bubble (or, for velocities, too few samples).
struct BubbleSample {
  double time = 0.0;                              ///< s
  std::optional<double> nose_height;              ///< m
  std::optional<double> nose_x;                   ///< m, where the nose was sought
  std::optional<double> rise_velocity;            ///< m/s, of the nose
  /// m/s, least-squares slope of centroid_y over the same window as rise_velocity: the bubble's own rise velocity
  std::optional<double> centroid_rise_velocity;
  std::optional<double> nose_gas_velocity;        ///< m/s, interstitial, half a cell above the nose
  std::optional<double> throughflow_ratio;        ///< U_th / U_mf
  std::optional<double> area;                     ///< m^2 (2D)
  std::optional<double> volume;                   ///< m^3 (3D)
  std::optional<double> equivalent_diameter;      ///< m: circle sqrt(4 A / pi) in 2D, sphere (6 V / pi)^(1/3) in 3D
  std::optional<double> theory_rise_velocity;     ///< m/s, C sqrt(g D) of rise_velocity.hpp for the dimension
  std::optional<double> centroid_x, centroid_y;   ///< m
  std::optional<double> centroid_z;               ///< m (3D)
  std::optional<double> nose_z;                   ///< m (3D), where the nose was sought
  std::optional<bool> attached;                   ///< touches the bottom cells above the jet
  std::optional<double> bed_height;               ///< m, top of the highest bed row; empty without a bed
  bool erupted = false;                           ///< the tracked bubble merged with the freeboard at this sample
  bool detached = false;                          ///< the tracked bubble left the jet at this sample
  int bubble_id = -1;                             ///< 0 for the first bubble tracked, 1 for the next...; -1 none
  int dimension = 2;                              ///< of the fields observed
};

/// Follows one bubble at a time: the jet bubble, then, once it detached, the same region as it rises, until it
/// erupts at the bed surface; then the next bubble. Call observe() once per sample, times increasing.
class BubbleTracker {
 public:
  explicit BubbleTracker(const BubbleConfig& config);

  /// One sample of the voidage eps and the vertical (axis 1) interstitial gas velocity vg at the cell centres,
  /// both over the same geometry; Dim is 2 or 3. Throws Error(BadInput) when the geometries differ or do not match
  /// the configured cell counts.
  template <int Dim>
  BubbleSample observe(double t, const CellView<Dim>& eps, const CellView<Dim>& vg);

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
    std::vector<double> centroid_h;  ///< centroid heights at the last nose_t.size() (or fewer) samples
  };
  State state() const {
    return {tracked_,  tracking_,        was_attached_,  bubble_count_, nose_t_,
            nose_h_,   detachment_time_, eruption_time_, centroid_h_};
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
    centroid_h_ = std::move(s.centroid_h);
  }

 private:
  /// The rise velocities of the tracked bubble (nose and centroid) with this sample's nose height.
  void update_rise(double t, double nose, BubbleSample& s);
  BubbleConfig config_;
  std::vector<std::uint8_t> tracked_;  // cells of the tracked bubble at the previous sample
  bool tracking_ = false;
  bool was_attached_ = false;
  int bubble_count_ = 0;
  std::vector<double> nose_t_, nose_h_;  // nose history of the tracked bubble, for the rise velocity
  std::vector<double> centroid_h_;       // centroid heights at the last samples of nose_t_ (fewer after a restore)
  std::optional<double> detachment_time_, eruption_time_;
};

/// Sub-cell height where a vertical eps profile sampled at cell centres y_lo < y_hi crosses the threshold
/// (linear interpolation; exact for a linear profile).
double threshold_crossing(double y_lo, double eps_lo, double y_hi, double eps_hi, double threshold);

/// Multilinear (bi- in 2D, tri- in 3D) interpolation of a cell-centred field at x, clamped to the outermost cell
/// centres.
template <int Dim>
double interpolate_cell_centred(const CellView<Dim>& f, const std::array<double, Dim>& x);

/// Connected regions of the cells where mask != 0, neighbours sharing a face (4 in 2D, 6 in 3D); mask and label
/// are axis 0 fastest over n cells per axis; label -1 outside the mask, labels 0..n-1 in order of the first cell met
/// in storage order. Returns the number of regions.
template <int Dim>
int label_regions(const Index<Dim>& n, const std::vector<std::uint8_t>& mask, std::vector<int>& label);

}  // namespace fluidbed
