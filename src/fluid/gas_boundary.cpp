#include "fluid/gas_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "parallel/periodic_halo.hpp"

namespace fluidbed {

double schedule_velocity(const InletSchedule& s, double u0, double t) {
  switch (s.kind) {
    case ScheduleKind::Constant:
      return u0;
    case ScheduleKind::Ramp:
      if (t <= s.ramp_start) return s.ramp_from;
      if (t >= s.ramp_start + s.ramp_time) return u0;
      return s.ramp_from + (t - s.ramp_start) / s.ramp_time * (u0 - s.ramp_from);
    case ScheduleKind::Table: {
      if (s.times.empty()) return u0;
      if (t <= s.times.front()) return s.velocities.front();
      if (t >= s.times.back()) return s.velocities.back();
      const std::size_t k = static_cast<std::size_t>(std::upper_bound(s.times.begin(), s.times.end(), t) - s.times.begin());
      const double f = (t - s.times[k - 1]) / (s.times[k] - s.times[k - 1]);
      return s.velocities[k - 1] + f * (s.velocities[k] - s.velocities[k - 1]);
    }
    case ScheduleKind::Sine:
      return u0 + s.amplitude * std::sin(2.0 * std::numbers::pi * s.frequency * t + s.phase);
    case ScheduleKind::Square: {
      const double cycle = s.frequency * t + s.phase / (2.0 * std::numbers::pi);
      return cycle - std::floor(cycle) < s.duty ? u0 + s.amplitude : u0;
    }
  }
  return u0;
}

double background_inlet_velocity(const GasBoundaryConfig& bc, double t) {
  if (bc.schedule.kind != ScheduleKind::Constant) return schedule_velocity(bc.schedule, bc.inlet_velocity, t);
  if (bc.ramp_time <= 0.0 || t >= bc.ramp_time) return bc.inlet_velocity;
  const double f = std::max(t, 0.0) / bc.ramp_time;
  return bc.ramp_from + f * (bc.inlet_velocity - bc.ramp_from);
}

void inlet_velocities(const GasBoundaryConfig& bc, double t, InletVelocities& v) {
  v.background = background_inlet_velocity(bc, t);
  v.jet.assign(bc.jets.size(), 0.0);
  v.active.assign(bc.jets.size(), 0);
  for (std::size_t k = 0; k < bc.jets.size(); ++k) {
    const InletJet& jet = bc.jets[k];
    if (t < jet.t_start || t >= jet.t_end) continue;
    v.active[k] = 1;
    v.jet[k] = schedule_velocity(jet.schedule, jet.velocity, t);
  }
}

InletVelocities inlet_velocities(const GasBoundaryConfig& bc, double t) {
  InletVelocities v;
  inlet_velocities(bc, t, v);
  return v;
}

namespace {
double schedule_peak(const InletSchedule& s, double u0) {
  switch (s.kind) {
    case ScheduleKind::Constant:
      return std::abs(u0);
    case ScheduleKind::Ramp:
      return std::max(std::abs(u0), std::abs(s.ramp_from));
    case ScheduleKind::Table: {
      double m = 0.0;
      for (double u : s.velocities) m = std::max(m, std::abs(u));
      return m;
    }
    case ScheduleKind::Sine:
      return std::abs(u0) + std::abs(s.amplitude);
    case ScheduleKind::Square:
      return std::max(std::abs(u0), std::abs(u0 + s.amplitude));
  }
  return std::abs(u0);
}

/// Fraction of the face [x_lo, x_hi] not covered by an active jet.
double background_fraction(const GasBoundaryConfig& bc, const InletVelocities& v, double x_lo, double x_hi) {
  double covered = 0.0;
  for (std::size_t k = 0; k < bc.jets.size(); ++k) {
    if (!v.active[k]) continue;
    const InletJet& jet = bc.jets[k];
    const double lo = std::max(x_lo, jet.x_centre - 0.5 * jet.width);
    const double hi = std::min(x_hi, jet.x_centre + 0.5 * jet.width);
    if (hi > lo) covered += hi - lo;
  }
  return std::max(0.0, 1.0 - covered / (x_hi - x_lo));
}
}  // namespace

namespace {
// The distributor factors average to 1 over all faces, but jets cover some faces: what the noise added to the
// background over the uncovered parts is taken back in proportion to them, so that the total inflow stays
// exactly that of the schedules (nothing to do, bit for bit, without noise or without a covered face).
void keep_background_flow(const std::vector<double>& noise, const std::vector<double>& fraction, double u_bg,
                          std::vector<double>& out) {
  bool covered = false;
  for (double f : fraction) covered = covered || f < 1.0;
  bool perturbed = false;
  for (double f : noise) perturbed = perturbed || f != 1.0;
  if (!covered || !perturbed) return;
  double added = 0.0, open = 0.0;
  for (std::size_t f = 0; f < out.size(); ++f) {
    added += (noise[f] - 1.0) * u_bg * fraction[f];
    open += fraction[f];
  }
  if (!(open > 0.0)) return;
  for (std::size_t f = 0; f < out.size(); ++f) out[f] -= added * fraction[f] / open;
}
}  // namespace

double inlet_peak_velocity(const GasBoundaryConfig& bc) {
  double u = bc.schedule.kind == ScheduleKind::Constant ? std::max(std::abs(bc.inlet_velocity), std::abs(bc.ramp_from))
                                                        : schedule_peak(bc.schedule, bc.inlet_velocity);
  for (const InletJet& jet : bc.jets) u = std::max(u, schedule_peak(jet.schedule, jet.velocity));
  return u;
}

double inlet_superficial_velocity(const GasBoundaryConfig& bc, const InletVelocities& v, double x_lo, double x_hi) {
  const double width = x_hi - x_lo;
  const double u_bg = v.background;
  double flux = u_bg * width;
  for (std::size_t k = 0; k < bc.jets.size(); ++k) {
    if (!v.active[k]) continue;
    const InletJet& jet = bc.jets[k];
    const double lo = std::max(x_lo, jet.x_centre - 0.5 * jet.width);
    const double hi = std::min(x_hi, jet.x_centre + 0.5 * jet.width);
    if (hi > lo) flux += (v.jet[k] - u_bg) * (hi - lo);
  }
  return flux / width;
}

double inlet_superficial_velocity(const GasBoundaryConfig& bc, double x_lo, double x_hi, double t) {
  return inlet_superficial_velocity(bc, inlet_velocities(bc, t), x_lo, x_hi);
}

std::vector<double> inlet_noise_factors(const GasBoundaryConfig& bc, int nx) {
  std::vector<double> f;
  inlet_noise_factors(bc, nx, f);
  return f;
}

void inlet_noise_factors(const GasBoundaryConfig& bc, int nx, std::vector<double>& f) {
  f.assign(static_cast<std::size_t>(std::max(nx, 0)), 1.0);
  if (bc.inlet_noise <= 0.0 || nx <= 0) return;
  double sum = 0.0;
  for (int i = 0; i < nx; ++i) {
    // splitmix64 of (seed, face): the same factors on every platform, independent of any other random stream.
    std::uint64_t z = bc.noise_seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(i + 1) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    const double u = static_cast<double>(z >> 11) * 0x1.0p-53;
    f[static_cast<std::size_t>(i)] = 1.0 + bc.inlet_noise * (2.0 * u - 1.0);
    sum += f[static_cast<std::size_t>(i)];
  }
  for (double& x : f) x *= static_cast<double>(nx) / sum;
}

namespace {

// The 2D bottom: slots across x, each face's background part through its distributor factor.
void inlet_profile_2d(const GasBoundaryConfig& bc, const InletVelocities& v, const Grid<2>& grid,
                      std::vector<double>& out, InletWork& w) {
  const int nx = grid.n(0);
  const std::size_t n = static_cast<std::size_t>(nx);
  out.resize(n);
  inlet_noise_factors(bc, nx, w.noise);
  const std::vector<double>& noise = w.noise;
  const double u_bg = v.background;
  std::vector<double>& fraction = w.fraction;
  fraction.resize(n);
  for (int i = 0; i < nx; ++i) {
    const double x_lo = grid.face(0, grid.domain.lo[0] + i);
    const std::size_t f = static_cast<std::size_t>(i);
    // Only the background flow passes through the perturbed distributor; a jet keeps its own velocity.
    const double u = inlet_superficial_velocity(bc, v, x_lo, x_lo + grid.h[0]);
    fraction[f] = background_fraction(bc, v, x_lo, x_lo + grid.h[0]);
    out[f] = u + (noise[f] - 1.0) * u_bg * fraction[f];
  }
  keep_background_flow(noise, fraction, u_bg, out);
}

}  // namespace

std::vector<InletJet> perforated_plate_holes(const PerforatedPlate& plate, int dimension) {
  std::vector<InletJet> holes;
  const int rows = dimension == 3 ? plate.n_z : 1;
  const bool tri = dimension == 3 && plate.layout == HolePitch::Triangular && rows > 1;
  const double row_pitch = tri ? 0.5 * std::sqrt(3.0) * plate.pitch : plate.pitch;
  // Centred block: a triangular block's odd rows reach half a pitch further in x.
  const double x_first = plate.x_centre - 0.5 * ((plate.n_x - 1) + (tri ? 0.5 : 0.0)) * plate.pitch;
  const double z_first = plate.z_centre - 0.5 * (rows - 1) * row_pitch;
  for (int k = 0; k < rows; ++k)
    for (int i = 0; i < plate.n_x; ++i) {
      InletJet h;
      h.x_centre = x_first + (i + (tri && k % 2 == 1 ? 0.5 : 0.0)) * plate.pitch;
      h.width = plate.hole;
      h.velocity = plate.velocity;
      h.t_start = plate.t_start;
      h.t_end = plate.t_end;
      h.schedule = plate.schedule;
      if (dimension == 3) {
        h.shape = InletShape::Disc;
        h.z_centre = z_first + k * row_pitch;
        h.depth = plate.hole;
      }
      holes.push_back(h);
    }
  return holes;
}

namespace {

// Integral of sqrt(r^2 - x^2) from 0 to x, |x| <= r: the area under the upper half of a circle.
double half_disc_primitive(double r, double x) {
  const double s = std::sqrt(std::max(r * r - x * x, 0.0));
  return 0.5 * (x * s + r * r * std::asin(std::clamp(x / r, -1.0, 1.0)));
}

// Area of the disc of radius r about the origin inside [x1, x2] x [z1, z2]: the integral over x of the part of
// the chord inside [z1, z2], split where a chord end crosses z1 or z2 so that each piece has a closed form.
double disc_rectangle_area(double r, double x1, double x2, double z1, double z2) {
  const double a = std::max(x1, -r);
  const double b = std::min(x2, r);
  if (!(b > a) || !(z2 > z1)) return 0.0;
  std::vector<double> cuts{a, b};
  for (double z : {z1, z2}) {
    if (std::abs(z) >= r) continue;
    const double xs = std::sqrt(r * r - z * z);
    for (double x : {-xs, xs})
      if (x > a && x < b) cuts.push_back(x);
  }
  std::sort(cuts.begin(), cuts.end());
  double area = 0.0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double p = cuts[k];
    const double q = cuts[k + 1];
    const double m = 0.5 * (p + q);
    const double s = std::sqrt(std::max(r * r - m * m, 0.0));
    const bool top_flat = z2 < s;
    const bool bottom_flat = z1 > -s;
    if ((top_flat ? z2 : s) <= (bottom_flat ? z1 : -s)) continue;
    const double chord = half_disc_primitive(r, q) - half_disc_primitive(r, p);
    area += (top_flat ? z2 * (q - p) : chord) - (bottom_flat ? z1 * (q - p) : -chord);
  }
  return area;
}

double overlap(double lo1, double hi1, double lo2, double hi2) {
  return std::max(0.0, std::min(hi1, hi2) - std::max(lo1, lo2));
}

}  // namespace

double jet_overlap_area(const InletJet& jet, double x_lo, double x_hi, double z_lo, double z_hi) {
  switch (jet.shape) {
    case InletShape::Slot:
      return overlap(x_lo, x_hi, jet.x_centre - 0.5 * jet.width, jet.x_centre + 0.5 * jet.width) * (z_hi - z_lo);
    case InletShape::Rectangle:
      return overlap(x_lo, x_hi, jet.x_centre - 0.5 * jet.width, jet.x_centre + 0.5 * jet.width) *
             overlap(z_lo, z_hi, jet.z_centre - 0.5 * jet.depth, jet.z_centre + 0.5 * jet.depth);
    case InletShape::Disc:
      return disc_rectangle_area(0.5 * jet.width, x_lo - jet.x_centre, x_hi - jet.x_centre, z_lo - jet.z_centre,
                                 z_hi - jet.z_centre);
  }
  return 0.0;
}

namespace {
template <int Dim>
void inlet_profile(const GasBoundaryConfig& bc, const InletVelocities& v, const Grid<Dim>& grid,
                   std::vector<double>& out, InletWork& w) {
  if constexpr (Dim == 2) {
    inlet_profile_2d(bc, v, grid, out, w);
  } else {
    const int nx = grid.n(0);
    const int nz = grid.n(2);
    out.resize(static_cast<std::size_t>(nx) * static_cast<std::size_t>(nz));
    inlet_noise_factors(bc, nx * nz, w.noise);
    const std::vector<double>& noise = w.noise;
    const double u_bg = v.background;
    const double area = grid.h[0] * grid.h[2];
    std::vector<double>& flux = w.flux;
    flux.assign(out.size(), u_bg * area);
    std::vector<double>& covered = w.covered;
    covered.assign(out.size(), 0.0);
    const double x0 = grid.face(0, grid.domain.lo[0]);
    const double z0 = grid.face(2, grid.domain.lo[2]);
    // Each jet visits only the faces its bounding box touches (one face of margin), so a plate of many holes costs
    // its holes' footprints, not holes x faces; a face's overlaps still add in jet order, and the faces skipped
    // would add exactly zero, so the profile is the same bit for bit.
    const auto first_last = [](double lo, double hi, double origin, double h, int n) {
      const int a = std::max(0, static_cast<int>(std::floor((lo - origin) / h)) - 1);
      const int b = std::min(n - 1, static_cast<int>(std::floor((hi - origin) / h)) + 1);
      return std::pair<int, int>{a, b};
    };
    for (std::size_t j = 0; j < bc.jets.size(); ++j) {
      if (!v.active[j]) continue;
      const InletJet& jet = bc.jets[j];
      const auto [i_a, i_b] = first_last(jet.x_centre - 0.5 * jet.width, jet.x_centre + 0.5 * jet.width, x0, grid.h[0], nx);
      const double half_z = jet.shape == InletShape::Disc ? 0.5 * jet.width : 0.5 * jet.depth;
      const auto [k_a, k_b] = jet.shape == InletShape::Slot
                                  ? std::pair<int, int>{0, nz - 1}
                                  : first_last(jet.z_centre - half_z, jet.z_centre + half_z, z0, grid.h[2], nz);
      for (int k = k_a; k <= k_b; ++k)
        for (int i = i_a; i <= i_b; ++i) {
          const double x_lo = grid.face(0, grid.domain.lo[0] + i);
          const double z_lo = grid.face(2, grid.domain.lo[2] + k);
          const double a = jet_overlap_area(jet, x_lo, x_lo + grid.h[0], z_lo, z_lo + grid.h[2]);
          const std::size_t f = static_cast<std::size_t>(k) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i);
          flux[f] += (v.jet[j] - u_bg) * a;
          covered[f] += a;
        }
    }
    std::vector<double>& fraction = w.fraction;
    fraction.resize(out.size());
    for (std::size_t f = 0; f < out.size(); ++f) {
      // Only the background flow passes through the perturbed distributor; a jet keeps its own velocity.
      fraction[f] = std::max(0.0, 1.0 - covered[f] / area);
      out[f] = flux[f] / area + (noise[f] - 1.0) * u_bg * fraction[f];
    }
    keep_background_flow(noise, fraction, u_bg, out);
  }
}

}  // namespace

template <int Dim>
void inlet_superficial_profile(const GasBoundaryConfig& bc, const InletVelocities& v, const Grid<Dim>& grid,
                               std::vector<double>& out) {
  InletWork w;
  inlet_profile(bc, v, grid, out, w);
}

template <int Dim>
void inlet_superficial_profile(const GasBoundaryConfig& bc, const Grid<Dim>& grid, double t, std::vector<double>& out) {
  InletWork w;
  inlet_superficial_profile(bc, grid, t, out, w);
}

template <int Dim>
void inlet_superficial_profile(const GasBoundaryConfig& bc, const Grid<Dim>& grid, double t, std::vector<double>& out,
                               InletWork& work) {
  inlet_velocities(bc, t, work.v);
  inlet_profile(bc, work.v, grid, out, work);
}

namespace {
// Uniform faces: the area-weighted mean is the plain mean.
double mean_of(const std::vector<double>& u) {
  double sum = 0.0;
  for (double x : u) sum += x;
  return u.empty() ? 0.0 : sum / static_cast<double>(u.size());
}
}  // namespace

template <int Dim>
double inlet_mean_velocity(const GasBoundaryConfig& bc, const Grid<Dim>& grid, double t) {
  std::vector<double> u;
  inlet_superficial_profile(bc, grid, t, u);
  return mean_of(u);
}

#define FLUIDBED_INLET_INSTANCES(D)                                                                              \
  template void inlet_superficial_profile(const GasBoundaryConfig&, const InletVelocities&, const Grid<D>&,     \
                                          std::vector<double>&);                                                 \
  template void inlet_superficial_profile(const GasBoundaryConfig&, const Grid<D>&, double, std::vector<double>&); \
  template void inlet_superficial_profile(const GasBoundaryConfig&, const Grid<D>&, double, std::vector<double>&,  \
                                          InletWork&);                                                           \
  template double inlet_mean_velocity(const GasBoundaryConfig&, const Grid<D>&, double);
FLUIDBED_INLET_INSTANCES(2)
FLUIDBED_INLET_INSTANCES(3)
#undef FLUIDBED_INLET_INSTANCES

template <int Dim>
void fill_wall_tangential(Field<Dim>& u, int e, bool high, WallKind kind, double u_wall) {
  const IndexBox<Dim>& b = u.box();
  const double sign = kind == WallKind::NoSlip ? -1.0 : 1.0;
  const double known = kind == WallKind::NoSlip ? 2.0 * u_wall : 0.0;
  // Ghost layer at distance k + 1 beyond the side mirrors the layer at distance k inside it.
  const int mirror_sum = high ? 2 * b.hi[e] - 1 : 2 * b.lo[e] - 1;
  for_each(b.outside(e, high, u.ghost()), [&](const Index<Dim>& c) {
    Index<Dim> m = c;
    m[e] = mirror_sum - c[e];
    u[c] = known + sign * u[m];
  });
}

template <int Dim>
void fill_zero_gradient(Field<Dim>& f, int e, bool high) {
  const IndexBox<Dim>& b = f.box();
  const int edge = high ? b.hi[e] - 1 : b.lo[e];
  for_each(b.outside(e, high, f.ghost()), [&](const Index<Dim>& c) {
    Index<Dim> m = c;
    m[e] = edge;
    f[c] = f[m];
  });
}

template <int Dim>
void fill_pressure_outlet(Field<Dim>& p, int e, bool high, double p_out) {
  const IndexBox<Dim>& b = p.box();
  const int mirror_sum = high ? 2 * b.hi[e] - 1 : 2 * b.lo[e] - 1;
  for_each(b.outside(e, high, p.ghost()), [&](const Index<Dim>& c) {
    Index<Dim> m = c;
    m[e] = mirror_sum - c[e];
    p[c] = 2.0 * p_out - p[m];
  });
}

template <int Dim>
void fix_wall_normal(Field<Dim>& u_a, int a, bool high) {
  u_a.fill(u_a.box().inside(a, high), 0.0);
}

template <int Dim>
void fill_velocity_ghosts(const Grid<Dim>& grid, const GasBoundaryConfig& bc, const Comm& comm, FaceFields<Dim>& u) {
  const bool outlet = bc.top == TopBoundary::PressureOutlet;
  for (int a = 0; a < Dim; ++a) {
    Field<Dim>& ua = u[a];
    for (int e = 0; e < Dim; ++e)
      for (bool high : {false, true}) {
        if (!grid.at_domain_side(e, high)) continue;
        if (e == a) {
          fill_zero_gradient(ua, e, high);
        } else if (e == 1 && high && outlet) {
          fill_zero_gradient(ua, e, high);
        } else {
          const WallKind kind = e == 0   ? bc.side_walls
                                : e == 2 ? bc.front_back_walls
                                : high   ? bc.top_wall
                                         : bc.bottom_wall;
          const double speed = e == 1 && high && a == 0 ? bc.lid_velocity : 0.0;
          fill_wall_tangential(ua, e, high, kind, speed);
        }
      }
    fill_periodic_ghosts(grid, ua);
    comm.exchange_halo(ua);
  }
}

template <int Dim>
void fill_pressure_ghosts(const Grid<Dim>& grid, const GasBoundaryConfig& bc, const Comm& comm, Field<Dim>& p) {
  for (int e = 0; e < Dim; ++e)
    for (bool high : {false, true}) {
      if (!grid.at_domain_side(e, high)) continue;
      if (e == 1 && high && bc.top == TopBoundary::PressureOutlet) {
        fill_pressure_outlet(p, e, high, bc.top_pressure);
      } else {
        fill_zero_gradient(p, e, high);
      }
    }
  fill_periodic_ghosts(grid, p);
  comm.exchange_halo(p);
}

#define FLUIDBED_GHOST_INSTANCES(D)                                                                              \
  template void fill_wall_tangential(Field<D>&, int, bool, WallKind, double);                                    \
  template void fill_zero_gradient(Field<D>&, int, bool);                                                        \
  template void fill_pressure_outlet(Field<D>&, int, bool, double);                                              \
  template void fix_wall_normal(Field<D>&, int, bool);                                                           \
  template void fill_velocity_ghosts(const Grid<D>&, const GasBoundaryConfig&, const Comm&, FaceFields<D>&);     \
  template void fill_pressure_ghosts(const Grid<D>&, const GasBoundaryConfig&, const Comm&, Field<D>&);
FLUIDBED_GHOST_INSTANCES(2)
FLUIDBED_GHOST_INSTANCES(3)
#undef FLUIDBED_GHOST_INSTANCES

void validate(const InletSchedule& s, const std::string& region) {
  const auto require = [&](bool ok, const std::string& what) {
    if (!ok) throw_input_error("gas: " + region + " schedule: " + what);
  };
  switch (s.kind) {
    case ScheduleKind::Constant:
      break;
    case ScheduleKind::Ramp:
      require(s.ramp_time > 0.0 && std::isfinite(s.ramp_time), "ramp_time must be positive");
      require(std::isfinite(s.ramp_from) && std::isfinite(s.ramp_start), "ramp_from and ramp_start must be finite");
      break;
    case ScheduleKind::Table:
      require(!s.times.empty() && s.times.size() == s.velocities.size(),
              "a table needs as many velocities as times, at least one");
      for (std::size_t k = 0; k < s.times.size(); ++k) {
        require(std::isfinite(s.times[k]) && std::isfinite(s.velocities[k]), "table values must be finite");
        require(k == 0 || s.times[k] > s.times[k - 1], "table times must increase strictly");
      }
      break;
    case ScheduleKind::Sine:
    case ScheduleKind::Square:
      require(s.frequency > 0.0 && std::isfinite(s.frequency), "frequency must be positive");
      require(std::isfinite(s.amplitude) && std::isfinite(s.phase), "amplitude and phase must be finite");
      require(s.kind == ScheduleKind::Sine || (s.duty > 0.0 && s.duty < 1.0), "duty must lie in (0, 1)");
      break;
  }
}

void validate(const GasConfig& c) {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw_input_error("gas: " + what);
  };
  require(c.rho_g > 0.0 && std::isfinite(c.rho_g), "rho_g must be positive");
  require(c.mu_g >= 0.0 && std::isfinite(c.mu_g), "mu_g must be non-negative");
  require(c.viscous == ViscousStress::Off || c.mu_g > 0.0, "viscous stress needs mu_g > 0");
  require(c.relax_velocity > 0.0 && c.relax_velocity <= 1.0, "relax_velocity must be in (0, 1]");
  require(c.relax_pressure > 0.0 && c.relax_pressure <= 1.0, "relax_pressure must be in (0, 1]");
  require(c.max_simple_iterations >= 1, "max_simple_iterations must be at least 1");
  require(c.mass_tolerance > 0.0, "mass_tolerance must be positive");
  require(c.momentum_tolerance > 0.0, "momentum_tolerance must be positive");
  require(c.coupling_tolerance >= 0.0 && c.coupling_tolerance < 1.0, "coupling_tolerance must lie in [0, 1)");
  require(c.momentum_solver_tolerance > 0.0 && c.momentum_solver_tolerance < 1.0,
          "momentum_solver_tolerance must lie in (0, 1)");
  require(c.pressure_solver_tolerance > 0.0 && c.pressure_solver_tolerance < 1.0,
          "pressure_solver_tolerance must lie in (0, 1)");
  require(c.momentum_solver_max_iterations >= 1, "momentum_solver_max_iterations must be at least 1");
  require(c.boundary.ramp_time >= 0.0 && std::isfinite(c.boundary.ramp_time), "inlet ramp_time must be non-negative");
  require(std::isfinite(c.boundary.ramp_from), "inlet ramp_from must be finite");
  require(c.boundary.inlet_noise >= 0.0 && c.boundary.inlet_noise < 1.0, "inlet noise must lie in [0, 1)");
  for (const InletJet& jet : c.boundary.jets) {
    require(jet.width > 0.0, "jet width must be positive");
    require(jet.shape != InletShape::Rectangle || jet.depth > 0.0, "a rectangular jet's depth must be positive");
    require(jet.t_end >= jet.t_start, "jet t_end must not precede t_start");
    validate(jet.schedule, "jet");
  }
  validate(c.boundary.schedule, "background");
}

}  // namespace fluidbed
