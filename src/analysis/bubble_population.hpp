#pragma once
// Every bubble of a bed, followed from sample to sample (issue 15, item 1): connected regions above the voidage
// threshold, less the freeboard and the distributor zone, associated between consecutive samples by the cells they
// share. Gives persistent ids, the events birth, split, coalescence, eruption and disappearance, and per bubble and
// sample its size, equivalent diameter, centroid, nose, tail, aspect ratio and rise velocities; a void that spans
// the cross-section (a slug, a plug lifted off the distributor) is followed too but flagged, and not counted as a
// bubble. docs/analysis.md ("Bubble population") gives the definitions and the columns of bubbles.csv,
// bubble_events.csv, bubble_frames.csv.
#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/cell_view.hpp"

namespace fluidbed {

/// Settings of BubblePopulation.
struct PopulationConfig {
  double eps_threshold = 0.8;       ///< a cell belongs to a bubble when eps > this (Gera et al. 1998, Section 3)
  double surface_eps = 0.7;         ///< bed surface as in bed_surface_row(); regions with a cell above it are freeboard
  double distributor_height = 0.0;  ///< m above the bottom face: regions with a cell centre below are not bubbles
  double min_size = 0.0;            ///< m^2 in 2D, m^3 in 3D: smaller regions are not bubbles
  int velocity_samples = 2;         ///< least-squares slope over this many samples of one id (2: backward difference)
};

/// What happened to a bubble at a sample.
enum class BubbleEvent { None, Birth, Split, Coalescence, Eruption, Disappearance };
/// "", "birth", "split", "coalescence", "eruption", "disappearance".
const char* bubble_event_name(BubbleEvent e);

/// One bubble at one sample.
template <int Dim>
struct BubbleRecord {
  double time = 0.0;  ///< s
  int id = -1;        ///< persistent id, from 0 in order of birth
  /// Birth, Split (a child of a split) or Coalescence at this sample, else None
  BubbleEvent event = BubbleEvent::None;
  std::vector<int> parents;  ///< ids it came from at this sample (split: the parent; coalescence: all merged)
  std::size_t cells = 0;
  /// The void spans the cross-section (a cell in every column along x, and along z in 3D): a slug or a plug lifted
  /// off the distributor. Followed like a bubble, but not counted as one (BubbleFrame).
  bool slug = false;
  double size = 0.0;                   ///< m^2 (2D) or m^3 (3D): cells times the cell measure
  double equivalent_diameter = 0.0;    ///< m: circle sqrt(4 A / pi) in 2D, sphere (6 V / pi)^(1/3) in 3D
  std::array<double, Dim> centroid{};  ///< m, mean of the cell centres
  double nose = 0.0;                   ///< m, highest point of the eps = threshold contour (sub-cell, see docs)
  double tail = 0.0;                   ///< m, lowest point of it
  double width = 0.0;                  ///< m, horizontal extent (3D: mean of the x and z extents)
  double aspect_ratio = 0.0;           ///< (nose - tail) / width
  std::optional<double> u_centroid;    ///< m/s, rise velocity of centroid[1]; empty at the first sample of an id
  std::optional<double> u_nose;        ///< m/s, rise velocity of the nose
};

/// One event; for Split `others` are the children, for Coalescence the ids merged into `id` (which survives).
struct BubbleEventRecord {
  double time = 0.0;  ///< s, the sample at which it was seen
  BubbleEvent event = BubbleEvent::None;
  int id = -1;              ///< the bubble born, split (the parent), surviving a coalescence, erupted or gone
  std::vector<int> others;  ///< split: children; coalescence: the other parents; birth: parents of a split child
  double height = 0.0;      ///< m, centroid height of `id` (for eruption and disappearance: at its last sample)
};

/// Per sample: the bed and the bubbles in it, for the bubble fraction and the window of the statistics.
struct BubbleFrame {
  double time = 0.0;                 ///< s
  std::optional<double> bed_height;  ///< m, bed_surface_height(); empty without a bed
  double bed_measure = 0.0;          ///< m^2 / m^3 between distributor_height and the bed surface, whole width
  double bubble_measure = 0.0;       ///< m^2 / m^3, sum of the bubbles' sizes (slugs not included)
  int bubbles = 0;                   ///< number of bubbles, slugs not included
  int slugs = 0;                     ///< number of voids that span the cross-section (BubbleRecord::slug)
  /// bubble_measure / bed_measure, the fraction of the bed occupied by bubbles; 0 without a bed.
  double bubble_fraction() const { return bed_measure > 0.0 ? bubble_measure / bed_measure : 0.0; }
};

/// Follows every bubble. Call observe() once per sample, times increasing; the sample interval must be short
/// enough that a bubble overlaps itself between samples (it rises less than its own height).
template <int Dim>
class BubblePopulation {
 public:
  explicit BubblePopulation(const PopulationConfig& config);

  /// One sample of the voidage; returns the bubbles of this sample. Events are appended to events().
  const std::vector<BubbleRecord<Dim>>& observe(double t, const CellView<Dim>& eps);

  const std::vector<BubbleRecord<Dim>>& current() const { return current_; }
  /// The events seen at the latest sample (the lines to append to bubble_events.csv).
  std::vector<BubbleEventRecord> sample_events() const {
    return {events_.begin() + static_cast<std::ptrdiff_t>(sample_events_begin_), events_.end()};
  }
  /// Every event so far, in order of time.
  const std::vector<BubbleEventRecord>& events() const { return events_; }
  /// Every sample so far; frames().back() is the latest.
  const std::vector<BubbleFrame>& frames() const { return frames_; }
  const PopulationConfig& config() const { return config_; }

  /// What the next observe() depends on, as flat arrays for a checkpoint: a restored population continues with the
  /// same ids, events and velocities (events() and frames() before the restore are not kept).
  struct State {
    std::vector<int> owner;          ///< per cell, the id of its bubble at the last sample, -1 none
    std::vector<int> ids;            ///< the bubbles of the last sample
    std::vector<double> cells;       ///< their cell counts
    std::vector<double> centroid_y;  ///< their centroid heights, m
    std::vector<int> history_count;  ///< per bubble, how many velocity samples it holds (<= velocity_samples)
    std::vector<double> history_t, history_centroid, history_nose;  ///< those samples, bubble after bubble
    int next_id = 0;
  };
  State state() const;
  void restore(const State& s);

 private:
  struct History {
    std::vector<double> t, centroid, nose;
  };
  /// The events of the previous sample's bubbles that left no single heir (split, eruption, disappearance).
  void close_previous(double t, const std::map<int, std::vector<int>>& children,
                      const std::map<int, std::size_t>& free_overlap, const std::vector<int>& id_of_region);
  /// Rise velocities over the samples of the same id since its birth, split or last coalescence.
  void update_velocities(double t, std::vector<BubbleRecord<Dim>>& now);
  std::size_t sample_events_begin_ = 0;
  PopulationConfig config_;
  std::vector<int> owner_;  // id of the bubble of each cell at the previous sample, -1 none
  std::vector<BubbleRecord<Dim>> current_;
  std::map<int, History> history_;
  std::vector<BubbleEventRecord> events_;
  std::vector<BubbleFrame> frames_;
  int next_id_ = 0;
};

}  // namespace fluidbed
