#pragma once
// The CSV rows of the analysis outputs: bubble.csv (the tracked bubble), bubbles.csv, bubble_events.csv and
// bubble_frames.csv (the population) and tracers/NNNNNN.csv (the tracer balls). The analysis computes the records;
// the run writes them in these columns (docs/output-format.md, docs/analysis.md).
#include <optional>
#include <string>
#include <vector>

#include "analysis/bubble_population.hpp"
#include "analysis/bubble_tracker.hpp"
#include "analysis/layer_tracers.hpp"

namespace fluidbed {

/// bubble.csv header: the columns of docs/interface.md, then equivalent_diameter_m, bed_height_m, erupted,
/// bubble_id, nose_x_m. For dimension 3, bubble_area_m2 is bubble_volume_m3 and nose_z_m and
/// theory_rise_velocity_m_s follow. With centroid, centroid_y_m and centroid_rise_velocity_m_s are appended last
/// (every earlier column unchanged).
std::string bubble_csv_header(int dimension = 2, bool centroid = false);
/// One bubble.csv line (no newline); empty values where the sample has none; columns for s.dimension.
std::string bubble_csv_row(const BubbleSample& s, bool centroid = false);
/// The same row as numbers (empty optionals where there is no value), in bubble_csv_header(s.dimension, centroid)
/// order.
std::vector<std::optional<double>> bubble_csv_values(const BubbleSample& s, bool centroid = false);


/// bubbles.csv header: time_s,id,event,parents,area_m2 (3D: volume_m3),equivalent_diameter_m,centroid_x_m,
/// centroid_y_m,(centroid_z_m,)nose_m,tail_m,aspect_ratio,u_centroid_m_s,u_nose_m_s,slug.
std::string bubbles_csv_header(int dimension);
/// One bubbles.csv line (no newline); parents separated by ';'.
template <int Dim>
std::string bubbles_csv_row(const BubbleRecord<Dim>& b);
/// bubble_events.csv header: time_s,event,id,others,height_m.
std::string bubble_events_csv_header();
std::string bubble_events_csv_row(const BubbleEventRecord& e);
/// bubble_frames.csv header: time_s,bed_height_m,bed_measure,bubble_measure,bubbles,bubble_fraction,slugs.
std::string bubble_frames_csv_header();
std::string bubble_frames_csv_row(const BubbleFrame& f);


/// tracers/NNNNNN.csv content: header ball_id,x,y,layer (ball_id,x,y,z,layer in 3D) and one line per ball
/// (shortest round-trip numbers).
template <int Dim>
std::string tracer_csv(const BallTracers<Dim>& tracers);

}  // namespace fluidbed
