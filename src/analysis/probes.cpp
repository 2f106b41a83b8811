#include "analysis/probes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "analysis/bubble_tracker.hpp"

namespace fluidbed {

template <int Dim>
double plane_mean(const CellView<Dim>& f, double y) {
  const CellGeometry<Dim>& g = f.geometry;
  // Linear in height between the two cell centres around y, as a tap between two cell centres reads.
  const double s = std::clamp((y - g.origin[1]) / g.h[1] - 0.5, 0.0, static_cast<double>(g.n[1] - 1));
  const int j0 = std::min(static_cast<int>(s), g.n[1] - 1);
  const int j1 = std::min(j0 + 1, g.n[1] - 1);
  const double w = s - j0;
  const int nz = Dim == 3 ? g.n[Dim - 1] : 1;
  double sum = 0.0;
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i < g.n[0]; ++i) {
      Index<Dim> lo{}, hi{};
      lo[0] = hi[0] = i;
      lo[1] = j0;
      hi[1] = j1;
      if constexpr (Dim == 3) lo[2] = hi[2] = k;
      sum += (1.0 - w) * f[lo] + w * f[hi];
    }
  }
  return sum / (static_cast<double>(g.n[0]) * nz);
}

template <int Dim>
double bed_height(const CellView<Dim>& eps, double solids_fraction) {
  const CellGeometry<Dim>& g = eps.geometry;
  const int nz = Dim == 3 ? g.n[Dim - 1] : 1;
  const auto row_solids = [&](int j) {
    double sum = 0.0;
    for (int k = 0; k < nz; ++k)
      for (int i = 0; i < g.n[0]; ++i) {
        Index<Dim> c{};
        c[0] = i;
        c[1] = j;
        if constexpr (Dim == 3) c[2] = k;
        sum += eps[c];
      }
    return 1.0 - sum / (static_cast<double>(g.n[0]) * nz);
  };
  // From the top down, so voids inside the bed (bubbles) below the surface do not count.
  double above = 0.0;
  for (int j = g.n[1] - 1; j >= 0; --j) {
    const double s = row_solids(j);
    if (s >= solids_fraction) {
      if (j == g.n[1] - 1) return g.face(1, g.n[1]);
      return g.centre(1, j) + g.h[1] * (s - solids_fraction) / (s - above);
    }
    above = s;
  }
  return 0.0;
}

double percentile(std::span<const double> values, double p) {
  if (values.empty()) return 0.0;
  std::vector<double> v(values.begin(), values.end());
  const double rank = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(rank);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(lo), v.end());
  const double a = v[lo];
  if (lo + 1 == v.size()) return a;
  const double b = *std::min_element(v.begin() + static_cast<std::ptrdiff_t>(lo) + 1, v.end());
  return a + (rank - static_cast<double>(lo)) * (b - a);
}

std::vector<std::string> probe_columns(const std::vector<ProbeSpec>& probes, int dimension, bool solids) {
  static constexpr const char* axis[3] = {"x", "y", "z"};
  std::vector<std::string> cols;
  for (const ProbeSpec& p : probes) {
    if (p.kind == ProbeKind::PressureDrop) {
      cols.push_back(p.name + "_dp_Pa");
      continue;
    }
    if (p.kind == ProbeKind::BedHeight) {
      cols.push_back(p.name + "_bed_height_m");
      continue;
    }
    if (p.kind == ProbeKind::ParticleTop) {
      cols.push_back(p.name + "_top_m");
      continue;
    }
    cols.push_back(p.name + "_p_Pa");
    cols.push_back(p.name + "_eps");
    for (int a = 0; a < dimension; ++a) cols.push_back(p.name + "_ug_" + axis[a] + "_m_s");
    if (solids)
      for (int a = 0; a < dimension; ++a) cols.push_back(p.name + "_us_" + axis[a] + "_m_s");
  }
  return cols;
}

template <int Dim>
std::vector<double> sample_probes(const std::vector<ProbeSpec>& probes, const ProbeFields<Dim>& fields) {
  const bool solids = fields.has_solids_velocity();
  const auto view = [&](const double* v) { return CellView<Dim>{fields.geometry, v}; };
  std::vector<double> row;
  for (const ProbeSpec& p : probes) {
    if (p.kind == ProbeKind::PressureDrop) {
      row.push_back(plane_mean<Dim>(view(fields.p), p.height) - plane_mean<Dim>(view(fields.p), p.height_top));
      continue;
    }
    if (p.kind == ProbeKind::BedHeight) {
      row.push_back(bed_height<Dim>(view(fields.eps), p.solids_fraction));
      continue;
    }
    if (p.kind == ProbeKind::ParticleTop) {
      row.push_back(percentile(fields.particle_tops, p.percentile));
      continue;
    }
    std::array<double, Dim> x{};
    for (int a = 0; a < Dim; ++a) x[a] = p.position[a];
    const auto read = [&](const double* v) {
      return p.kind == ProbeKind::Point ? interpolate_cell_centred<Dim>(view(v), x) : plane_mean<Dim>(view(v), p.height);
    };
    row.push_back(read(fields.p));
    row.push_back(read(fields.eps));
    for (int a = 0; a < Dim; ++a) row.push_back(read(fields.ug[a]));
    if (solids)
      for (int a = 0; a < Dim; ++a) row.push_back(read(fields.us[a]));
  }
  return row;
}

template double plane_mean<2>(const CellView<2>&, double);
template double plane_mean<3>(const CellView<3>&, double);
template double bed_height<2>(const CellView<2>&, double);
template double bed_height<3>(const CellView<3>&, double);
template std::vector<double> sample_probes<2>(const std::vector<ProbeSpec>&, const ProbeFields<2>&);
template std::vector<double> sample_probes<3>(const std::vector<ProbeSpec>&, const ProbeFields<3>&);

}  // namespace fluidbed
