#include "run/average_series.hpp"

#include <algorithm>
#include <iterator>
#include <cmath>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/vtk_writer.hpp"

namespace fluidbed {

namespace {

template <int Dim>
AverageFields<Dim> fields_of(const FieldView& fv) {
  AverageFields<Dim> f;
  f.geometry = fv.geometry<Dim>();
  f.eps = fv.eps;
  for (int a = 0; a < Dim; ++a) {
    f.ug[a] = fv.ug[static_cast<std::size_t>(a)];
    f.us[a] = fv.us[static_cast<std::size_t>(a)];
  }
  f.theta = fv.theta;
  return f;
}

constexpr const char* kAxis[3] = {"x", "y", "z"};

}  // namespace

AverageSeries::AverageSeries(std::filesystem::path out, const AveragesConfig& config, const FieldView& fv,
                             const Hdf5File* checkpoint, double t_now)
    : out_(std::move(out)), config_(config), dim_(fv.dimension) {
  if (dim_ == 3) {
    avg3_.emplace(fv.geometry<3>());
  } else {
    avg2_.emplace(fv.geometry<2>());
  }
  if (checkpoint && config_.interval > 0.0 && t_now >= config_.t_start) {
    // On the window's schedule, after the instant the checkpoint holds: 1e-9 of an interval absorbs the rounding
    // of t_now - t_start.
    next_ = static_cast<std::int64_t>(std::floor((t_now - config_.t_start) / config_.interval + 1e-9)) + 1;
  }
  if (!checkpoint || !checkpoint->has("averages/sums")) return;
  const Hdf5File& f = *checkpoint;
  // Another window is another average: its sums do not belong to this one.
  if (f.attribute_double("averages", "t_start") != config_.t_start ||
      f.attribute_double("averages", "t_end") != config_.t_end ||
      f.attribute_double("averages", "interval") != config_.interval) {
    return;
  }
  const std::int64_t n = f.attribute_int64("averages", "samples");
  const std::vector<double> sums = f.read_double("averages/sums");
  if (dim_ == 3) {
    avg3_->restore({n, sums});
  } else {
    avg2_->restore({n, sums});
  }
  next_ = f.attribute_int64("averages", "next");
  first_t_ = f.attribute_double("averages", "first_t");
  last_t_ = f.attribute_double("averages", "last_t");
  closed_ = f.attribute_int64("averages", "closed") != 0;
  restored_ = true;
}

std::int64_t AverageSeries::samples() const { return dim_ == 3 ? avg3_->samples() : avg2_->samples(); }

bool AverageSeries::due(double t, double dt) const {
  const double slack = std::max(0.5 * dt, 1e-9 * std::max(config_.interval, config_.t_end - config_.t_start));
  if (config_.interval == 0.0) return t >= config_.t_start - slack && t <= config_.t_end + slack;
  return t >= due_time() - slack && due_time() <= config_.t_end + slack;
}

void AverageSeries::observe(double t, double dt, const FieldView& fv, const std::optional<ParticleArrays>& particles) {
  if (closed_) return;
  const double slack = std::max(0.5 * dt, 1e-9 * std::max(config_.interval, config_.t_end - config_.t_start));
  if (due(t, dt)) {
    add(t, fv, particles);
    // One sample per due time, however many of them a long step passed.
    while (config_.interval > 0.0 && due_time() <= t + slack) ++next_;
  }
  if (t >= config_.t_end - slack) {
    closed_ = true;  // before write(): the files say the window is complete
    if (samples() > 0) write();
  }
}

void AverageSeries::add(double t, const FieldView& fv, const std::optional<ParticleArrays>& particles) {
  if (samples() == 0) first_t_ = t;
  last_t_ = t;
  const auto sample = [&]<int Dim>(TimeAverage<Dim>& avg) {
    if (!particles || particles->size() == 0) {
      avg.add(fields_of<Dim>(fv));
      return;
    }
    // Ascending id: the sums do not depend on how the store happens to be sorted.
    const std::vector<std::size_t> order = particles->order_by_id();
    AverageParticles<Dim> p;
    for (int a = 0; a < Dim; ++a) {
      p.x[a] = particles->x[static_cast<std::size_t>(a)];
      p.v[a] = particles->v[static_cast<std::size_t>(a)];
    }
    p.radius = particles->radius;
    p.order = order;
    avg.add(fields_of<Dim>(fv), &p);
  };
  if (dim_ == 3) {
    sample(*avg3_);
  } else {
    sample(*avg2_);
  }
}

void AverageSeries::finish() {
  if (!closed_ && samples() > 0) write();
}

void AverageSeries::save(Hdf5File& f) const {
  std::vector<double> sums;
  std::int64_t samples = 0;
  if (dim_ == 3) {
    auto st = avg3_->state();
    sums = std::move(st.sums);
    samples = st.samples;
  } else {
    auto st = avg2_->state();
    sums = std::move(st.sums);
    samples = st.samples;
  }
  f.create_group("averages");
  f.write("averages/sums", sums);
  f.set_attribute("averages", "samples", samples);
  f.set_attribute("averages", "next", next_);
  f.set_attribute("averages", "first_t", first_t_);
  f.set_attribute("averages", "last_t", last_t_);
  f.set_attribute("averages", "closed", static_cast<std::int64_t>(closed_ ? 1 : 0));
  f.set_attribute("averages", "t_start", config_.t_start);
  f.set_attribute("averages", "t_end", config_.t_end);
  f.set_attribute("averages", "interval", config_.interval);
}

void AverageSeries::write() const {
  if (dim_ == 3) {
    write_dim(*avg3_);
  } else {
    write_dim(*avg2_);
  }
  const bool complete = closed_;
  write_file_atomic(out_ / "averages.json",
                    fmt::format("{{\"t_start\": {}, \"t_end\": {}, \"interval\": {}, \"samples\": {}, "
                                "\"first_sample_s\": {}, \"last_sample_s\": {}, \"window_complete\": {}, "
                                "\"solids_velocity_particle_weight\": \"solids volume fraction (mass for one "
                                "solids density)\", \"granular_temperature_weight\": \"solids volume\"}}\n",
                                config_.t_start, config_.t_end, config_.interval, samples(), first_t_, last_t_,
                                complete ? "true" : "false"));
}

template <int Dim>
void AverageSeries::write_dim(const TimeAverage<Dim>& avg) const {
  const CellGeometry<Dim>& g = avg.geometry();
  const std::vector<double> eps = avg.voidage();
  const auto ug = avg.gas_velocity();
  const auto usc = avg.solids_velocity_cell();
  const auto usp = avg.solids_velocity_particle();
  const std::vector<double> theta = avg.granular_temperature();
  const std::vector<double> presence = avg.solids_presence();

  VtiGrid grid;
  grid.dimension = Dim;
  for (int a = 0; a < Dim; ++a) {
    grid.n[static_cast<std::size_t>(a)] = g.n[a];
    grid.h[static_cast<std::size_t>(a)] = g.h[a];
    grid.origin[static_cast<std::size_t>(a)] = g.origin[a];
  }
  const auto vec = [](const std::array<std::vector<double>, Dim>& v) {
    std::array<const double*, 3> c{};
    for (int a = 0; a < Dim; ++a) c[static_cast<std::size_t>(a)] = v[a].data();
    return c;
  };
  write_vti(out_ / "averages.vti", grid, last_t_,
            {{"voidage", {eps.data(), nullptr, nullptr}, 1},
             {"gas_velocity", vec(ug), Dim},
             {"solids_velocity_cell", vec(usc), Dim},
             {"solids_velocity_particle", vec(usp), Dim},
             {"granular_temperature", {theta.data(), nullptr, nullptr}, 1},
             {"solids_presence", {presence.data(), nullptr, nullptr}, 1}});

  write_file_atomic(out_ / "averages.csv", [&](std::ostream& os) {
    std::string header;
    for (int a = 0; a < Dim; ++a) header += fmt::format("{}{}", a ? "," : "", "ijk"[a]);
    for (int a = 0; a < Dim; ++a) header += fmt::format(",{}_m", kAxis[a]);
    header += ",voidage";
    for (int a = 0; a < Dim; ++a) header += fmt::format(",ug_{}_m_s", kAxis[a]);
    for (int a = 0; a < Dim; ++a) header += fmt::format(",us_cell_{}_m_s", kAxis[a]);
    for (int a = 0; a < Dim; ++a) header += fmt::format(",us_particle_{}_m_s", kAxis[a]);
    header += ",granular_temperature_m2_s2,solids_presence\n";
    os << header;
    std::string line;
    // A comma, then the shortest text that reads back to the same double; nothing for an undefined average.
    const auto put = [&line](double v) {
      line.push_back(',');
      if (!std::isnan(v)) fmt::format_to(std::back_inserter(line), "{}", v);
    };
    for (std::size_t k = 0; k < g.cells(); ++k) {
      const Index<Dim> c = g.cell_of(k);
      line.clear();
      for (int a = 0; a < Dim; ++a) fmt::format_to(std::back_inserter(line), "{}{}", a ? "," : "", c[a]);
      for (int a = 0; a < Dim; ++a) put(g.centre(a, c[a]));
      put(eps[k]);
      for (int a = 0; a < Dim; ++a) put(ug[a][k]);
      for (int a = 0; a < Dim; ++a) put(usc[a][k]);
      for (int a = 0; a < Dim; ++a) put(usp[a][k]);
      put(theta[k]);
      put(presence[k]);
      line.push_back('\n');
      os << line;
    }
  });
}

template void AverageSeries::write_dim<2>(const TimeAverage<2>&) const;
template void AverageSeries::write_dim<3>(const TimeAverage<3>&) const;

}  // namespace fluidbed
