#include "run/probe_series.hpp"

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace fluidbed {

namespace {

template <int Dim>
ProbeFields<Dim> probe_fields(const FieldView& fv, std::span<const double> tops) {
  ProbeFields<Dim> f;
  f.particle_tops = tops;
  for (int a = 0; a < Dim; ++a) {
    f.geometry.n[a] = fv.n[a];
    f.geometry.h[a] = fv.h[a];
    f.geometry.origin[a] = fv.origin[a];
    f.ug[a] = fv.ug[a];
    f.us[a] = fv.us[a];
  }
  f.p = fv.p;
  f.eps = fv.eps;
  return f;
}

}  // namespace

ProbeSeries::ProbeSeries(const std::filesystem::path& path, const std::vector<ProbeSpec>& probes, int dimension,
                         bool solids, bool restart, double t_cut)
    : probes_(probes), dim_(dimension) {
  std::vector<std::string> cols{"time_s"};
  for (std::string& c : probe_columns(probes_, dim_, solids)) cols.push_back(std::move(c));
  csv_.emplace(restart ? CsvWriter::resume(path, cols, t_cut) : CsvWriter(path, cols));
}

bool ProbeSeries::reads_particles() const {
  for (const ProbeSpec& p : probes_)
    if (p.kind == ProbeKind::ParticleTop) return true;
  return false;
}

void ProbeSeries::sample(double t, const FieldView& fv, const ParticleArrays* particles) {
  if (particles) {
    tops_.resize(particles->size());
    const std::span<const double> y = particles->x[1];
    for (std::size_t i = 0; i < tops_.size(); ++i) tops_[i] = y[i] + particles->radius[i];
  } else {
    tops_.clear();
  }
  const std::vector<double> v = dim_ == 3 ? sample_probes<3>(probes_, probe_fields<3>(fv, tops_))
                                          : sample_probes<2>(probes_, probe_fields<2>(fv, tops_));
  std::vector<std::optional<double>> row{t};
  for (double x : v) row.push_back(x);
  csv_->row(row);
}

}  // namespace fluidbed
