#include "run/bubble_series.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include "run/analysis_csv.hpp"

namespace fluidbed {

namespace {

std::vector<std::string> split_header(const std::string& header) {
  std::vector<std::string> cols;
  for (std::size_t a = 0, b; a <= header.size(); a = b + 1) {
    b = header.find(',', a);
    if (b == std::string::npos) b = header.size();
    cols.push_back(header.substr(a, b - a));
  }
  return cols;
}

CsvWriter open_csv(const std::filesystem::path& path, const std::string& header, bool restart, double t_cut) {
  return restart ? CsvWriter::resume(path, split_header(header), t_cut) : CsvWriter(path, split_header(header));
}

std::vector<std::int32_t> to_int32(const std::vector<int>& v) { return {v.begin(), v.end()}; }

template <int Dim>
void save_state(Hdf5File& f, const typename BubblePopulation<Dim>::State& s) {
  f.create_group("bubbles");
  f.write("bubbles/owner", to_int32(s.owner));
  f.write("bubbles/ids", to_int32(s.ids));
  f.write("bubbles/cells", s.cells);
  f.write("bubbles/centroid_y", s.centroid_y);
  f.write("bubbles/history_count", to_int32(s.history_count));
  f.write("bubbles/history_t", s.history_t);
  f.write("bubbles/history_centroid", s.history_centroid);
  f.write("bubbles/history_nose", s.history_nose);
  f.set_attribute("bubbles", "next_id", static_cast<std::int64_t>(s.next_id));
}

template <int Dim>
typename BubblePopulation<Dim>::State load_state(const Hdf5File& f) {
  typename BubblePopulation<Dim>::State s;
  const auto ints = [&](const char* name) {
    const std::vector<std::int32_t> v = f.read_int32(name);
    return std::vector<int>(v.begin(), v.end());
  };
  s.owner = ints("bubbles/owner");
  s.ids = ints("bubbles/ids");
  s.cells = f.read_double("bubbles/cells");
  s.centroid_y = f.read_double("bubbles/centroid_y");
  s.history_count = ints("bubbles/history_count");
  s.history_t = f.read_double("bubbles/history_t");
  s.history_centroid = f.read_double("bubbles/history_centroid");
  s.history_nose = f.read_double("bubbles/history_nose");
  s.next_id = static_cast<int>(f.attribute_int64("bubbles", "next_id"));
  return s;
}

template <int Dim>
CellView<Dim> eps_view(const FieldView& fv) {
  return CellView<Dim>{fv.geometry<Dim>(), fv.eps};
}

template <int Dim>
void observe_into(BubblePopulation<Dim>& pop, double t, const FieldView& fv, CsvWriter& bubbles, CsvWriter& events,
                  CsvWriter& frames) {
  for (const BubbleRecord<Dim>& b : pop.observe(t, eps_view<Dim>(fv))) bubbles.line(bubbles_csv_row(b));
  for (const BubbleEventRecord& e : pop.sample_events()) events.line(bubble_events_csv_row(e));
  frames.line(bubble_frames_csv_row(pop.frames().back()));
}

}  // namespace

BubbleSeries::BubbleSeries(const std::filesystem::path& out, int dimension, const PopulationConfig& config,
                           bool restart, double t_cut, const Hdf5File* checkpoint)
    : dim_(dimension) {
  const bool restore = restart && checkpoint && checkpoint->has("bubbles/owner");
  if (dim_ == 3) {
    pop3_.emplace(config);
    if (restore) pop3_->restore(load_state<3>(*checkpoint));
  } else {
    pop2_.emplace(config);
    if (restore) pop2_->restore(load_state<2>(*checkpoint));
  }
  bubbles_.emplace(open_csv(out / kFiles[0], bubbles_csv_header(dim_), restart, t_cut));
  events_.emplace(open_csv(out / kFiles[1], bubble_events_csv_header(), restart, t_cut));
  frames_.emplace(open_csv(out / kFiles[2], bubble_frames_csv_header(), restart, t_cut));
}

void BubbleSeries::observe(double t, const FieldView& fv) {
  if (dim_ == 3) {
    observe_into(*pop3_, t, fv, *bubbles_, *events_, *frames_);
  } else {
    observe_into(*pop2_, t, fv, *bubbles_, *events_, *frames_);
  }
}

void BubbleSeries::save(Hdf5File& f) const {
  if (dim_ == 3) {
    save_state<3>(f, pop3_->state());
  } else {
    save_state<2>(f, pop2_->state());
  }
}

}  // namespace fluidbed
