#include "fluid/gas_solver.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "core/error.hpp"
#include "fluid/stencil_matrix.hpp"

namespace fluidbed {

namespace {

enum class Comp { U, V };

double limiter(ConvectionScheme scheme, double r) {
  switch (scheme) {
    case ConvectionScheme::VanLeer:
      return (r + std::abs(r)) / (1.0 + std::abs(r));
    case ConvectionScheme::Minmod:
      return std::max(0.0, std::min(1.0, r));
    case ConvectionScheme::Upwind:
      break;
  }
  return 0.0;
}

// TVD face value minus the upwind one (Sweby 1984 form, r = upwind gradient ratio), added by deferred correction.
double high_order_correction(ConvectionScheme scheme, double phi_far, double phi_up, double phi_down) {
  const double jump = phi_down - phi_up;
  if (jump == 0.0) return 0.0;
  return 0.5 * limiter(scheme, (phi_up - phi_far) / jump) * jump;
}

struct Momentum {
  std::vector<int> id;                    // unknown number per face of the component's array, -1 if fixed
  std::vector<std::array<int, 2>> where;  // (along, across) index of each unknown
  StencilMatrix a;
  Eigen::VectorXd rhs;
  Eigen::VectorXd x;
  Field2 d;  // velocity change per unit pressure-correction difference, per face
  CheckedSparseSolver solver;  // BiCGSTAB, a sparse LU when it stops short of the tolerance
};

}  // namespace

struct GasSolver::Impl {
  Grid2 grid;
  GasConfig cfg;
  StaggeredFields f;
  PressureCorrectionSolver pressure;
  Momentum mom_u;
  Momentum mom_v;
  bool outlet = false;
  // Per-step face data and work arrays.
  Field2 epsx, epsy, epsx_old, epsy_old, betax, betay, usx, vsy, mx, my, u_old, v_old, ax, ay, imbalance, p_corr;
  Field2 eps_cell;
  std::vector<double> inlet;

  Impl(const Grid2& g, const GasConfig& c, PressureSolverKind kind) : grid(g), cfg(c), pressure(g, kind) {}

  template <Comp C>
  void setup(Momentum& m);
  template <Comp C>
  void solve_momentum(Momentum& m, double dt);
  int linear_fallbacks = 0;  // momentum solves of the current step answered by the LU
  void mass_fluxes();
  double continuity(const Field2& eps_old, const Field2& eps_new, double dt);  // sum |imbalance|
  double reference_mass_flow() const;
};

template <Comp C>
void GasSolver::Impl::setup(Momentum& m) {
  const int nx = grid.nx;
  const int ny = grid.ny;
  const int n_al = C == Comp::U ? nx : ny;
  const int n_ac = C == Comp::U ? ny : nx;
  const int faces_al = n_al + 1;
  m.id.assign(static_cast<std::size_t>(faces_al) * static_cast<std::size_t>(n_ac), -1);
  m.where.clear();
  const auto idx = [&](int a, int b) { return static_cast<std::size_t>(b) * faces_al + static_cast<std::size_t>(a); };
  const bool top_unknown = C == Comp::V && outlet;
  for (int b = 0; b < n_ac; ++b)
    for (int a = 1; a <= n_al; ++a) {
      if (a == n_al && !top_unknown) continue;
      m.id[idx(a, b)] = static_cast<int>(m.where.size());
      m.where.push_back({a, b});
    }
  const int n = static_cast<int>(m.where.size());
  std::vector<std::array<int, 4>> nb(static_cast<std::size_t>(n));
  const auto get = [&](int a, int b) { return (a < 0 || a > n_al || b < 0 || b >= n_ac) ? -1 : m.id[idx(a, b)]; };
  for (int r = 0; r < n; ++r) {
    const int a = m.where[static_cast<std::size_t>(r)][0];
      const int b = m.where[static_cast<std::size_t>(r)][1];
    nb[static_cast<std::size_t>(r)] = {get(a - 1, b), get(a + 1, b), get(a, b - 1), get(a, b + 1)};
    if (a == n_al) nb[static_cast<std::size_t>(r)] = {get(a - 1, b), -1, -1, -1};  // outlet half cell
  }
  m.a.build(n, nb);
  m.rhs.resize(n);
  m.x.resize(n);
  m.d = C == Comp::U ? Field2(nx + 1, ny) : Field2(nx, ny + 1);
  m.solver.set_tolerance(cfg.momentum_solver_tolerance);
  m.solver.set_max_iterations(cfg.momentum_solver_max_iterations);
}

void GasSolver::Impl::mass_fluxes() {
  const int nx = grid.nx;
  const int ny = grid.ny;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i) mx(i, j) = cfg.rho_g * epsx(i, j) * f.u(i, j) * grid.dy;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < nx; ++i) my(i, j) = cfg.rho_g * epsy(i, j) * f.v(i, j) * grid.dx;
}

double GasSolver::Impl::continuity(const Field2& eps_old, const Field2& eps_new, double dt) {
  const int nx = grid.nx;
  const int ny = grid.ny;
  const double vol = grid.dx * grid.dy;
  std::vector<double> row_sum(static_cast<std::size_t>(ny), 0.0);
#pragma omp parallel for schedule(static) if (nx * ny >= kParallelCells)
  for (int j = 0; j < ny; ++j) {
    double s = 0.0;
    for (int i = 0; i < nx; ++i) {
      // Eq. 11 integrated over the cell: accumulation plus net outflow.
      const double r = cfg.rho_g * (eps_new(i, j) - eps_old(i, j)) * vol / dt + mx(i + 1, j) - mx(i, j) +
                       my(i, j + 1) - my(i, j);
      imbalance(i, j) = r;
      s += std::abs(r);
    }
    row_sum[static_cast<std::size_t>(j)] = s;
  }
  double total = 0.0;
  for (double s : row_sum) total += s;  // fixed order: independent of the thread count
  return total;
}

double GasSolver::Impl::reference_mass_flow() const {
  double m_in = 0.0;
  for (int i = 0; i < grid.nx; ++i) m_in += my(i, 0);
  double speed = std::abs(cfg.boundary.lid_velocity);
  for (double x : f.u.v) speed = std::max(speed, std::abs(x));
  for (double x : f.v.v) speed = std::max(speed, std::abs(x));
  const double width = grid.width();
  // With the gas at rest the reference must not fall below the round-off of the velocities, or SIMPLE can never
  // meet the tolerance: floor it at a micro-fraction of the free-fall speed over the domain height.
  const double v_floor = std::max(1e-12, 1e-6 * std::sqrt(std::hypot(cfg.gravity.x, cfg.gravity.y) * grid.height()));
  return std::max({std::abs(m_in), cfg.rho_g * speed * width, cfg.rho_g * v_floor * width});
}

template <Comp C>
void GasSolver::Impl::solve_momentum(Momentum& m, double dt) {
  const int nx = grid.nx;
  const int ny = grid.ny;
  const int n_al = C == Comp::U ? nx : ny;
  const int n_ac = C == Comp::U ? ny : nx;
  const double h_al = C == Comp::U ? grid.dx : grid.dy;
  const double h_ac = C == Comp::U ? grid.dy : grid.dx;
  const double g_c = C == Comp::U ? cfg.gravity.x : cfg.gravity.y;
  const double rho = cfg.rho_g;
  const double mu = cfg.viscous == ViscousStress::Off ? 0.0 : cfg.mu_g;
  const double alpha = cfg.relax_velocity;
  const GasBoundaryConfig& bc = cfg.boundary;
  Field2& phi_field = C == Comp::U ? f.u : f.v;
  const Field2& phi_old = C == Comp::U ? u_old : v_old;
  const Field2& eps_f = C == Comp::U ? epsx : epsy;
  const Field2& eps_f_old = C == Comp::U ? epsx_old : epsy_old;
  const Field2& beta_f = C == Comp::U ? betax : betay;
  const Field2& us_f = C == Comp::U ? usx : vsy;
  // (along, across) addressing of face arrays, cell arrays and the two mass-flux arrays.
  const auto face = [&](const Field2& fld, int a, int b) { return C == Comp::U ? fld(a, b) : fld(b, a); };
  const auto cell = [&](const Field2& fld, int c, int b) { return C == Comp::U ? fld(c, b) : fld(b, c); };
  const auto m_al = [&](int a, int b) { return C == Comp::U ? mx(a, b) : my(b, a); };
  const auto m_ac = [&](int c, int k) { return C == Comp::U ? my(c, k) : mx(k, c); };
  const auto pres = [&](int c, int b) { return C == Comp::U ? f.p(c, b) : f.p(b, c); };
  const auto phi = [&](int a, int b) { return face(phi_field, a, b); };
  // The other velocity component at (along cell c, across face k).
  const auto other = [&](int c, int k) { return C == Comp::U ? f.v(c, k) : f.u(k, c); };
  const bool full_stress = cfg.viscous == ViscousStress::Full;
  const auto fixed = [&](int a, int b) {
    return m.id[static_cast<std::size_t>(b) * static_cast<std::size_t>(n_al + 1) + static_cast<std::size_t>(a)] < 0;
  };
  // Across-boundary walls: tangential kind and speed. The top of U may be an outlet (zero gradient: no term).
  const bool low_noslip = (C == Comp::U ? bc.bottom_wall : bc.side_walls) == WallKind::NoSlip;
  const bool high_is_wall = C == Comp::V || bc.top == TopBoundary::Wall;
  const bool high_noslip = C == Comp::U ? (bc.top == TopBoundary::Wall && bc.top_wall == WallKind::NoSlip)
                                        : bc.side_walls == WallKind::NoSlip;
  const double high_speed = C == Comp::U ? bc.lid_velocity : 0.0;
  const ConvectionScheme scheme = cfg.convection;
  const int n = static_cast<int>(m.where.size());

#pragma omp parallel for schedule(static) if (nx * ny >= kParallelCells)
  for (int r = 0; r < n; ++r) {
    const int a = m.where[static_cast<std::size_t>(r)][0];
      const int b = m.where[static_cast<std::size_t>(r)][1];
    const bool half = a == n_al;  // outlet face: half control volume inside the domain
    const double vol = h_al * h_ac * (half ? 0.5 : 1.0);
    const double ef = face(eps_f, a, b);
    double b_src = 0.0;
    double sum_nb = 0.0;
    double sum_unknown_nb = 0.0;
    std::array<double, 4> off{0.0, 0.0, 0.0, 0.0};
    // neighbour k: coefficient, and its value when it is fixed
    const auto add = [&](int slot, int an, int bn, double coeff) {
      sum_nb += coeff;
      if (fixed(an, bn)) {
        b_src += coeff * phi(an, bn);
      } else {
        off[static_cast<std::size_t>(slot)] = -coeff;
        sum_unknown_nb += coeff;
      }
    };
    // Along the component: faces at the cell centres a-1 (minus) and a (plus).
    {
      const double fm = 0.5 * (m_al(a - 1, b) + m_al(a, b));
      const double dm = mu * cell(eps_cell, a - 1, b) * h_ac / h_al;
      add(0, a - 1, b, dm + std::max(fm, 0.0));
      if (scheme != ConvectionScheme::Upwind && !half) {
        const bool fwd = fm > 0.0;
        const int far = fwd ? a - 2 : a + 1;
        if (far >= 0 && far <= n_al) {
          const double c = fwd ? high_order_correction(scheme, phi(far, b), phi(a - 1, b), phi(a, b))
                               : high_order_correction(scheme, phi(far, b), phi(a, b), phi(a - 1, b));
          b_src += fm * c;
        }
      }
    }
    if (!half) {
      const double fp = 0.5 * (m_al(a, b) + m_al(a + 1, b));
      const double dp = mu * cell(eps_cell, a, b) * h_ac / h_al;
      add(1, a + 1, b, dp + std::max(-fp, 0.0));
      if (scheme != ConvectionScheme::Upwind) {
        const bool fwd = fp > 0.0;
        const int far = fwd ? a - 1 : a + 2;
        if (far >= 0 && far <= n_al) {
          const double c = fwd ? high_order_correction(scheme, phi(far, b), phi(a, b), phi(a + 1, b))
                               : high_order_correction(scheme, phi(far, b), phi(a + 1, b), phi(a, b));
          b_src -= fp * c;
        }
      }
      // Across the component: faces at the corners b -/+ 1/2.
      const double fs = 0.5 * (m_ac(a - 1, b) + m_ac(a, b));
      if (b > 0) {
        const double e_corner = 0.25 * (cell(eps_cell, a - 1, b) + cell(eps_cell, a, b) + cell(eps_cell, a - 1, b - 1) +
                                        cell(eps_cell, a, b - 1));
        add(2, a, b - 1, mu * e_corner * h_al / h_ac + std::max(fs, 0.0));
        if (scheme != ConvectionScheme::Upwind) {
          const bool fwd = fs > 0.0;
          const int far = fwd ? b - 2 : b + 1;
          if (far >= 0 && far < n_ac) {
            const double c = fwd ? high_order_correction(scheme, phi(a, far), phi(a, b - 1), phi(a, b))
                                 : high_order_correction(scheme, phi(a, far), phi(a, b), phi(a, b - 1));
            b_src += fs * c;
          }
        }
      } else {
        // Low across boundary: inflow (bottom inlet) brings no tangential momentum; wall friction if no-slip.
        const double coeff = std::max(fs, 0.0) + (low_noslip ? mu * ef * h_al / (0.5 * h_ac) : 0.0);
        sum_nb += coeff;
      }
      const double fn = 0.5 * (m_ac(a - 1, b + 1) + m_ac(a, b + 1));
      if (b < n_ac - 1) {
        const double e_corner = 0.25 * (cell(eps_cell, a - 1, b) + cell(eps_cell, a, b) + cell(eps_cell, a - 1, b + 1) +
                                        cell(eps_cell, a, b + 1));
        add(3, a, b + 1, mu * e_corner * h_al / h_ac + std::max(-fn, 0.0));
        if (scheme != ConvectionScheme::Upwind) {
          const bool fwd = fn > 0.0;
          const int far = fwd ? b - 1 : b + 2;
          if (far >= 0 && far < n_ac) {
            const double c = fwd ? high_order_correction(scheme, phi(a, far), phi(a, b), phi(a, b + 1))
                                 : high_order_correction(scheme, phi(a, far), phi(a, b + 1), phi(a, b));
            b_src -= fn * c;
          }
        }
      } else if (high_is_wall && high_noslip) {
        const double coeff = mu * ef * h_al / (0.5 * h_ac);
        sum_nb += coeff;
        b_src += coeff * high_speed;
      }
      if (full_stress) {
        // Transpose part of the stress, div(eps mu (grad u)^T), lagged (deferred) from the current iterate:
        // along faces eps mu d(phi)/d(along), across faces eps mu d(other)/d(along). Zero at slip walls and outlets.
        b_src += mu * h_ac / h_al *
                 (cell(eps_cell, a, b) * (phi(a + 1, b) - phi(a, b)) -
                  cell(eps_cell, a - 1, b) * (phi(a, b) - phi(a - 1, b)));
        const auto corner_eps = [&](int k) {
          if (k > 0 && k < n_ac)
            return 0.25 * (cell(eps_cell, a - 1, k - 1) + cell(eps_cell, a, k - 1) + cell(eps_cell, a - 1, k) +
                           cell(eps_cell, a, k));
          return ef;
        };
        const bool low_open = b > 0 || low_noslip;
        const bool high_open = b < n_ac - 1 || (high_is_wall && high_noslip);
        if (high_open) b_src += mu * corner_eps(b + 1) * (other(a, b + 1) - other(a - 1, b + 1));
        if (low_open) b_src -= mu * corner_eps(b) * (other(a, b) - other(a - 1, b));
      }
    }
    // Eq. 12: backward Euler in the non-conservative form (continuity subtracted), implicit drag, gravity, pressure.
    const double ap0 = rho * face(eps_f_old, a, b) * vol / dt;
    const double drag = face(beta_f, a, b) * vol;
    const double ap = ap0 + sum_nb + drag;
    const double ap_relaxed = ap / alpha;
    const double area = ef * h_ac;  // pressure force per unit pressure difference
    const double p_low = pres(a - 1, b);
    const double p_high = half ? bc.top_pressure : pres(a, b);
    b_src += ap0 * face(phi_old, a, b) + drag * face(us_f, a, b) + rho * ef * g_c * vol + area * (p_low - p_high) +
             (ap_relaxed - ap) * phi(a, b);
    m.a.set_row(r, ap_relaxed, off);
    m.rhs[r] = b_src;
    m.x[r] = phi(a, b);
    const double denom = cfg.coupling == PressureCoupling::Simplec ? ap_relaxed - sum_unknown_nb : ap_relaxed;
    (C == Comp::U ? m.d(a, b) : m.d(b, a)) = area / denom;
  }
  Eigen::VectorXd sol = m.x;
  const LinearSolveOutcome res = m.solver.solve(m.a.matrix(), m.rhs, sol);
  if (res.fell_back) ++linear_fallbacks;
  if (!res.ok) {
    std::string at;
    if (res.bad_row >= 0) {
      const auto& w = m.where[static_cast<std::size_t>(res.bad_row)];
      at = fmt::format(" at the {} face ({}, {})", C == Comp::U ? "u" : "v", C == Comp::U ? w[0] : w[1],
                       C == Comp::U ? w[1] : w[0]);
    }
    throw_simulation_error(fmt::format("gas {} momentum: linear solve failed{}: {}", C == Comp::U ? "u" : "v", at, res.why));
  }
  for (int r = 0; r < n; ++r) {
    const int a = m.where[static_cast<std::size_t>(r)][0];
      const int b = m.where[static_cast<std::size_t>(r)][1];
    (C == Comp::U ? phi_field(a, b) : phi_field(b, a)) = sol[r];
  }
}

GasSolver::GasSolver(const Grid2& grid, const GasConfig& config, PressureSolverKind pressure_solver)
    : impl_(std::make_unique<Impl>(grid, config, pressure_solver)) {
  validate(config);
  if (grid.nx < 2 || grid.ny < 2 || !(grid.dx > 0.0) || !(grid.dy > 0.0))
    throw_input_error("gas: the grid needs at least 2 x 2 cells of positive size");
  Impl& s = *impl_;
  s.outlet = config.boundary.top == TopBoundary::PressureOutlet;
  s.f = StaggeredFields::zeros(grid);
  s.setup<Comp::U>(s.mom_u);
  s.setup<Comp::V>(s.mom_v);
  const int nx = grid.nx;
  const int ny = grid.ny;
  s.mx = Field2(nx + 1, ny);
  s.my = Field2(nx, ny + 1);
  s.ax = Field2(nx + 1, ny);
  s.ay = Field2(nx, ny + 1);
  s.imbalance = Field2(nx, ny);
  s.p_corr = Field2(nx, ny);
}

GasSolver::~GasSolver() = default;
GasSolver::GasSolver(GasSolver&&) noexcept = default;
GasSolver& GasSolver::operator=(GasSolver&&) noexcept = default;

GasStepReport GasSolver::advance(double t_new, double dt, const Field2& eps_old, const Field2& eps_new,
                                 const Field2& beta, const Field2& us, const Field2& vs) {
  Impl& s = *impl_;
  const Grid2& g = s.grid;
  const int nx = g.nx;
  const int ny = g.ny;
  for (const Field2* fld : {&eps_old, &eps_new, &beta, &us, &vs}) {
    if (fld->nx != nx || fld->ny != ny) throw_input_error("gas advance: cell fields must be nx x ny");
  }
  if (!(dt > 0.0)) throw_input_error("gas advance: dt must be positive");
  for (std::size_t k = 0; k < eps_new.size(); ++k) {
    // eps divides the inlet flux and scales every control volume; beta < 0 would make the drag anti-dissipative.
    if (!(eps_new.v[k] > 0.0 && eps_new.v[k] <= 1.0) || !(eps_old.v[k] > 0.0 && eps_old.v[k] <= 1.0) ||
        !(beta.v[k] >= 0.0) || !std::isfinite(beta.v[k]) || !std::isfinite(us.v[k]) || !std::isfinite(vs.v[k])) {
      throw_simulation_error(fmt::format(
          "gas advance at t = {:.6g} s: cell ({}, {}) has eps_old = {:.4g}, eps_new = {:.4g}, beta = {:.4g}, "
          "solids velocity ({:.4g}, {:.4g}); need 0 < eps <= 1, beta >= 0 and finite values",
          t_new, k % static_cast<std::size_t>(nx), k / static_cast<std::size_t>(nx), eps_old.v[k], eps_new.v[k],
          beta.v[k], us.v[k], vs.v[k]));
    }
  }
  const GasConfig& cfg = s.cfg;
  s.eps_cell = eps_new;
  cell_to_u_faces(eps_new, s.epsx);
  cell_to_v_faces(eps_new, s.epsy);
  cell_to_u_faces(eps_old, s.epsx_old);
  cell_to_v_faces(eps_old, s.epsy_old);
  cell_to_u_faces(beta, s.betax);
  cell_to_v_faces(beta, s.betay);
  cell_to_u_faces(us, s.usx);
  cell_to_v_faces(vs, s.vsy);
  s.u_old = s.f.u;
  s.v_old = s.f.v;
  // Boundary values: walls, and the inlet's superficial velocity turned into the interstitial face velocity.
  for (int j = 0; j < ny; ++j) {
    s.f.u(0, j) = 0.0;
    s.f.u(nx, j) = 0.0;
  }
  inlet_superficial_profile(cfg.boundary, g, t_new - 0.5 * dt, s.inlet);
  for (int i = 0; i < nx; ++i) {
    s.f.v(i, 0) = s.inlet[static_cast<std::size_t>(i)] / eps_new(i, 0);
    if (!s.outlet) s.f.v(i, ny) = 0.0;
  }

  GasStepReport rep;
  s.linear_fallbacks = 0;
  bool converged = false;
  double residual = 0.0;
  double m_ref = 0.0;
  for (int it = 1; it <= cfg.max_simple_iterations; ++it) {
    s.mass_fluxes();
    try {
      s.solve_momentum<Comp::U>(s.mom_u, dt);
      s.solve_momentum<Comp::V>(s.mom_v, dt);
    } catch (const Error& e) {
      throw_simulation_error(fmt::format(
          "gas at t = {:.6g} s (dt = {:.3g} s), SIMPLE iteration {}: {}. Likely cause: an inflow or a drag too strong "
          "for the time step; remedy: reduce the time step, check the inlet and jet velocities",
          t_new, dt, it, e.what()));
    }
    s.mass_fluxes();
    const double abs_imbalance = s.continuity(eps_old, eps_new, dt);
    m_ref = s.reference_mass_flow();
    residual = abs_imbalance / m_ref;
    rep.simple_iterations = it;
    converged = residual < cfg.mass_tolerance;
    // Pressure correction (SIMPLE): face coefficients rho eps A d, p' = 0 beyond the outlet.
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i <= nx; ++i) s.ax(i, j) = cfg.rho_g * s.epsx(i, j) * g.dy * s.mom_u.d(i, j);
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i) s.ay(i, j) = cfg.rho_g * s.epsy(i, j) * g.dx * s.mom_v.d(i, j);
    for (std::size_t k = 0; k < s.imbalance.size(); ++k) s.imbalance.v[k] = -s.imbalance.v[k];
    s.p_corr.fill(0.0);
    // Factorised at the first SIMPLE iteration of each step only (the same in a restarted run).
    try {
      s.pressure.solve(s.ax, s.ay, s.imbalance, s.p_corr, it > 1);
    } catch (const Error& e) {
      throw_simulation_error(fmt::format(
          "gas at t = {:.6g} s (dt = {:.3g} s), SIMPLE iteration {}: {}. Likely cause: a voidage, drag or velocity "
          "that is no longer finite or usable; remedy: reduce the time step, check the inlet and jet velocities",
          t_new, dt, it, e.what()));
    }
    const Field2& pc = s.p_corr;
    for (std::size_t k = 0; k < s.f.p.size(); ++k) s.f.p.v[k] += cfg.relax_pressure * pc.v[k];
    for (int j = 0; j < ny; ++j)
      for (int i = 1; i < nx; ++i) s.f.u(i, j) += s.mom_u.d(i, j) * (pc(i - 1, j) - pc(i, j));
    for (int j = 1; j < ny; ++j)
      for (int i = 0; i < nx; ++i) s.f.v(i, j) += s.mom_v.d(i, j) * (pc(i, j - 1) - pc(i, j));
    if (s.outlet)
      for (int i = 0; i < nx; ++i) s.f.v(i, ny) += s.mom_v.d(i, ny) * pc(i, ny - 1);
    for (double x : s.f.p.v)
      if (!std::isfinite(x)) throw_simulation_error(fmt::format("gas: pressure is not finite at t = {:.6g} s", t_new));
    if (converged) break;
  }
  rep.mass_residual = residual;
  rep.reference_mass_flow = m_ref;
  rep.linear_fallbacks = s.linear_fallbacks;
  if (!converged) {
    throw_simulation_error(fmt::format(
        "gas: SIMPLE did not converge at t = {:.6g} s (dt = {:.3g} s): normalised mass residual {:.3e} > tolerance "
        "{:.1e} after {} iterations; reduce the time step or raise gas.max_iterations",
        t_new, dt, residual, cfg.mass_tolerance, cfg.max_simple_iterations));
  }
  // Gas mass balance of the corrected velocities.
  s.mass_fluxes();
  const double vol = g.dx * g.dy;
  for (int i = 0; i < nx; ++i) {
    rep.mass_in += s.my(i, 0);
    rep.mass_out += s.my(i, ny);
  }
  for (int j = 0; j < ny; ++j) {
    double row = 0.0;
    for (int i = 0; i < nx; ++i) row += eps_new(i, j) - eps_old(i, j);
    rep.accumulation += cfg.rho_g * row * vol / dt;
  }
  rep.mass_balance = rep.mass_out - rep.mass_in + rep.accumulation;
  rep.mass_balance_relative = std::abs(rep.mass_balance) / m_ref;
  for (const Field2* fld : {&s.f.u, &s.f.v})
    for (double x : fld->v)
      if (!std::isfinite(x)) throw_simulation_error(fmt::format("gas: velocity is not finite at t = {:.6g} s", t_new));
  return rep;
}

const Grid2& GasSolver::grid() const { return impl_->grid; }
const GasConfig& GasSolver::config() const { return impl_->cfg; }
const StaggeredFields& GasSolver::fields() const { return impl_->f; }
StaggeredFields& GasSolver::fields() { return impl_->f; }

Vec2 GasSolver::velocity_at(Vec2 x) const {
  return {interpolate_u(impl_->grid, impl_->f.u, x), interpolate_v(impl_->grid, impl_->f.v, x)};
}

Vec2 GasSolver::pressure_gradient_at(Vec2 x) const {
  return interpolate_pressure_gradient(impl_->grid, impl_->f.p, x);
}

void GasSolver::cell_velocity(Field2& ug, Field2& vg) const { cell_centre_velocity(impl_->f.u, impl_->f.v, ug, vg); }

void GasSolver::cell_pressure_gradient(Field2& dpdx, Field2& dpdy) const {
  fluidbed::cell_pressure_gradient(impl_->grid, impl_->f.p, dpdx, dpdy);
}

double GasSolver::pressure_drop() const {
  const Grid2& g = impl_->grid;
  double bottom = 0.0;
  double top = 0.0;
  for (int i = 0; i < g.nx; ++i) {
    bottom += impl_->f.p(i, 0);
    top += impl_->f.p(i, g.ny - 1);
  }
  return (bottom - top) / g.nx;
}

}  // namespace fluidbed
