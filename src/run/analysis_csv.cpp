#include "run/analysis_csv.hpp"

#include <cstddef>

#include <fmt/format.h>

namespace fluidbed {

namespace {

// An optional value, empty where there is none.
std::string opt(const std::optional<double>& v) { return v ? fmt::format("{}", *v) : std::string(); }

// Bubble ids separated by ';'.
std::string join_ids(const std::vector<int>& ids) {
  std::string s;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (k) s += ';';
    s += fmt::format("{}", ids[k]);
  }
  return s;
}

}  // namespace

std::string bubble_csv_header(int dimension, bool centroid) {
  const std::string tail = centroid ? ",centroid_y_m,centroid_rise_velocity_m_s" : "";
  if (dimension == 3)
    return "time_s,nose_height_m,rise_velocity_m_s,nose_gas_velocity_m_s,throughflow_ratio,bubble_volume_m3,attached,"
           "equivalent_diameter_m,bed_height_m,erupted,bubble_id,nose_x_m,nose_z_m,theory_rise_velocity_m_s" +
           tail;
  return "time_s,nose_height_m,rise_velocity_m_s,nose_gas_velocity_m_s,throughflow_ratio,bubble_area_m2,attached,"
         "equivalent_diameter_m,bed_height_m,erupted,bubble_id,nose_x_m" +
         tail;
}

namespace {

std::vector<std::optional<double>> bubble_csv_values_base(const BubbleSample& s) {
  std::optional<double> attached;
  if (s.attached) attached = *s.attached ? 1.0 : 0.0;
  std::optional<double> id;
  if (s.bubble_id >= 0) id = static_cast<double>(s.bubble_id);
  if (s.dimension == 3)
    return {s.time, s.nose_height, s.rise_velocity, s.nose_gas_velocity, s.throughflow_ratio, s.volume, attached,
            s.equivalent_diameter, s.bed_height, s.erupted ? 1.0 : 0.0, id, s.nose_x, s.nose_z,
            s.theory_rise_velocity};
  return {s.time, s.nose_height, s.rise_velocity, s.nose_gas_velocity, s.throughflow_ratio, s.area, attached,
          s.equivalent_diameter, s.bed_height, s.erupted ? 1.0 : 0.0, id, s.nose_x};
}

}  // namespace

std::vector<std::optional<double>> bubble_csv_values(const BubbleSample& s, bool centroid) {
  std::vector<std::optional<double>> v = bubble_csv_values_base(s);
  if (centroid) {
    v.push_back(s.centroid_y);
    v.push_back(s.centroid_rise_velocity);
  }
  return v;
}

std::string bubble_csv_row(const BubbleSample& s, bool centroid) {
  const std::string attached = s.attached ? (*s.attached ? "1" : "0") : "";
  const std::string id = s.bubble_id >= 0 ? fmt::format("{}", s.bubble_id) : std::string();
  std::string row = fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}", s.time, opt(s.nose_height), opt(s.rise_velocity),
                                opt(s.nose_gas_velocity), opt(s.throughflow_ratio),
                                opt(s.dimension == 3 ? s.volume : s.area), attached, opt(s.equivalent_diameter),
                                opt(s.bed_height), s.erupted ? 1 : 0, id, opt(s.nose_x));
  if (s.dimension == 3) row += fmt::format(",{},{}", opt(s.nose_z), opt(s.theory_rise_velocity));
  if (centroid) row += fmt::format(",{},{}", opt(s.centroid_y), opt(s.centroid_rise_velocity));
  return row;
}


std::string bubbles_csv_header(int dimension) {
  if (dimension == 3)
    return "time_s,id,event,parents,volume_m3,equivalent_diameter_m,centroid_x_m,centroid_y_m,centroid_z_m,nose_m,"
           "tail_m,aspect_ratio,u_centroid_m_s,u_nose_m_s,slug";
  return "time_s,id,event,parents,area_m2,equivalent_diameter_m,centroid_x_m,centroid_y_m,nose_m,tail_m,"
         "aspect_ratio,u_centroid_m_s,u_nose_m_s,slug";
}

template <int Dim>
std::string bubbles_csv_row(const BubbleRecord<Dim>& b) {
  std::string row = fmt::format("{},{},{},{},{},{}", b.time, b.id, bubble_event_name(b.event), join_ids(b.parents),
                                b.size, b.equivalent_diameter);
  for (int a = 0; a < Dim; ++a) row += fmt::format(",{}", b.centroid[a]);
  row += fmt::format(",{},{},{},{},{},{}", b.nose, b.tail, b.aspect_ratio, opt(b.u_centroid), opt(b.u_nose),
                     b.slug ? 1 : 0);
  return row;
}

std::string bubble_events_csv_header() { return "time_s,event,id,others,height_m"; }

std::string bubble_events_csv_row(const BubbleEventRecord& e) {
  return fmt::format("{},{},{},{},{}", e.time, bubble_event_name(e.event), e.id, join_ids(e.others), e.height);
}

std::string bubble_frames_csv_header() {
  return "time_s,bed_height_m,bed_measure,bubble_measure,bubbles,bubble_fraction,slugs";
}

std::string bubble_frames_csv_row(const BubbleFrame& f) {
  return fmt::format("{},{},{},{},{},{},{}", f.time, opt(f.bed_height), f.bed_measure, f.bubble_measure, f.bubbles,
                     f.bubble_fraction(), f.slugs);
}

template <int Dim>
std::string tracer_csv(const BallTracers<Dim>& tracers) {
  std::string out = Dim == 2 ? "ball_id,x,y,layer\n" : "ball_id,x,y,z,layer\n";
  for (std::size_t k = 0; k < tracers.size(); ++k) {
    if constexpr (Dim == 2) {
      out += fmt::format("{},{},{},{}\n", tracers.id[k], tracers.x[k], tracers.y[k], tracers.layer[k]);
    } else {
      out += fmt::format("{},{},{},{},{}\n", tracers.id[k], tracers.x[k], tracers.y[k], tracers.z[k], tracers.layer[k]);
    }
  }
  return out;
}

template std::string bubbles_csv_row(const BubbleRecord<2>&);
template std::string bubbles_csv_row(const BubbleRecord<3>&);
template std::string tracer_csv(const BallTracers<2>&);
template std::string tracer_csv(const BallTracers<3>&);

}  // namespace fluidbed
