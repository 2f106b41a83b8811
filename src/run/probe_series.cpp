#include "run/probe_series.hpp"

#include <string>

namespace fluidbed {

namespace {

template <int Dim>
ProbeFields<Dim> probe_fields(const FieldView& fv) {
  ProbeFields<Dim> f;
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

void ProbeSeries::sample(double t, const FieldView& fv) {
  const std::vector<double> v =
      dim_ == 3 ? sample_probes<3>(probes_, probe_fields<3>(fv)) : sample_probes<2>(probes_, probe_fields<2>(fv));
  std::vector<std::optional<double>> row{t};
  for (double x : v) row.push_back(x);
  csv_->row(row);
}

}  // namespace fluidbed
