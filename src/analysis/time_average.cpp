#include "analysis/time_average.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace fluidbed {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Block indices of TimeAverage's sums (see its kSums).
template <int Dim>
struct Blocks {
  static constexpr int eps = 0;
  static constexpr int ug = 1;
  static constexpr int solids_count = 1 + Dim;
  static constexpr int us = 2 + Dim;
  static constexpr int eps_s = 2 + 2 * Dim;
  static constexpr int eps_s_us = 3 + 2 * Dim;
  static constexpr int theta_w = 3 + 3 * Dim;
  static constexpr int theta_sum = 4 + 3 * Dim;
};

std::vector<double> ratio(const std::vector<double>& num, const std::vector<double>& den) {
  std::vector<double> r(num.size());
  for (std::size_t c = 0; c < num.size(); ++c) r[c] = den[c] > 0.0 ? num[c] / den[c] : kNaN;
  return r;
}

}  // namespace

template <int Dim>
void particle_granular_temperature(const CellGeometry<Dim>& g, const AverageParticles<Dim>& p,
                                   std::vector<double>& theta, std::vector<double>& weight) {
  const std::size_t cells = g.cells();
  const std::size_t n = p.radius.size();
  theta.assign(cells, 0.0);
  weight.assign(cells, 0.0);
  std::vector<int> count(cells, 0);
  std::array<std::vector<double>, Dim> mean;
  for (auto& m : mean) m.assign(cells, 0.0);
  std::vector<std::size_t> cell_of(n);
  const auto slot = [&](std::size_t k) { return p.order.empty() ? k : p.order[k]; };
  // Two passes (mean, then the fluctuation about it) rather than <v^2> - <v>^2, which cancels digits where the
  // fluctuation is small against the mean.
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = slot(k);
    Index<Dim> c{};
    for (int a = 0; a < Dim; ++a) c[a] = g.cell(a, p.x[a][i]);
    const std::size_t cell = g.index(c);
    cell_of[i] = cell;
    const double w = 4.0 / 3.0 * std::numbers::pi * p.radius[i] * p.radius[i] * p.radius[i];
    weight[cell] += w;
    ++count[cell];
    for (int a = 0; a < Dim; ++a) mean[a][cell] += w * p.v[a][i];
  }
  for (std::size_t c = 0; c < cells; ++c)
    for (int a = 0; a < Dim; ++a) mean[a][c] = weight[c] > 0.0 ? mean[a][c] / weight[c] : 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = slot(k);
    const std::size_t cell = cell_of[i];
    const double w = 4.0 / 3.0 * std::numbers::pi * p.radius[i] * p.radius[i] * p.radius[i];
    double c2 = 0.0;
    for (int a = 0; a < Dim; ++a) {
      const double d = p.v[a][i] - mean[a][cell];
      c2 += d * d;
    }
    theta[cell] += w * c2;
  }
  for (std::size_t c = 0; c < cells; ++c) {
    // One particle has no fluctuation about itself: such a cell has no temperature to report.
    if (count[c] < 2) {
      theta[c] = 0.0;
      weight[c] = 0.0;
    } else {
      theta[c] /= Dim * weight[c];
    }
  }
}

template <int Dim>
TimeAverage<Dim>::TimeAverage(const CellGeometry<Dim>& geometry) : geometry_(geometry) {
  for (auto& s : sums_) s.assign(geometry_.cells(), 0.0);
}

template <int Dim>
void TimeAverage<Dim>::add(const AverageFields<Dim>& f, const AverageParticles<Dim>* particles) {
  using B = Blocks<Dim>;
  const std::size_t cells = geometry_.cells();
  bool solids = true;
  for (const double* c : f.us) solids = solids && c != nullptr;
  const bool tfm_theta = !particles && f.theta != nullptr;
  if (particles) particle_granular_temperature(geometry_, *particles, theta_, weight_);
  for (std::size_t c = 0; c < cells; ++c) {
    const double eps = f.eps[c];
    const double eps_s = 1.0 - eps;
    block(B::eps)[c] += eps;
    for (int a = 0; a < Dim; ++a) block(B::ug + a)[c] += f.ug[a][c];
    if (solids && eps_s > 0.0) {
      block(B::solids_count)[c] += 1.0;
      block(B::eps_s)[c] += eps_s;
      for (int a = 0; a < Dim; ++a) {
        block(B::us + a)[c] += f.us[a][c];
        block(B::eps_s_us + a)[c] += eps_s * f.us[a][c];
      }
    }
    if (particles) {
      block(B::theta_w)[c] += weight_[c];
      block(B::theta_sum)[c] += weight_[c] * theta_[c];
    } else if (tfm_theta && eps_s > 0.0) {
      block(B::theta_w)[c] += eps_s;
      block(B::theta_sum)[c] += eps_s * f.theta[c];
    }
  }
  ++samples_;
}

template <int Dim>
std::vector<double> TimeAverage<Dim>::voidage() const {
  std::vector<double> r(block(Blocks<Dim>::eps));
  for (double& v : r) v = samples_ > 0 ? v / static_cast<double>(samples_) : kNaN;
  return r;
}

template <int Dim>
std::array<std::vector<double>, Dim> TimeAverage<Dim>::gas_velocity() const {
  std::array<std::vector<double>, Dim> r;
  for (int a = 0; a < Dim; ++a) {
    r[a] = block(Blocks<Dim>::ug + a);
    for (double& v : r[a]) v = samples_ > 0 ? v / static_cast<double>(samples_) : kNaN;
  }
  return r;
}

template <int Dim>
std::array<std::vector<double>, Dim> TimeAverage<Dim>::solids_velocity_cell() const {
  std::array<std::vector<double>, Dim> r;
  for (int a = 0; a < Dim; ++a) r[a] = ratio(block(Blocks<Dim>::us + a), block(Blocks<Dim>::solids_count));
  return r;
}

template <int Dim>
std::array<std::vector<double>, Dim> TimeAverage<Dim>::solids_velocity_particle() const {
  std::array<std::vector<double>, Dim> r;
  for (int a = 0; a < Dim; ++a) r[a] = ratio(block(Blocks<Dim>::eps_s_us + a), block(Blocks<Dim>::eps_s));
  return r;
}

template <int Dim>
std::vector<double> TimeAverage<Dim>::granular_temperature() const {
  return ratio(block(Blocks<Dim>::theta_sum), block(Blocks<Dim>::theta_w));
}

template <int Dim>
std::vector<double> TimeAverage<Dim>::solids_presence() const {
  std::vector<double> r(block(Blocks<Dim>::solids_count));
  for (double& v : r) v = samples_ > 0 ? v / static_cast<double>(samples_) : kNaN;
  return r;
}

template <int Dim>
typename TimeAverage<Dim>::State TimeAverage<Dim>::state() const {
  State s;
  s.samples = samples_;
  s.sums.reserve(kSums * geometry_.cells());
  for (const auto& b : sums_) s.sums.insert(s.sums.end(), b.begin(), b.end());
  return s;
}

template <int Dim>
void TimeAverage<Dim>::restore(const State& s) {
  const std::size_t cells = geometry_.cells();
  if (s.sums.size() != kSums * cells || s.samples < 0) {
    throw std::invalid_argument("time-average state of another grid: " + std::to_string(s.sums.size()) +
                                " values, expected " + std::to_string(kSums * cells));
  }
  for (int b = 0; b < kSums; ++b) {
    const auto from = s.sums.begin() + static_cast<std::ptrdiff_t>(b * cells);
    block(b).assign(from, from + static_cast<std::ptrdiff_t>(cells));
  }
  samples_ = s.samples;
}

template void particle_granular_temperature<2>(const CellGeometry<2>&, const AverageParticles<2>&,
                                               std::vector<double>&, std::vector<double>&);
template void particle_granular_temperature<3>(const CellGeometry<3>&, const AverageParticles<3>&,
                                               std::vector<double>&, std::vector<double>&);
template class TimeAverage<2>;
template class TimeAverage<3>;

}  // namespace fluidbed
