#pragma once
// Closed-form solutions shared by the DEM verification tests, and small helpers to set up one-particle runs.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <omp.h>

#include "dem/contact_law.hpp"
#include "dem/dem_config.hpp"
#include "dem/packing.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed::test {

/// Linear spring-dashpot contact as a damped oscillator: m d'' + eta d' + k d = m a, with d the overlap, a a
/// constant acceleration pushing into the contact (g for a sphere on a floor, 0 without gravity), and
/// d(0) = d0, d'(0) = v0 (the closed-form solution of the paper's Eqs. 2 and 8, underdamped since e > 0).
struct DampedOscillator {
  double m, k, eta, a = 0.0, d0 = 0.0, v0 = 0.0;

  double gamma() const { return eta / (2.0 * m); }
  double omega_d() const { return std::sqrt(k / m - gamma() * gamma()); }
  double d_static() const { return m * a / k; }
  double amp_cos() const { return d0 - d_static(); }
  double amp_sin() const { return (v0 + gamma() * amp_cos()) / omega_d(); }

  double overlap(double t) const {
    const double wd = omega_d();
    return d_static() + std::exp(-gamma() * t) * (amp_cos() * std::cos(wd * t) + amp_sin() * std::sin(wd * t));
  }
  double rate(double t) const {
    const double g = gamma(), wd = omega_d(), A = amp_cos(), B = amp_sin();
    return std::exp(-g * t) * ((-g * A + wd * B) * std::cos(wd * t) + (-g * B - wd * A) * std::sin(wd * t));
  }
  /// Repulsive normal force k d + eta d' (negative in the dashpot's attractive tail).
  double force(double t) const { return k * overlap(t) + eta * rate(t); }
};

/// First root after t_lo of a function that is positive just after t_lo, found by scanning (step h) and
/// bisecting to round-off.
inline double first_root(const std::function<double(double)>& f, double t_lo, double t_hi, double h) {
  double a = t_lo + 1e-3 * h;
  double fa = f(a);
  for (double b = a + h; b <= t_hi + h; b += h) {
    const double fb = f(b);
    if ((fa > 0.0) != (fb > 0.0)) {
      double lo = a, hi = b;
      for (int it = 0; it < 200 && hi - lo > 1e-16 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        if ((f(mid) > 0.0) == (fa > 0.0)) lo = mid; else hi = mid;
      }
      return 0.5 * (lo + hi);
    }
    a = b;
    fa = fb;
  }
  return std::nan("");
}

/// Composite Simpson rule with n (even) intervals; used on smooth pieces only, so its error (h^4) is far
/// below the tolerances of the tests.
inline double simpson(const std::function<double(double)>& f, double a, double b, int n = 4000) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * ((i % 2) ? 4.0 : 2.0);
  return s * h / 3.0;
}

/// Contact end (overlap back to zero) of an impact starting at zero overlap.
inline double contact_end_time(const DampedOscillator& o) {
  const double period = 2.0 * std::numbers::pi / o.omega_d();
  return first_root([&](double t) { return o.overlap(t); }, 0.0, 2.0 * period, period / 4000.0);
}

/// Integral of |normal force| over the contact (the Coulomb bound of the tangential impulse is mu times it).
inline double abs_normal_impulse(const DampedOscillator& o) {
  const double t_end = contact_end_time(o);
  const double period = 2.0 * std::numbers::pi / o.omega_d();
  const double t_f = first_root([&](double t) { return o.force(t); }, 0.0, t_end, period / 4000.0);
  auto f = [&](double t) { return o.force(t); };
  if (!(t_f < t_end)) return simpson(f, 0.0, t_end);
  return simpson(f, 0.0, t_f) - simpson(f, t_f, t_end);
}

/// One species, walls and gravity as given, friction and restitution the same for pairs and walls.
inline DemConfig one_species_config(double d, double rho, double k, double e, double mu, double dt, Vec2 g,
                                    double width, double height, WallConfig walls) {
  DemConfig c;
  c.species = {Species{d, rho}};
  c.stiffness = k;
  c.tangential_stiffness_ratio = 1.0;
  c.pair = {InteractionParams{e, mu}};
  c.wall = {InteractionParams{e, mu}};
  c.domain.width = width;
  c.domain.height = height;
  c.walls = walls;
  c.domain.gravity = {g.x, g.y, 0.0};
  c.dt = dt;
  return c;
}

/// The 3D box [0, box.x] x [0, box.y] x [0, box.z] with one species, as one_species_config.
inline DemConfig one_species_config_3d(double d, double rho, double k, double e, double mu, double dt, Vec3 g,
                                       Vec3 box, WallConfig walls) {
  DemConfig c = one_species_config(d, rho, k, e, mu, dt, {g.x, g.y}, box.x, box.y, walls);
  c.domain.dimension = 3;
  c.domain.depth = box.z;
  c.domain.gravity = g;
  return c;
}

/// All six walls of a 3D box.
inline WallConfig closed_box() { return WallConfig{true, true, true, true, false, true, true}; }

/// Random placement of `count` particles over the whole 3D box [0, box.x] x [0, box.y] x [0, box.z].
inline PackingConfig box_packing(Vec3 box, std::int64_t count, std::uint64_t seed, double min_gap = 0.0002) {
  PackingConfig pc;
  pc.count = count;
  pc.x_max = box.x;
  pc.y_max = box.y;
  pc.z_max = box.z;
  pc.min_gap = min_gap;
  pc.seed = seed;
  return pc;
}

/// Runs the enclosed code on `n` OpenMP threads. One-particle runs use one: on a shared, loaded machine each
/// parallel region would otherwise wait for a second thread every step.
class ScopedThreads {
 public:
  explicit ScopedThreads(int n) : saved_(omp_get_max_threads()) { omp_set_num_threads(n); }
  ~ScopedThreads() { omp_set_num_threads(saved_); }
  ScopedThreads(const ScopedThreads&) = delete;
  ScopedThreads& operator=(const ScopedThreads&) = delete;

 private:
  int saved_;
};

inline double rel_err(double computed, double exact) { return std::abs(computed - exact) / std::abs(exact); }

/// A printed table in the style of the MFIX verification suite (exact vs computed vs error).
class Table {
 public:
  /// `label` > 0 adds a leading text column of that width (see labelled_row).
  Table(std::string title, std::vector<std::string> columns, int label = 0) : cols_(std::move(columns)), label_(label) {
    fmt::print("\n{}\n", title);
    std::string line(static_cast<std::size_t>(label_), ' ');
    for (const auto& c : cols_) line += fmt::format("{:>14}", c);
    fmt::print("{}\n", line);
  }
  void row(const std::vector<double>& v) const {
    std::string line;
    for (double x : v) line += fmt::format("{:>14.6g}", x);
    fmt::print("{}\n", line);
    std::fflush(stdout);
  }
  void labelled_row(const std::string& label, const std::vector<double>& v) const {
    fmt::print("{:<{}}", label, label_);
    row(v);
  }

 private:
  std::vector<std::string> cols_;
  int label_ = 0;
};

}  // namespace fluidbed::test
