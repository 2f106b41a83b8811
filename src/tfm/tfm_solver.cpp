#include "tfm/tfm_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <string>

#include "core/error.hpp"
#include "fluid/drag.hpp"
#include "fluid/gas_boundary.hpp"
#include "tfm/packing_limiter.hpp"
#include "tfm/tvd_convection.hpp"

namespace fluidbed::tfm {
namespace {

// Solids fraction kept in the face mass and drag of an empty face, so that the 2x2 drag system stays regular;
// both scale together, so trace solids still move at their terminal slip.
constexpr double kEpsSFloor = 1e-8;
// Faces with less solids than this carry no solids-momentum convection and do not limit dt (trace solids).
constexpr double kEpsSTrace = 1e-4;
// Below this solids fraction the constant solids viscosity is ramped to zero ("constant in the bed").
constexpr double kEpsSBed = 0.05;

int clampi(int k, int lo, int hi) { return std::min(std::max(k, lo), hi); }

// Uniform number in [0, 1) from (seed, stream, index) by the splitmix64 finaliser (Steele et al. 2014): the same
// on every platform and independent of the order in which cells ask, so the perturbations are reproducible.
double seeded_uniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream * 0x100000001B3ULL + index + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

// Advective term (U . grad) u of the x-velocity at u-face (i, j), TVD face values, advective form
// div(U u) - u div(U) so that it vanishes for a uniform field.
template <class Law>
double advect_u(const Field2& u, const Field2& v, int i, int j, double dx, double dy) {
  const int nx = u.nx - 1, ny = u.ny;
  auto U = [&](int a, int b) { return u(clampi(a, 0, nx), clampi(b, 0, ny - 1)); };
  const double ue_vel = 0.5 * (U(i, j) + U(i + 1, j));
  const double uw_vel = 0.5 * (U(i - 1, j) + U(i, j));
  const double vn_vel = 0.5 * (v(i - 1, j + 1) + v(i, j + 1));
  const double vs_vel = 0.5 * (v(i - 1, j) + v(i, j));
  const double fe = ue_vel * tvd::face_value<Law>(ue_vel, U(i - 1, j), U(i, j), U(i + 1, j), U(i + 2, j));
  const double fw = uw_vel * tvd::face_value<Law>(uw_vel, U(i - 2, j), U(i - 1, j), U(i, j), U(i + 1, j));
  const double fn = vn_vel * tvd::face_value<Law>(vn_vel, U(i, j - 1), U(i, j), U(i, j + 1), U(i, j + 2));
  const double fs = vs_vel * tvd::face_value<Law>(vs_vel, U(i, j - 2), U(i, j - 1), U(i, j), U(i, j + 1));
  return (fe - fw) / dx + (fn - fs) / dy - U(i, j) * ((ue_vel - uw_vel) / dx + (vn_vel - vs_vel) / dy);
}

// Same for the y-velocity at v-face (i, j).
template <class Law>
double advect_v(const Field2& u, const Field2& v, int i, int j, double dx, double dy) {
  const int nx = v.nx, ny = v.ny - 1;
  auto V = [&](int a, int b) { return v(clampi(a, 0, nx - 1), clampi(b, 0, ny)); };
  const int jl = clampi(j - 1, 0, ny - 1), jh = clampi(j, 0, ny - 1);
  const double vn_vel = 0.5 * (V(i, j) + V(i, j + 1));
  const double vs_vel = 0.5 * (V(i, j - 1) + V(i, j));
  const double ue_vel = 0.5 * (u(i + 1, jl) + u(i + 1, jh));
  const double uw_vel = 0.5 * (u(i, jl) + u(i, jh));
  const double fn = vn_vel * tvd::face_value<Law>(vn_vel, V(i, j - 1), V(i, j), V(i, j + 1), V(i, j + 2));
  const double fs = vs_vel * tvd::face_value<Law>(vs_vel, V(i, j - 2), V(i, j - 1), V(i, j), V(i, j + 1));
  const double fe = ue_vel * tvd::face_value<Law>(ue_vel, V(i - 1, j), V(i, j), V(i + 1, j), V(i + 2, j));
  const double fw = uw_vel * tvd::face_value<Law>(uw_vel, V(i - 2, j), V(i - 1, j), V(i, j), V(i + 1, j));
  return (fe - fw) / dx + (fn - fs) / dy - V(i, j) * ((ue_vel - uw_vel) / dx + (vn_vel - vs_vel) / dy);
}

// Partial elimination of the interphase drag (Syamlal 1998, MFIX): the gas and solids momentum equations of
// one face are solved together as a 2x2 system, so the drag is fully implicit and never limits dt.
struct FaceSolve {
  double ug, us;  // predicted velocities
  double dg, ds;  // velocity response to a unit gas-pressure-correction gradient
  double gs, ss;  // velocity response to a unit solids-pressure-correction gradient
};

FaceSolve solve_face(double a_g, double a_s, double beta, double rhs_g, double rhs_s, double eps_g, double eps_s) {
  const double m11 = a_g + beta, m22 = a_s + beta, m12 = -beta;
  const double det = m11 * m22 - m12 * m12;
  FaceSolve f{};
  f.ug = (m22 * rhs_g - m12 * rhs_s) / det;
  f.us = (m11 * rhs_s - m12 * rhs_g) / det;
  f.dg = (m22 * eps_g - m12 * eps_s) / det;
  f.ds = (m11 * eps_s - m12 * eps_g) / det;
  f.gs = -m12 / det;
  f.ss = m11 / det;
  return f;
}

template <SolidsRheology R>
double solids_pressure_law(const TfmConfig& c, const GranularMaterial& m, double eps, double theta) {
  if constexpr (R == SolidsRheology::KineticTheory) {
    // Eq. 19: frictional regime at or below eps*, kinetic theory above.
    if (eps <= c.eps_star) return frictional_pressure(eps, c.eps_star);
    return kt_pressure(m, eps, theta);
  } else {
    return modulus_pressure(c.modulus, eps, c.eps_star);
  }
}

}  // namespace

void validate(const TfmConfig& c) {
  auto need = [](bool ok, const char* what) {
    if (!ok) throw_input_error(std::string("tfm: ") + what);
  };
  need(c.width > 0.0 && c.height > 0.0, "width and height must be positive");
  need(c.cell_size > 0.0 && c.cell_size <= std::min(c.width, c.height), "cell_size must be positive and fit the domain");
  const double nx = c.width / c.cell_size, ny = c.height / c.cell_size;
  need(std::abs(nx - std::round(nx)) < 1e-6 && std::abs(ny - std::round(ny)) < 1e-6,
       "width and height must be whole multiples of cell_size");
  need(c.d_p > 0.0, "d_p must be positive");
  need(c.rho_s > c.rho_g && c.rho_g > 0.0, "need rho_s > rho_g > 0");
  need(c.mu_g > 0.0, "mu_g must be positive");
  need(c.e > 0.0 && c.e <= 1.0, "e must lie in (0, 1]");
  need(c.rheology != SolidsRheology::KineticTheory || c.e < 1.0,
       "e = 1 does not work with the kinetic theory: the algebraic granular temperature balances shear production "
       "against collisional dissipation (K4 ~ 1 - e^2, Eqs. 25-26), which vanishes for elastic particles, so Theta "
       "has no finite value; use e < 1 (the paper: 0.9)");
  need(c.eps_noise >= 0.0 && c.eps_noise < 0.5, "eps_noise must lie in [0, 0.5)");
  need(c.linear_max_iterations >= 0, "linear_max_iterations must be non-negative");
  need(c.phi_deg > 0.0 && c.phi_deg < 90.0, "phi_deg must lie in (0, 90)");
  need(c.eps_star > 0.0 && c.eps_star < 1.0, "eps_star must lie in (0, 1)");
  need(c.eps_initial >= c.eps_star && c.eps_initial <= 1.0, "eps_initial must lie in [eps_star, 1]");
  need(c.packed_height >= 0.0 && c.packed_height <= c.height, "packed_height must lie in [0, height]");
  need(c.mu_s_constant >= 0.0 && c.mu_s_max > 0.0, "solids viscosities must be non-negative (mu_s_max positive)");
  need(c.modulus.a > 0.0 && c.modulus.b > 0.0, "modulus a and b must be positive");
  need(c.cfl > 0.0 && c.cfl <= 1.0, "cfl must lie in (0, 1]");
  need(c.max_dense_change > 0.0 && c.max_dense_change < 0.1, "max_dense_change must lie in (0, 0.1)");
  need(packing_allowance(c) >= 0.0 && packing_allowance(c) < c.eps_star, "max_compaction must lie in [0, eps_star)");
  need(c.dt_max > 0.0 && c.dt_min > 0.0 && c.dt_min < c.dt_max, "need 0 < dt_min < dt_max");
  need(c.mass_corrections >= 0 && c.mass_corrections <= 10, "mass_corrections must lie in [0, 10]");
  for (const InletJet& j : c.boundary.jets) {
    need(j.width > 0.0 && j.t_end >= j.t_start, "each jet needs width > 0 and t_end >= t_start");
  }
  need(c.boundary.top == TopBoundary::PressureOutlet || c.boundary.lid_velocity == 0.0,
       "a moving lid (boundary lid_velocity) is not supported by the two-fluid model");
}

namespace {
Grid2 validated_grid(const TfmConfig& c) {
  validate(c);
  return Grid2::uniform(c.width, c.height, static_cast<int>(std::lround(c.width / c.cell_size)),
                        static_cast<int>(std::lround(c.height / c.cell_size)));
}
}  // namespace

TfmSolver::TfmSolver(const TfmConfig& config)
    : config_(config), grid_(validated_grid(config)), pressure_solver_(grid_) {
  const int nx = grid_.nx, ny = grid_.ny;
  e_matrix_.build_cells(nx, ny);
  s_.eps = Field2(nx, ny, 1.0);
  for (int j = 0; j < ny; ++j) {
    // Partly filled cells get the volume-weighted voidage, so the initial mass matches packed_height exactly.
    const double filled = std::clamp((config_.packed_height - j * grid_.dy) / grid_.dy, 0.0, 1.0);
    for (int i = 0; i < nx; ++i) s_.eps(i, j) = 1.0 - filled * (1.0 - config_.eps_initial);
  }
  if (config_.eps_noise > 0.0) {
    // Kept at or above eps*: a cell starting compacted would start on the frictional pressure (Eq. 21).
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        if (s_.eps(i, j) >= 1.0) continue;
        const double u = seeded_uniform(config_.seed, 1, grid_.index(i, j));
        s_.eps(i, j) = std::clamp(s_.eps(i, j) + config_.eps_noise * (2.0 * u - 1.0), config_.eps_star, 1.0);
      }
    }
  }
  s_.ug = Field2(nx + 1, ny);
  s_.us = Field2(nx + 1, ny);
  s_.vg = Field2(nx, ny + 1);
  s_.vs = Field2(nx, ny + 1);
  s_.theta = Field2(nx, ny);
  s_.p = Field2(nx, ny);
  // Gas carries the background inflow: superficial velocity over the face voidage the continuity equation uses,
  // so the initial volume flux is divergence-free.
  // The background inflow at t = 0 (the start of an inlet ramp, src/fluid/gas_boundary.hpp).
  const double u_in = background_inlet_velocity(config_.boundary, 0.0);
  {
    Field2 up(nx + 1, ny, 0.0), vp(nx, ny + 1, 1.0), eg_x, eg_y;
    tvd_face_values(grid_, config_.limiter, s_.eps, FaceVelocity{up, vp, false}, eg_x, eg_y);
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const bool closed = j == ny && !(config_.boundary.top == TopBoundary::PressureOutlet);
        s_.vg(i, j) = closed ? 0.0 : u_in / (j == 0 ? 1.0 : eg_y(i, j));
      }
    }
  }
  // Pressure from the steady gas momentum balance of every face (Eq. 17 without inertia), integrated down
  // from the top: in a bed at rest the drag then carries exactly what the gas flow can carry.
  const double g = std::abs(config_.gravity.y);
  const DragBetaFn beta_of = drag_beta_function(DragModel{config_.drag_law, config_.drag_switch});
  auto drop_across = [&](int i, int j) {  // P(below) - P(above) across horizontal face j
    const double eg = j == ny ? s_.eps(i, ny - 1) : 0.5 * (s_.eps(i, j - 1) + s_.eps(i, j));
    auto beta_at = [&](int jc) {
      DragInput in{std::min(s_.eps(i, jc), 1.0 - kEpsSFloor), config_.d_p, config_.rho_g, config_.mu_g,
                   0.5 * (vg_interstitial(i, jc) + s_.vg(i, jc + 1))};
      return beta_of(in);
    };
    const double beta = j == ny ? beta_at(ny - 1) : 0.5 * (beta_at(j - 1) + beta_at(j));
    return config_.rho_g * g * grid_.dy + beta * s_.vg(i, j) * grid_.dy / eg;
  };
  for (int i = 0; i < nx; ++i) {
    s_.p(i, ny - 1) = config_.boundary.top_pressure + ((config_.boundary.top == TopBoundary::PressureOutlet) ? 0.5 * drop_across(i, ny) : 0.0);
    for (int j = ny - 1; j > 0; --j) s_.p(i, j - 1) = s_.p(i, j) + drop_across(i, j);
  }
  p_s_ = Field2(nx, ny);
  mu_s_ = Field2(nx, ny);
  lambda_s_ = Field2(nx, ny);
  beta_c_ = Field2(nx, ny);
  dps_deps_ = Field2(nx, ny);
}

double TfmSolver::vg_interstitial(int i, int j) const {
  // The distributor face stores the superficial inflow; inside the bottom cell the gas moves at U / eps.
  return j == 0 ? s_.vg(i, 0) / s_.eps(i, 0) : s_.vg(i, j);
}

void TfmSolver::mask_trace_solids_velocity() {
  const int nx = grid_.nx, ny = grid_.ny;
  auto has = [&](int i, int j) { return 1.0 - s_.eps(i, j) > kEpsSTrace; };
  const Field2 u0 = s_.us, v0 = s_.vs;
  // A face with (almost) no solids on one side has no meaningful solids velocity; it takes the velocity of the
  // next face into the solids (zero gradient), so stresses and convection at a bed surface see the bed only.
  for (int j = 0; j < ny; ++j) {
    for (int i = 1; i < nx; ++i) {
      const bool l = has(i - 1, j), r = has(i, j);
      if (l && r) continue;
      double val = 0.0;
      if (l && i - 1 > 0 && has(i - 2, j)) val = u0(i - 1, j);
      if (r && i + 1 < nx && has(i + 1, j)) val = u0(i + 1, j);
      s_.us(i, j) = val;
    }
  }
  for (int j = 1; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const bool b = has(i, j - 1), t = has(i, j);
      if (b && t) continue;
      double val = 0.0;
      if (b && j - 1 > 0 && has(i, j - 2)) val = v0(i, j - 1);
      if (t && j + 1 < ny && has(i, j + 1)) val = v0(i, j + 1);
      s_.vs(i, j) = val;
    }
  }
}

void TfmSolver::compute_cell_closures() {
  with_rheology(config_.rheology, [this](auto r) { compute_cell_closures_of<decltype(r)::value>(); });
}

template <SolidsRheology R>
void TfmSolver::compute_cell_closures_of() {
  const TfmConfig& c = config_;
  const GranularMaterial mat{c.d_p, c.rho_s, c.e};
  const double phi = c.phi_deg * 3.14159265358979323846 / 180.0;
  const int nx = grid_.nx, ny = grid_.ny;
  const double dx = grid_.dx, dy = grid_.dy;
  Field2 usc(nx, ny), vsc(nx, ny);
  solids_velocity_cells(usc, vsc);
  const DragBetaFn beta_of = drag_beta_function(DragModel{c.drag_law, c.drag_switch});  // chosen once
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double eps = s_.eps(i, j);
      const double eps_s = 1.0 - eps;
      const double ugc = 0.5 * (s_.ug(i, j) + s_.ug(i + 1, j)), vgc = 0.5 * (vg_interstitial(i, j) + s_.vg(i, j + 1));
      const double slip = std::hypot(usc(i, j) - ugc, vsc(i, j) - vgc);
      // Eq. 13 with the shared drag law; the floor keeps beta / (eps_s rho_s) finite in empty cells.
      DragInput in{std::min(eps, 1.0 - kEpsSFloor), c.d_p, c.rho_g, c.mu_g, slip};
      beta_c_(i, j) = beta_of(in);

      double mu = 0.0, lambda = 0.0, theta = 0.0;
      if constexpr (R == SolidsRheology::ConstantViscosity) {
        mu = std::min(c.mu_s_constant * std::min(1.0, eps_s / kEpsSBed), c.mu_s_max);
      } else if constexpr (R == SolidsRheology::KineticTheory) {
        StrainRate<2> d;
        d(0, 0) = (s_.us(i + 1, j) - s_.us(i, j)) / dx;
        d(1, 1) = (s_.vs(i, j + 1) - s_.vs(i, j)) / dy;
        const int il = std::max(i - 1, 0), ih = std::min(i + 1, nx - 1);
        const int jl = std::max(j - 1, 0), jh = std::min(j + 1, ny - 1);
        const double dudy = jh > jl ? (usc(i, jh) - usc(i, jl)) / ((jh - jl) * dy) : 0.0;
        const double dvdx = ih > il ? (vsc(ih, j) - vsc(il, j)) / ((ih - il) * dx) : 0.0;
        d(0, 1) = 0.5 * (dudy + dvdx);
        if (eps <= c.eps_star) {
          mu = frictional_viscosity(eps, c.eps_star, phi, d, c.mu_s_max);
        } else if (eps_s > 0.0) {
          theta = algebraic_granular_temperature(mat, eps, d);
          mu = std::min(kt_shear_viscosity(mat, eps, theta), c.mu_s_max);
          lambda = std::clamp(kt_bulk_viscosity(mat, eps, theta), -c.mu_s_max, c.mu_s_max);
        }
      }
      mu_s_(i, j) = mu;
      lambda_s_(i, j) = lambda;
      s_.theta(i, j) = theta;
      p_s_(i, j) = solids_pressure_law<R>(c, mat, eps, theta);
      // dP_s/d eps_s sets the speed of compaction waves that the explicit solids pressure must resolve.
      const double h = 1e-7;
      const double p_lo = solids_pressure_law<R>(c, mat, eps - h, theta);
      const double p_hi = solids_pressure_law<R>(c, mat, eps + h, theta);
      dps_deps_(i, j) = std::max(0.0, (p_lo - p_hi) / (2 * h));
    }
  }
}

double TfmSolver::choose_dt(double t_stop) const {
  double vmax = 0.0;
  const Field2& e = s_.eps;
  const int nx = grid_.nx, ny = grid_.ny;
  for (double x : s_.ug.v) vmax = std::max(vmax, std::abs(x));
  for (double x : s_.vg.v) vmax = std::max(vmax, std::abs(x));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double es = 1.0 - e(clampi(i - 1, 0, nx - 1), j), es2 = 1.0 - e(clampi(i, 0, nx - 1), j);
      if (std::min(es, es2) > kEpsSTrace) vmax = std::max(vmax, std::abs(s_.us(i, j)));
    }
  }
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double es = 1.0 - e(i, clampi(j - 1, 0, ny - 1)), es2 = 1.0 - e(i, clampi(j, 0, ny - 1));
      if (std::min(es, es2) > kEpsSTrace) vmax = std::max(vmax, std::abs(s_.vs(i, j)));
    }
  }
  // Paper Table 3 item 5: dt < dy / V_max. The solids pressure is implicit through the coupled correction,
  // so its compaction-wave speed does not enter.
  const double speed = vmax;
  double dt = config_.dt_max;
  if (speed > 0.0) dt = std::min(dt, config_.cfl * std::min(grid_.dx, grid_.dy) / speed);
  // Compaction rate of the last step, extrapolated: keeps cells from jumping deep past eps* in one step.
  if (s_.dense_change > 0.0 && s_.dt > 0.0) dt = std::min(dt, s_.dt * config_.max_dense_change / s_.dense_change);
  return std::min(dt, t_stop - s_.time);
}

double TfmSolver::step(double t_stop) {
  const TfmConfig& c = config_;
  const int nx = grid_.nx, ny = grid_.ny;
  const double dx = grid_.dx, dy = grid_.dy;
  const double rho_g = c.rho_g, rho_s = c.rho_s;
  const double gx = c.gravity.x, gy = c.gravity.y;
  const bool top_open = c.boundary.top == TopBoundary::PressureOutlet;

  mask_trace_solids_velocity();
  compute_cell_closures();
  const double dt = choose_dt(t_stop);
  if (!(dt >= c.dt_min) && t_stop - s_.time > c.dt_min) {
    throw_simulation_error(fmt::format(
        "tfm at t = {:.6g} s (step {}): the time step {:.3g} s fell below tfm.dt_min = {:.3g} s (largest solids "
        "speed {:.4g} m/s, last compaction per step {:.3g}). Likely cause: the solids are running away (speed) or a "
        "cell is being compacted ever faster past eps*. Remedy: {}",
        s_.time, s_.steps, dt, c.dt_min, max_solids_speed(), s_.dense_change, remedy()));
  }
  std::vector<double> inlet;
  // Jets, the start-up ramp and the distributor non-uniformity, as for the CFD-DEM gas (src/fluid/gas_boundary).
  inlet_superficial_profile(config_.boundary, grid_, s_.time + dt, inlet);
  linear_fallbacks_ = 0;

  const Field2& eps = s_.eps;
  const Field2& p = s_.p;
  const Field2 ug0 = s_.ug, us0 = s_.us, vs0 = s_.vs;
  // Gas enters the bed through the distributor at its interstitial speed: the convection sees U / eps there.
  Field2 vg0 = s_.vg;
  for (int i = 0; i < nx; ++i) vg0(i, 0) = s_.vg(i, 0) / eps(i, 0);
  Field2 dgu(nx + 1, ny), dsu(nx + 1, ny), dgv(nx, ny + 1), dsv(nx, ny + 1);
  Field2 gsu(nx + 1, ny), ssu(nx + 1, ny), gsv(nx, ny + 1), ssv(nx, ny + 1);
  const double mu_wall = c.solids_no_slip_walls ? 1.0 : 0.0;
  auto mu_corner = [&](int i, int j) {  // corner at (x_i, y_j), interior only
    // Harmonic mean of the four cells: a corner touching an empty cell carries no shear, so a dilute face is
    // never driven by the viscosity of a dense diagonal neighbour (which the explicit cross terms cannot bear).
    const double m[4] = {mu_s_(i - 1, j - 1), mu_s_(i, j - 1), mu_s_(i - 1, j), mu_s_(i, j)};
    double inv = 0.0;
    for (double x : m) {
      if (x <= 0.0) return 0.0;
      inv += 1.0 / x;
    }
    return 4.0 / inv;
  };
  auto bearing = [&](int i0, int j0, int i1, int j1) {
    return std::min(1.0 - eps(i0, j0), 1.0 - eps(i1, j1)) > kEpsSTrace;
  };
  auto div_s = [&](int i, int j) { return (us0(i + 1, j) - us0(i, j)) / dx + (vs0(i, j + 1) - vs0(i, j)) / dy; };

  // The momentum loops are compiled once per limiter law; the law is chosen here, once per step.
  tvd::with_limiter(c.limiter, [&](auto law) {
    using Law = decltype(law);
    // x-momentum on interior vertical faces (Eqs. 17-18).
    for (int j = 0; j < ny; ++j) {
      for (int i = 1; i < nx; ++i) {
        const double eg = 0.5 * (eps(i - 1, j) + eps(i, j));
        const double es = std::max(1.0 - eg, kEpsSFloor);
        const double beta = 0.5 * (beta_c_(i - 1, j) + beta_c_(i, j));
        const double dpdx = (p(i, j) - p(i - 1, j)) / dx;
        const double adv_g = advect_u<Law>(ug0, vg0, i, j, dx, dy);
        const double a_g = eg * rho_g / dt;
        const double rhs_g = a_g * ug0(i, j) - eg * rho_g * adv_g + eg * rho_g * gx - eg * dpdx;
        if (!bearing(i - 1, j, i, j)) {
          // No solids on one side: the solids velocity stays as extrapolated from the bed, the gas feels its drag.
          s_.ug(i, j) = (rhs_g + beta * us0(i, j)) / (a_g + beta);
          dgu(i, j) = eg / (a_g + beta);
          dsu(i, j) = 0.0;
          continue;
        }
        const double dpsdx = (p_s_(i, j) - p_s_(i - 1, j)) / dx;
        // Eq. 19 stress divergence; the Laplacian diagonal is taken implicitly (point-implicit) for stability.
        auto sxx = [&](int ci) {
          return 2.0 * mu_s_(ci, j) * (us0(ci + 1, j) - us0(ci, j)) / dx + lambda_s_(ci, j) * div_s(ci, j);
        };
        auto sxy = [&](int jc) {  // corner (i, jc); bottom and top are free-slip for the solids
          if (jc == 0 || jc == ny) return 0.0;
          return mu_corner(i, jc) * ((us0(i, jc) - us0(i, jc - 1)) / dy + (vs0(i, jc) - vs0(i - 1, jc)) / dx);
        };
        double diag = 2.0 * (mu_s_(i, j) + mu_s_(i - 1, j)) / (dx * dx);
        if (j > 0) diag += mu_corner(i, j) / (dy * dy);
        if (j < ny - 1) diag += mu_corner(i, j + 1) / (dy * dy);
        const double visc = (sxx(i) - sxx(i - 1)) / dx + (sxy(j + 1) - sxy(j)) / dy + diag * us0(i, j);
        const double adv_s = advect_u<Law>(us0, vs0, i, j, dx, dy);
        const double a_s = es * rho_s / dt;
        const double rhs_s = a_s * us0(i, j) - es * rho_s * adv_s + es * rho_s * gx - es * dpdx - dpsdx + visc;
        const FaceSolve f = solve_face(a_g, a_s + diag, beta, rhs_g, rhs_s, eg, es);
        s_.ug(i, j) = f.ug;
        s_.us(i, j) = f.us;
        dgu(i, j) = f.dg;
        dsu(i, j) = f.ds;
        gsu(i, j) = f.gs;
        ssu(i, j) = f.ss;
      }
    }
    // y-momentum on interior horizontal faces and, when open, the top face (ghost pressure keeps P = P_top there).
    for (int j = 1; j <= ny; ++j) {
      const bool top = j == ny;
      if (top && !top_open) break;
      for (int i = 0; i < nx; ++i) {
        const double eg = top ? eps(i, ny - 1) : 0.5 * (eps(i, j - 1) + eps(i, j));
        const double es = std::max(1.0 - eg, kEpsSFloor);
        const double beta = top ? beta_c_(i, ny - 1) : 0.5 * (beta_c_(i, j - 1) + beta_c_(i, j));
        const double p_above = top ? 2.0 * c.boundary.top_pressure - p(i, ny - 1) : p(i, j);
        const double dpdy = (p_above - p(i, j - 1)) / dy;
        const double adv_g = advect_v<Law>(ug0, vg0, i, j, dx, dy);
        const double a_g = eg * rho_g / dt;
        const double rhs_g = a_g * vg0(i, j) - eg * rho_g * adv_g + eg * rho_g * gy - eg * dpdy;
        if (top || !bearing(i, j - 1, i, j)) {
          // Solids cannot leave through the top; on a face with no solids on one side the solids velocity stays
          // as extrapolated from the bed. Only the gas row remains, with the drag of those solids.
          const double v_s = top ? 0.0 : vs0(i, j);
          s_.vg(i, j) = (rhs_g + beta * v_s) / (a_g + beta);
          dgv(i, j) = eg / (a_g + beta);
          s_.vs(i, j) = v_s;
          dsv(i, j) = 0.0;
          continue;
        }
        const double dpsdy = (p_s_(i, j) - p_s_(i, j - 1)) / dy;
        auto syy = [&](int cj) {
          return 2.0 * mu_s_(i, cj) * (vs0(i, cj + 1) - vs0(i, cj)) / dy + lambda_s_(i, cj) * div_s(i, cj);
        };
        double diag = 2.0 * (mu_s_(i, j) + mu_s_(i, j - 1)) / (dy * dy);
        auto sxy = [&](int ic) {  // corner (ic, j); side walls slip, or no-slip with the wall at dx/2
          if (ic == 0 || ic == nx) {
            const double mu_w = mu_wall * 0.5 * (mu_s_(ic == 0 ? 0 : nx - 1, j - 1) + mu_s_(ic == 0 ? 0 : nx - 1, j));
            const double v_in = vs0(ic == 0 ? 0 : nx - 1, j);
            return (ic == 0 ? 2.0 : -2.0) * mu_w * v_in / dx;
          }
          return mu_corner(ic, j) * ((us0(ic, j) - us0(ic, j - 1)) / dy + (vs0(ic, j) - vs0(ic - 1, j)) / dx);
        };
        for (int ic : {i, i + 1}) {
          if (ic == 0 || ic == nx) {
            diag += mu_wall * (mu_s_(ic == 0 ? 0 : nx - 1, j - 1) + mu_s_(ic == 0 ? 0 : nx - 1, j)) / (dx * dx);
          } else {
            diag += mu_corner(ic, j) / (dx * dx);
          }
        }
        const double visc = (syy(j) - syy(j - 1)) / dy + (sxy(i + 1) - sxy(i)) / dx + diag * vs0(i, j);
        const double adv_s = advect_v<Law>(us0, vs0, i, j, dx, dy);
        const double a_s = es * rho_s / dt;
        const double rhs_s = a_s * vs0(i, j) - es * rho_s * adv_s + es * rho_s * gy - es * dpdy - dpsdy + visc;
        const FaceSolve f = solve_face(a_g, a_s + diag, beta, rhs_g, rhs_s, eg, es);
        s_.vg(i, j) = f.ug;
        s_.vs(i, j) = f.us;
        dgv(i, j) = f.dg;
        dsv(i, j) = f.ds;
        gsv(i, j) = f.gs;
        ssv(i, j) = f.ss;
      }
    }
  });
  // Boundary faces: walls, inflow through the distributor, closed lid.
  for (int j = 0; j < ny; ++j) {
    s_.ug(0, j) = s_.ug(nx, j) = s_.us(0, j) = s_.us(nx, j) = 0.0;
  }
  for (int i = 0; i < nx; ++i) {
    s_.vg(i, 0) = inlet[static_cast<std::size_t>(i)];
    s_.vs(i, 0) = 0.0;
    s_.vs(i, ny) = 0.0;
    if (!top_open) s_.vg(i, ny) = 0.0;
  }

  // Correction step. Both phases are incompressible, so the mixture volume flux must be divergence-free
  // (Eqs. 15 + 16); that fixes the gas-pressure correction P'. The solids pressure is then made implicit by a
  // solids volume fraction correction E' (as in MFIX): the solids continuity (Eq. 16) must hold with
  // P_s + K E', K = dP_s/d eps_s, so the stiff compaction limit does not limit dt. A second P' solve (same
  // matrix) restores the mixture constraint after the E' correction. Face volume fractions are the TVD values
  // the continuity uses.
  Field2 eps_s(nx, ny), eg_x, eg_y, es_x, es_y;
  for (std::size_t k = 0; k < eps_s.size(); ++k) eps_s.v[k] = 1.0 - eps.v[k];
  tvd_face_values(grid_, c.limiter, eps, FaceVelocity{s_.ug, s_.vg, false}, eg_x, eg_y);
  tvd_face_values(grid_, c.limiter, eps_s, FaceVelocity{s_.us, s_.vs, false}, es_x, es_y);
  for (int i = 0; i < nx; ++i) eg_y(i, 0) = 1.0;  // gas enters through the distributor undiluted
  const int n = nx * ny;
  auto id = [&](int i, int j) { return static_cast<int>(grid_.index(i, j)); };
  // Net outflow of gas and of solids volume from every cell with the current face velocities.
  auto outflow = [&](Eigen::VectorXd& out_g, Eigen::VectorXd& out_s) {
    out_g.resize(n);
    out_s.resize(n);
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        out_g[id(i, j)] = dy * (eg_x(i + 1, j) * s_.ug(i + 1, j) - eg_x(i, j) * s_.ug(i, j)) +
                          dx * (eg_y(i, j + 1) * s_.vg(i, j + 1) - eg_y(i, j) * s_.vg(i, j));
        out_s[id(i, j)] = dy * (es_x(i + 1, j) * s_.us(i + 1, j) - es_x(i, j) * s_.us(i, j)) +
                          dx * (es_y(i, j + 1) * s_.vs(i, j + 1) - es_y(i, j) * s_.vs(i, j));
      }
    }
  };
  // Face coefficients of the P' equation for the shared pressure-correction solver (src/fluid): interior faces
  // couple neighbours; the open top couples to P' = 0 on the outlet face, half a cell above the centre.
  Field2 a_x(nx + 1, ny), a_y(nx, ny + 1), rhs_p(nx, ny), p_corr(nx, ny);
  for (int j = 0; j < ny; ++j) {
    for (int i = 1; i < nx; ++i) a_x(i, j) = dy / dx * (eg_x(i, j) * dgu(i, j) + es_x(i, j) * dsu(i, j));
  }
  for (int j = 1; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) a_y(i, j) = dx / dy * (eg_y(i, j) * dgv(i, j) + es_y(i, j) * dsv(i, j));
  }
  if (top_open) {
    for (int i = 0; i < nx; ++i) a_y(i, ny) = 2.0 * dx * eg_y(i, ny) * dgv(i, ny) / dy;
  }
  Eigen::VectorXd out_g, out_s;
  // The second call has the same coefficients: it reuses the first call's factorisation (one preconditioned CG
  // iteration with the exact factors) instead of factorising the same matrix again.
  auto correct_pressure = [&](bool same_matrix) {
    outflow(out_g, out_s);
    for (int k = 0; k < n; ++k) rhs_p.v[static_cast<std::size_t>(k)] = -(out_g[k] + out_s[k]);
    p_corr.fill(0.0);
    try {
      pressure_solver_.solve(a_x, a_y, rhs_p, p_corr, same_matrix);
    } catch (const Error& e) {
      throw_simulation_error(fmt::format(
          "tfm at t = {:.6g} s (step {}, dt = {:.3g} s): {} (mixture volume constraint, Eqs. 15 + 16). Likely cause: "
          "face velocities that are no longer finite (a solids stress or drag that overflowed). Remedy: {}",
          s_.time, s_.steps, dt, e.what(), remedy()));
    }
    const std::vector<double>& pc = p_corr.v;
    for (int j = 0; j < ny; ++j) {
      for (int i = 1; i < nx; ++i) {
        const double g = (pc[static_cast<std::size_t>(id(i, j))] - pc[static_cast<std::size_t>(id(i - 1, j))]) / dx;
        s_.ug(i, j) -= dgu(i, j) * g;
        s_.us(i, j) -= dsu(i, j) * g;
      }
    }
    for (int j = 1; j <= ny; ++j) {
      if (j == ny && !top_open) break;
      for (int i = 0; i < nx; ++i) {
        const double above = j == ny ? -p_corr(i, ny - 1) : p_corr(i, j);
        const double g = (above - p_corr(i, j - 1)) / dy;
        s_.vg(i, j) -= dgv(i, j) * g;
        s_.vs(i, j) -= dsv(i, j) * g;
      }
    }
    for (std::size_t k = 0; k < pc.size(); ++k) s_.p.v[k] += pc[k];
  };
  correct_pressure(false);

  // Solids volume fraction correction: (V/dt) E' - sum_faces es ss K grad E' = -(solids outflow). The matrix
  // is the Laplacian of the solids-pressure response times diag(K), plus V/dt; solved for W = K E' would be
  // symmetric, but K vanishes in dilute cells, so E' is the unknown.
  // Row of cell P: (V/dt + K_P sum_f a_f) E'_P - sum_f a_f K_nb E'_nb, with a_f the face's area / distance times
  // its solids flux response; written in place into the fixed five-point pattern.
  const double vol = dx * dy;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double aw = i > 0 ? dy / dx * es_x(i, j) * ssu(i, j) : 0.0;
      const double ae = i + 1 < nx ? dy / dx * es_x(i + 1, j) * ssu(i + 1, j) : 0.0;
      const double as = j > 0 ? dx / dy * es_y(i, j) * ssv(i, j) : 0.0;
      const double an = j + 1 < ny ? dx / dy * es_y(i, j + 1) * ssv(i, j + 1) : 0.0;
      const double kw = i > 0 ? dps_deps_(i - 1, j) : 0.0, ke = i + 1 < nx ? dps_deps_(i + 1, j) : 0.0;
      const double ks = j > 0 ? dps_deps_(i, j - 1) : 0.0, kn = j + 1 < ny ? dps_deps_(i, j + 1) : 0.0;
      e_matrix_.set_row(id(i, j), vol / dt + dps_deps_(i, j) * (aw + ae + as + an),
                        {-aw * kw, -ae * ke, -as * ks, -an * kn});
    }
  }
  outflow(out_g, out_s);
  solids_solver_.set_tolerance(1e-12);
  solids_solver_.set_max_iterations(c.linear_max_iterations);
  Eigen::VectorXd e_corr;
  const LinearSolveOutcome e_res = solids_solver_.solve(e_matrix_.matrix(), -out_s, e_corr);
  if (e_res.fell_back) ++linear_fallbacks_;
  if (!e_res.ok) {
    // Name the cell: the row that is not finite, else the stiffest cell (largest dP_s/d eps_s).
    int r = e_res.bad_row;
    if (r < 0) {
      r = static_cast<int>(std::max_element(dps_deps_.v.begin(), dps_deps_.v.end()) - dps_deps_.v.begin());
    }
    const int ci = r % nx, cj = r / nx;
    throw_simulation_error(fmt::format(
        "tfm at t = {:.6g} s (step {}, dt = {:.3g} s): the solids-fraction correction (implicit solids pressure, "
        "E' equation) failed: {}. At {}: voidage {:.4g}, solids pressure {:.4g} Pa, dP_s/d eps_s {:.4g} Pa, "
        "granular temperature {:.4g} m^2/s^2. Likely cause: a solids pressure that is not finite or too stiff for "
        "the step (a voidage far below eps*, or a runaway granular temperature). Remedy: {}",
        s_.time, s_.steps, dt, e_res.why, where(ci, cj), s_.eps(ci, cj), p_s_(ci, cj), dps_deps_(ci, cj),
        s_.theta(ci, cj), remedy()));
  }
  auto w = [&](int i, int j) { return dps_deps_(i, j) * e_corr[id(i, j)]; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 1; i < nx; ++i) {
      const double g = (w(i, j) - w(i - 1, j)) / dx;
      s_.ug(i, j) -= gsu(i, j) * g;
      s_.us(i, j) -= ssu(i, j) * g;
    }
  }
  for (int j = 1; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double g = (w(i, j) - w(i, j - 1)) / dy;
      s_.vg(i, j) -= gsv(i, j) * g;
      s_.vs(i, j) -= ssv(i, j) * g;
    }
  }
  correct_pressure(true);

  // Eq. 16, fully implicit with the limiter by deferred correction, as conservative face fluxes (per unit area).
  FaceFluxes fs;
  try {
    advance_scalar_implicit(grid_, c.limiter, eps_s, FaceVelocity{s_.us, s_.vs, false}, dt, c.mass_corrections, fs,
                            c.linear_max_iterations, &linear_fallbacks_);
  } catch (const Error& e) {
    throw_simulation_error(fmt::format("tfm at t = {:.6g} s (step {}, dt = {:.3g} s): {}. Remedy: {}", s_.time,
                                       s_.steps, dt, e.what(), remedy()));
  }
  const FaceFluxes fs_unlimited = fs;
  // Packing limit (docs/model-tfm.md): eps >= eps* - max_compaction exactly. The solids pressure stiffens the bed
  // only through a linearisation, so the bound is kept on the fluxes: inflows into a cell that would pass it are
  // scaled down (Zalesak-type one-sided limiter).
  packing_sweeps_ = limit_packing(grid_, eps_s, dt, 1.0 - (c.eps_star - packing_allowance(c)), fs).sweeps;
  const Field2 eps_s_new = conservative_update(grid_, eps_s, fs, dt);
  // Face velocities follow the fluxes the continuity used, so momentum sees what the continuity did: a limited
  // solids face is slowed by its factor; the gas carries the mixture flux that the pressure correction made
  // divergence-free (with its face fractions eg, es) minus the solids flux actually moved, so Eq. 15 with
  // eps = 1 - eps_s closes on every cell (the gas takes up the difference between the face fractions of the
  // correction and of the implicit continuity as well as the volume the limiter held back).
  FaceFluxes fs_corr{Field2(nx + 1, ny), Field2(nx, ny + 1)}, fg_shift{Field2(nx + 1, ny), Field2(nx, ny + 1)};
  for (std::size_t k = 0; k < fs.x.size(); ++k) fs_corr.x.v[k] = es_x.v[k] * s_.us.v[k];
  for (std::size_t k = 0; k < fs.y.size(); ++k) fs_corr.y.v[k] = es_y.v[k] * s_.vs.v[k];
  transfer_to_gas(fs_corr, fs, fg_shift);
  auto follow = [](double& us, double& ug, double f_old, double f_new, double shift, double eg) {
    if (f_new != f_old && f_old != 0.0) us *= f_new / f_old;
    if (shift != 0.0) ug += shift / eg;
  };
  for (std::size_t k = 0; k < fs.x.size(); ++k) {
    follow(s_.us.v[k], s_.ug.v[k], fs_unlimited.x.v[k], fs.x.v[k], fg_shift.x.v[k], eg_x.v[k]);
  }
  for (std::size_t k = 0; k < fs.y.size(); ++k) {
    follow(s_.vs.v[k], s_.vg.v[k], fs_unlimited.y.v[k], fs.y.v[k], fg_shift.y.v[k], eg_y.v[k]);
  }

  // Gas continuity residual of this step (Eq. 15 with the face voidages of the step), before eps is replaced.
  {
    double sum = 0.0;
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const double accumulation = dx * dy * ((1.0 - eps_s_new(i, j)) - eps(i, j)) / dt;
        const double out = dy * (eg_x(i + 1, j) * s_.ug(i + 1, j) - eg_x(i, j) * s_.ug(i, j)) +
                           dx * (eg_y(i, j + 1) * s_.vg(i, j + 1) - eg_y(i, j) * s_.vg(i, j));
        sum += std::abs(accumulation + out);
      }
    }
    // Normalised as the gas solver's mass residual (src/fluid/gas_solver.cpp), in volume rather than mass:
    // by the largest of the inlet flow, the largest gas face speed times the width, and a round-off floor.
    double inflow = 0.0, speed = 0.0;
    for (int i = 0; i < nx; ++i) inflow += dx * s_.vg(i, 0);
    for (double x : s_.ug.v) speed = std::max(speed, std::abs(x));
    for (double x : s_.vg.v) speed = std::max(speed, std::abs(x));
    const double width = grid_.width();
    const double v_floor = std::max(1e-12, 1e-6 * std::sqrt(std::hypot(gx, gy) * grid_.height()));
    s_.gas_residual = sum / std::max({std::abs(inflow), speed * width, v_floor * width});
  }

  // eps = 1 - eps_s closes Eq. 15.
  double dense_change = 0.0;
  for (std::size_t k = 0; k < eps_s_new.size(); ++k) {
    const double eps_new = 1.0 - eps_s_new.v[k];
    // Only compaction below eps* matters: that is where the solids pressure stiffens exponentially.
    if (eps_new < c.eps_star) dense_change = std::max(dense_change, s_.eps.v[k] - eps_new);
    s_.eps.v[k] = eps_new;
  }

  s_.time += dt;
  // A step clipped to reach t_stop says little about the natural step; keep the rate of a full one.
  if (dt >= 0.5 * s_.dt || s_.steps == 0) {
    s_.dt = dt;
    s_.dense_change = dense_change;
  }
  ++s_.steps;
  check_health(dt);
  return dt;
}

double TfmSolver::reference_speed() const {
  const GasBoundaryConfig& b = config_.boundary;
  double u_in = std::max(std::abs(b.inlet_velocity), std::abs(b.ramp_from)) * (1.0 + b.inlet_noise);
  for (const InletJet& j : b.jets) u_in = std::max(u_in, std::abs(j.velocity));
  return u_in / config_.eps_star + std::sqrt(2.0 * std::hypot(config_.gravity.x, config_.gravity.y) * grid_.height());
}

std::string TfmSolver::where(int i, int j) const {
  return fmt::format("cell ({}, {}) at x = {:.3f} m, y = {:.3f} m", i, j, (i + 0.5) * grid_.dx, (j + 0.5) * grid_.dy);
}

std::string TfmSolver::remedy() const {
  std::string r;
  if (config_.rheology == SolidsRheology::KineticTheory && config_.e > 0.95) {
    r = fmt::format("lower tfm.restitution (now {:g}; the paper: 0.9): nearly elastic particles dissipate almost no "
                    "granular energy (K4 ~ 1 - e^2, Eq. 25), so Theta and the solids pressure grow with the shear, "
                    "and a smaller time step does not cure it; otherwise ", config_.e);
  }
  return r + fmt::format("lower tfm.cfl (now {:g}) or tfm.dt_max (now {:g} s), and check the inlet and jet velocities "
                         "against the bed's minimum fluidization velocity", config_.cfl, config_.dt_max);
}

void TfmSolver::check_health(double dt) const {
  const int nx = grid_.nx, ny = grid_.ny;
  const double t = s_.time;
  auto fail = [&](const std::string& what, int i, int j, const std::string& cause) {
    throw_simulation_error(fmt::format("tfm: the run went bad at t = {:.6g} s (step {}, dt = {:.3g} s): {} in {}. "
                                       "Likely cause: {}. Remedy: {}",
                                       t, s_.steps, dt, what, where(i, j), cause, remedy()));
  };
  const char* overflow = "a solids pressure or viscosity that overflowed, or a linear solve fed with such values";
  // The deferred TVD correction of the implicit continuity undershoots a little at the bed surface (solids
  // fractions down to -1e-5 in the paper's case); below the trace level that carries no momentum it is a defect.
  constexpr double kVoidageSlack = kEpsSTrace;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double e = s_.eps(i, j);
      if (!std::isfinite(e) || !std::isfinite(s_.p(i, j)) || !std::isfinite(s_.theta(i, j))) {
        fail(fmt::format("a non-finite value (voidage {}, pressure {}, granular temperature {})", e, s_.p(i, j),
                         s_.theta(i, j)), i, j, overflow);
      }
      if (e < -kVoidageSlack || e > 1.0 + kVoidageSlack) {
        fail(fmt::format("the voidage is {:.9g}, outside [0, 1]", e), i, j,
             "a solids flux out of a cell larger than its content: the time step outran the solids velocity");
      }
    }
  }
  const double v_ref = reference_speed();
  const double v_gas_max = 10.0 * v_ref;
  auto faces = [&](const Field2& g, const Field2& sol, bool vertical) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const double ug = g(i, j), us = sol(i, j);
        // The cell on the inner side of the face (clamped at the boundaries).
        const int ci = vertical ? std::min(i, nx - 1) : i, cj = vertical ? j : std::min(j, ny - 1);
        if (!std::isfinite(ug) || !std::isfinite(us)) {
          fail(fmt::format("a non-finite face velocity (gas {}, solids {} m/s)", ug, us), ci, cj, overflow);
        }
        const int i0 = vertical ? clampi(i - 1, 0, nx - 1) : i, j0 = vertical ? j : clampi(j - 1, 0, ny - 1);
        const bool carries = std::min(1.0 - s_.eps(i0, j0), 1.0 - s_.eps(ci, cj)) > kEpsSTrace;
        if (carries && std::abs(us) > v_ref) {
          fail(fmt::format("the solids move at {:.4g} m/s, faster than anything that drives them ({:.3g} m/s: the "
                           "fastest interstitial inflow plus free fall over the domain height)", std::abs(us), v_ref),
               ci, cj, "an instability of the solids momentum");
        }
        if (std::abs(ug) > v_gas_max) {
          fail(fmt::format("the gas moves at {:.4g} m/s, ten times the fastest interstitial inflow plus free fall "
                           "({:.3g} m/s)", std::abs(ug), v_ref), ci, cj,
               "an instability of the coupled gas-solids momentum");
        }
      }
    }
  };
  faces(s_.ug, s_.us, true);
  faces(s_.vg, s_.vs, false);
  // Theta is the mean square fluctuation velocity per direction: its root cannot exceed the speed scale either.
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (1.0 - s_.eps(i, j) < kBedSolidsFraction) continue;
      if (s_.theta(i, j) > v_ref * v_ref) {
        fail(fmt::format("the granular temperature is {:.4g} m^2/s^2 (fluctuation speed {:.4g} m/s, above the {:.3g} "
                         "m/s that drives the bed) at solids fraction {:.3g}",
                         s_.theta(i, j), std::sqrt(s_.theta(i, j)), v_ref, 1.0 - s_.eps(i, j)),
             i, j, "a runaway granular temperature: production by shear outgrows the collisional dissipation");
      }
    }
  }
}

double TfmSolver::bed_granular_temperature_max() const {
  double m = 0.0;
  for (std::size_t k = 0; k < s_.eps.size(); ++k) {
    if (1.0 - s_.eps.v[k] >= kBedSolidsFraction) m = std::max(m, s_.theta.v[k]);
  }
  return m;
}

double TfmSolver::solids_mean_granular_temperature() const {
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k < s_.eps.size(); ++k) {
    const double es = 1.0 - s_.eps.v[k];
    num += es * s_.theta.v[k];
    den += es;
  }
  return den > 0.0 ? num / den : 0.0;
}

void TfmSolver::advance_to(double t) {
  // Stop within a rounding distance of t instead of taking a vanishing last step.
  while (t - s_.time > 1e-12 * std::max(1.0, std::abs(t))) step(t);
}

double TfmSolver::solids_mass() const {
  double sum = 0.0;
  for (double e : s_.eps.v) sum += 1.0 - e;
  return sum * config_.rho_s * grid_.dx * grid_.dy;
}

double TfmSolver::pressure_drop() const {
  double sum = 0.0;
  const int ny = grid_.ny;
  for (int i = 0; i < grid_.nx; ++i) {
    sum += ny > 1 ? 1.5 * s_.p(i, 0) - 0.5 * s_.p(i, 1) : s_.p(i, 0);
  }
  const double top = (config_.boundary.top == TopBoundary::PressureOutlet) ? config_.boundary.top_pressure : 0.0;
  return sum / grid_.nx - top;
}

double TfmSolver::contents_weight_per_area() const {
  double sum = 0.0;
  for (double e : s_.eps.v) sum += e * config_.rho_g + (1.0 - e) * config_.rho_s;
  return sum * grid_.dx * grid_.dy * std::abs(config_.gravity.y) / grid_.width();
}

double TfmSolver::max_solids_speed() const {
  const int nx = grid_.nx, ny = grid_.ny;
  double vmax = 0.0;
  const Field2& e = s_.eps;
  for (int j = 0; j < ny; ++j) {
    for (int i = 1; i < nx; ++i) {
      if (std::min(1.0 - e(i - 1, j), 1.0 - e(i, j)) > 1e-6) vmax = std::max(vmax, std::abs(s_.us(i, j)));
    }
  }
  for (int j = 1; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (std::min(1.0 - e(i, j - 1), 1.0 - e(i, j)) > 1e-6) vmax = std::max(vmax, std::abs(s_.vs(i, j)));
    }
  }
  return vmax;
}

double TfmSolver::min_voidage() const { return *std::min_element(s_.eps.v.begin(), s_.eps.v.end()); }

void TfmSolver::gas_velocity_cells(Field2& u, Field2& v) const {
  u = Field2(grid_.nx, grid_.ny);
  v = Field2(grid_.nx, grid_.ny);
  for (int j = 0; j < grid_.ny; ++j) {
    for (int i = 0; i < grid_.nx; ++i) {
      u(i, j) = 0.5 * (s_.ug(i, j) + s_.ug(i + 1, j));
      v(i, j) = 0.5 * (vg_interstitial(i, j) + s_.vg(i, j + 1));
    }
  }
}

void TfmSolver::solids_velocity_cells(Field2& u, Field2& v) const {
  u = Field2(grid_.nx, grid_.ny);
  v = Field2(grid_.nx, grid_.ny);
  for (int j = 0; j < grid_.ny; ++j) {
    for (int i = 0; i < grid_.nx; ++i) {
      u(i, j) = 0.5 * (s_.us(i, j) + s_.us(i + 1, j));
      v(i, j) = 0.5 * (s_.vs(i, j) + s_.vs(i, j + 1));
    }
  }
}

std::vector<NamedArray> TfmSolver::save_state() const {
  auto arr = [](const char* name, const Field2& f) { return NamedArray{name, f.nx, f.ny, f.v}; };
  return {arr("eps", s_.eps),
          arr("p", s_.p),
          arr("ug", s_.ug),
          arr("vg", s_.vg),
          arr("us", s_.us),
          arr("vs", s_.vs),
          arr("theta", s_.theta),
          NamedArray{"time", 1, 1, {s_.time}},
          NamedArray{"dt", 1, 1, {s_.dt}},
          NamedArray{"steps", 1, 1, {static_cast<double>(s_.steps)}},
          NamedArray{"dense_change", 1, 1, {s_.dense_change}},
          NamedArray{"gas_residual", 1, 1, {s_.gas_residual}}};
}

void TfmSolver::restore_state(const std::vector<NamedArray>& arrays) {
  TfmState next = s_;
  auto find = [&](const char* name, int nx, int ny) -> const NamedArray& {
    for (const NamedArray& a : arrays) {
      if (a.name != name) continue;
      if (a.nx != nx || a.ny != ny || a.values.size() != static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny)) {
        throw_input_error(std::string("tfm restart: array '") + name + "' does not match the grid");
      }
      return a;
    }
    throw_input_error(std::string("tfm restart: array '") + name + "' is missing");
  };
  auto load = [&](const char* name, Field2& f) { f.v = find(name, f.nx, f.ny).values; };
  load("eps", next.eps);
  load("p", next.p);
  load("ug", next.ug);
  load("vg", next.vg);
  load("us", next.us);
  load("vs", next.vs);
  load("theta", next.theta);
  next.time = find("time", 1, 1).values[0];
  next.dt = find("dt", 1, 1).values[0];
  next.steps = static_cast<long>(find("steps", 1, 1).values[0]);
  next.dense_change = find("dense_change", 1, 1).values[0];
  // Monitor only, and absent from checkpoints written before it existed: optional.
  next.gas_residual = 0.0;
  for (const NamedArray& a : arrays) {
    if (a.name == "gas_residual" && a.values.size() == 1) next.gas_residual = a.values[0];
  }
  s_ = std::move(next);
}

}  // namespace fluidbed::tfm
