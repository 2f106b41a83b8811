#include "tfm/tfm_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "numerics/tvd_lines.hpp"
#include "closures/drag.hpp"
#include "fluid/gas_boundary.hpp"
#include "numerics/structured_solver_hypre.hpp"
#include "numerics/multigrid_cg.hpp"
#include "numerics/stencil_bicgstab.hpp"
#include "numerics/band_pressure_solver.hpp"
#include "numerics/line_loop.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/exact_sum.hpp"
#include "parallel/periodic_halo.hpp"
#include "tfm/packing_limiter.hpp"

namespace fluidbed::tfm {
namespace {

// Solids fraction kept in the face mass and drag of an empty face, so that the 2x2 drag system stays regular;
// both scale together, so trace solids still move at their terminal slip.
constexpr double kEpsSFloor = 1e-8;
// Faces with less solids than this carry no solids-momentum convection and do not limit dt (trace solids).
constexpr double kEpsSTrace = 1e-4;
// Below this solids fraction the constant solids viscosity is ramped to zero ("constant in the bed").
constexpr double kEpsSBed = 0.05;

// Uniform number in [0, 1) from (seed, stream, index) by the splitmix64 finaliser (Steele et al. 2014): the same
// on every platform and independent of the order in which cells ask, so the perturbations are reproducible.
double seeded_uniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream * 0x100000001B3ULL + index + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

template <int Dim>
Index<Dim> with(Index<Dim> c, int a, int value) {
  c[a] = value;
  return c;
}

// Advective term (U . grad) u_d of velocity component d on a line of its faces along axis 0 (n faces from f),
// TVD face values, in the advective form div(U u_d) - u_d div(U) so that it vanishes for a uniform field; the
// transport velocity of each face of the momentum cell is the mean of the two faces it joins. Ghost layers stand in
// for the clamped stencil. The fluxes through the momentum cells' faces are computed as vectorised runs
// (tvd::face_fluxes), each face once: along axis 0 the low face of a cell is the high face of the one before it,
// along axis 1 it is the high face of the same cell on the line before (kept from that line when the thread has
// just done it). Every flux is the expression of the face by face form, with the same operands: the same bits.
template <int Dim>
struct AdvectLine {
  int n;
  std::vector<double> v0, f0;      // axis 0: the n + 1 faces of the line's cells, velocity and flux
  std::vector<double> v_hi, f_hi;  // axis 1 (and 2 in turn): the high faces
  std::vector<double> v_lo, f_lo;  // and the low ones
  std::vector<double> v1_prev, f1_prev;  // the last line's axis-1 high faces
  Index<Dim> prev{};
  bool has_prev = false;
  std::vector<double> div;
  explicit AdvectLine(int n_faces)
      : n(n_faces), v0(n + 1), f0(n + 1), v_hi(n), f_hi(n), v_lo(n), f_lo(n), v1_prev(n), f1_prev(n), div(n) {}

  template <int d>
  void run(tvd::Limiter limiter, const FaceFields<Dim>& vel, const Grid<Dim>& g, const Index<Dim>& f, double* adv) {
    const Field<Dim>& u = vel[d];
    const double* pu = u.data().data() + u.index(f);
    // Velocity of the momentum cells' faces along axis a on the line starting at face `line`: vl[i] (the low face
    // of face i's cell) for i in [0, count). On the line one step up along a it gives this line's high faces.
    auto low_velocity = [&](int a, const Index<Dim>& line, int count, double* vl) {
      if (a == d) {
        const double* pl = u.data().data() + u.index(line);
        const auto su = static_cast<std::ptrdiff_t>(u.stride(a));
        for (int i = 0; i < count; ++i) vl[i] = 0.5 * (pl[i - su] + pl[i]);
      } else {
        const Field<Dim>& v = vel[a];
        const double* pv = v.data().data() + v.index(line);
        const auto sd = static_cast<std::ptrdiff_t>(v.stride(d));
        for (int i = 0; i < count; ++i) vl[i] = 0.5 * (pv[i - sd] + pv[i]);
      }
    };
    // Axis 0: the faces of cells i - 1 | i for i = 0 .. n.
    {
      low_velocity(0, f, n + 1, v0.data());
      tvd::face_fluxes(limiter, n + 1, v0.data(), pu, static_cast<std::ptrdiff_t>(u.stride(0)), f0.data());
      const double h = g.h[0];
      for (int i = 0; i < n; ++i) {
        adv[i] = (f0[i + 1] - f0[i]) / h;
        div[i] = (v0[i + 1] - v0[i]) / h;
      }
    }
    for (int a = 1; a < Dim; ++a) {
      const auto su = static_cast<std::ptrdiff_t>(u.stride(a));
      // The high face of this line's cells is the low face of the next line's: velocity and flux at the line
      // shifted by one along a.
      Index<Dim> up = f;
      ++up[a];
      low_velocity(a, up, n, v_hi.data());
      tvd::face_fluxes(limiter, n, v_hi.data(), pu + su, su, f_hi.data());
      Index<Dim> below = f;
      --below[a];
      if (a == 1 && has_prev && prev == below) {
        v_lo.swap(v1_prev);
        f_lo.swap(f1_prev);
      } else {
        low_velocity(a, f, n, v_lo.data());
        tvd::face_fluxes(limiter, n, v_lo.data(), pu, su, f_lo.data());
      }
      const double h = g.h[a];
      for (int i = 0; i < n; ++i) {
        adv[i] = adv[i] + (f_hi[i] - f_lo[i]) / h;
        div[i] = div[i] + (v_hi[i] - v_lo[i]) / h;
      }
      if (a == 1) {  // keep this line's high faces for the next line
        v1_prev.swap(v_hi);
        f1_prev.swap(f_hi);
      }
    }
    prev = f;
    has_prev = true;
    for (int i = 0; i < n; ++i) adv[i] = adv[i] - pu[i] * div[i];
  }
};

// The slot of plane (p, q), p < q, among the planes of cell edges: (0, 1) -> 0, (0, 2) -> 1, (1, 2) -> 2.
constexpr int edge_plane(int p, int q) { return p + q - 1; }

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

template <SolidsRheology R, FrictionalModel F>
double solids_pressure_law(const TfmConfig& c, const GranularMaterial& m, double eps, double theta) {
  if constexpr (R == SolidsRheology::KineticTheory) {
    // Eq. 19: frictional regime at or below eps*, kinetic theory above; or the two added (Johnson-Jackson).
    if constexpr (F != FrictionalModel::Schaeffer)
      return kt_pressure(m, eps, theta) + jj_frictional_pressure(c.friction, 1.0 - eps);
    if (eps <= c.eps_star) return frictional_pressure(eps, c.eps_star);
    return kt_pressure(m, eps, theta);
  } else {
    return modulus_pressure(c.modulus, eps, c.eps_star);
  }
}

template <int Dim>
std::string index_name(const Index<Dim>& c) {
  std::string s = "(";
  for (int a = 0; a < Dim; ++a) s += fmt::format("{}{}", a > 0 ? ", " : "", c[a]);
  return s + ")";
}

}  // namespace

void validate(const TfmConfig& c) {
  auto need = [](bool ok, const char* what) {
    if (!ok) throw_input_error(std::string("tfm: ") + what);
  };
  const DomainConfig& d = c.domain;
  need(d.dimension == 2 || d.dimension == 3, "the dimension must be 2 or 3");
  const bool three_d = d.dimension == 3;
  need(d.width > 0.0 && d.height > 0.0 && (!three_d || d.depth > 0.0), "width, height (and depth in 3D) must be positive");
  const double smallest = three_d ? std::min({d.width, d.height, d.depth}) : std::min(d.width, d.height);
  need(c.cell_size > 0.0 && c.cell_size <= smallest, "cell_size must be positive and fit the domain");
  auto whole = [&](double length) {
    const double n = length / c.cell_size;
    return std::abs(n - std::round(n)) < 1e-6;
  };
  need(whole(d.width) && whole(d.height) && (!three_d || whole(d.depth)),
       "width, height (and depth in 3D) must be whole multiples of cell_size");
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
  need(c.packed_height >= 0.0 && c.packed_height <= d.height, "packed_height must lie in [0, height]");
  need(c.mu_s_constant >= 0.0 && c.mu_s_max > 0.0, "solids viscosities must be non-negative (mu_s_max positive)");
  need(c.modulus.a > 0.0 && c.modulus.b > 0.0, "modulus a and b must be positive");
  const int sliding = sliding_wall_axis(d.dimension);
  const bool slides = c.sliding_wall[0] != 0.0 || c.sliding_wall[1] != 0.0 || (three_d && c.sliding_wall[2] != 0.0);
  need(!slides || (c.solids_no_slip_walls && !d.periodic[static_cast<std::size_t>(sliding)] &&
                   c.sliding_wall[static_cast<std::size_t>(sliding)] == 0.0),
       "a sliding wall (the high side wall of z in 3D, x in 2D) needs solids_no_slip_walls, a wall there (not a "
       "periodic axis) and a velocity tangential to it");
  need(c.yield_stress >= 0.0 && c.yield_regularisation > 0.0,
       "the Bingham yield stress must be non-negative and its regularisation m positive");
  need(c.cfl > 0.0 && c.cfl <= 1.0, "cfl must lie in (0, 1]");
  need(c.max_dense_change > 0.0 && c.max_dense_change < 0.1, "max_dense_change must lie in (0, 0.1)");
  need(packing_allowance(c) >= 0.0 && packing_allowance(c) < c.eps_star, "max_compaction must lie in [0, eps_star)");
  if (c.rheology == SolidsRheology::KineticTheory && c.frictional != FrictionalModel::Schaeffer) {
    const FrictionalParams& f = c.friction;
    need(f.eps_s_min > 0.0 && f.eps_s_min < f.eps_s_max && f.eps_s_max < 1.0,
         "the frictional onset and packing limit must satisfy 0 < onset < limit < 1");
    need(1.0 - (c.eps_star - packing_allowance(c)) < f.eps_s_max,
         "the frictional packing limit must lie above the densest solids fraction the packing limiter allows, "
         "1 - (eps* - max_compaction): the Johnson-Jackson pressure diverges there");
  }
  need(c.dt_max > 0.0 && c.dt_min > 0.0 && c.dt_min < c.dt_max, "need 0 < dt_min < dt_max");
  need(c.mass_corrections >= 0 && c.mass_corrections <= 10, "mass_corrections must lie in [0, 10]");
  for (const InletJet& j : c.boundary.jets) {
    need(j.width > 0.0 && j.t_end >= j.t_start, "each jet needs width > 0 and t_end >= t_start");
  }
  need(c.boundary.top == TopBoundary::PressureOutlet || c.boundary.lid_velocity == 0.0,
       "a moving lid (boundary lid_velocity) is not supported by the two-fluid model");
  need(!d.periodic[1], "the vertical axis (y: distributor and outlet) cannot be periodic");
  need(three_d || !d.periodic[2], "a 2D case has no periodic z axis");
  for (int a : {0, 2}) {
    const double length = a == 0 ? d.width : d.depth;
    need(!d.periodic[static_cast<std::size_t>(a)] || std::lround(length / c.cell_size) >= 3,
         "a periodic axis needs at least 3 cells (face 0 must join two different cells)");
  }
  need(!d.any_periodic() || c.pressure_solver != PressureBackend::HyprePfmg,
       "pressure_solver = \"hypre-pfmg\" does not take periodic axes (domain.periodic): use \"eigen\", "
       "\"eigen-cg\" or \"cg-multigrid\"");
}

template <int Dim>
struct TfmSolver<Dim>::Work {
  FaceFields<Dim> g0, s0;          // velocities entering the step (gas interstitial on the distributor), ghosts filled
  FaceFields<Dim> dg, ds;          // velocity response to a unit P' gradient (gas, solids)
  FaceFields<Dim> gs, ss;          // velocity response to a unit (K E') gradient (gas, solids)
  FaceFields<Dim> eg, es;          // TVD face fractions of the step
  FaceFields<Dim> a;               // face coefficients of the P' equation
  Field<Dim> eps_s, eps_s_new;     // solids fraction before and after the continuity
  Field<Dim> rhs_p, p_corr;
  FaceFluxes<Dim> fs, fs_unlimited, fs_corr, fg_shift;
  CellVectorField<Dim> usc;        // solids velocity at cell centres (strain rate)
  // mu_corner of every interior cell edge, per plane (p, q) with p < q (one plane in 2D, three in 3D): each edge
  // is shared by the momentum cells of both components around it, so it is computed once a step.
  std::array<Field<Dim>, Dim * (Dim - 1) / 2> mu_edge;
  std::array<Field<Dim>, Dim * (Dim - 1) / 2> shear_edge;  // the Eq. 19 shear stress on those edges
  Field<Dim> div_s;                                         // div u_s of each cell
  std::array<Field<Dim>, Dim> normal;                       // Eq. 19 normal stress of each cell, per component
  Eigen::VectorXd out_g, out_s;
  std::vector<double> inlet;
  InletWork inlet_work;  // the inlet profile's work arrays, kept between steps
  double dense_change = 0.0;
  std::unique_ptr<StructuredSolver<Dim>> pressure;  // shared with the gas solver (src/fluid)
  // The solids-fraction correction E': its rows, solver and vectors (the same bits on any rank count).
  std::unique_ptr<StencilBicgstab<Dim>> e_solver;
  std::vector<double> e_rhs, e_corr;
  Field<Dim> e_field;  // E' on the block with its ghosts (the faces on the block's edge read the neighbour's)
  ImplicitTransportWork<Dim> transport;  // the implicit solids continuity's matrix, solver and work arrays
};

namespace {
template <int Dim>
Grid<Dim> validated_grid(const TfmConfig& c) {
  validate(c);
  if (c.domain.dimension != Dim) {
    throw_input_error(fmt::format("tfm: a {}D solver cannot run a case of dimension {}", Dim, c.domain.dimension));
  }
  const Vec<Dim> extent = c.domain.extent<Dim>();
  Index<Dim> n{};
  for (int a = 0; a < Dim; ++a) n[a] = static_cast<int>(std::lround(extent[a] / c.cell_size));
  Grid<Dim> g = Grid<Dim>::uniform(extent, n, kGhost);
  for (int a = 0; a < Dim; ++a) g.periodic[static_cast<std::size_t>(a)] = c.domain.periodic[static_cast<std::size_t>(a)];
  return g;
}
}  // namespace

template <int Dim>
Index<Dim> tfm_blocks(int ranks, const Index<Dim>& n, const std::array<bool, Dim>& periodic) {
  Index<Dim> best{};
  long best_faces = -1;
  for (int by = 1; by <= ranks; ++by) {
    if (ranks % by != 0) continue;
    const int bz = ranks / by;
    if (Dim == 2 && bz != 1) continue;
    if (by > n[1] || (periodic[1] && by > 1)) continue;
    if (Dim == 3 && (bz > n[Dim - 1] || (periodic[Dim - 1] && bz > 1))) continue;
    // Cell faces between blocks: (by - 1) planes of nx nz faces, (bz - 1) planes of nx ny.
    const long faces = static_cast<long>(n[0]) * ((by - 1) * (Dim == 3 ? n[Dim - 1] : 1) + (Dim == 3 ? (bz - 1) * n[1] : 0));
    if (best_faces >= 0 && faces >= best_faces) continue;
    best_faces = faces;
    best[0] = 1;
    best[1] = by;
    if constexpr (Dim == 3) best[2] = bz;
  }
  return best;
}

template <int Dim>
TfmSolver<Dim>::TfmSolver(const TfmConfig& config, const Comm& comm)
    : config_(config), comm_(comm), grid_(validated_grid<Dim>(config)), w_(std::make_unique<Work>()) {
  if (comm.size() > 1) {
    Index<Dim> n{};
    for (int a = 0; a < Dim; ++a) n[a] = grid_.n(a);
    const Index<Dim> blocks = tfm_blocks<Dim>(comm.size(), n, grid_.periodic);
    if (blocks[0] == 0) {
      throw_input_error(fmt::format("tfm: {} ranks cannot share this grid: the blocks span x and every periodic axis, "
                                    "so the ranks must divide among the cells of the other axes", comm.size()));
    }
    if (config_.pressure_solver != PressureBackend::CgMultigrid) {
      throw_input_error(fmt::format("tfm on {} ranks: gas.pressure_solver = \"cg-multigrid\" is the backend whose "
                                    "answer does not depend on the ranks (the others run on one process)", comm.size()));
    }
    grid_.owned = block_of<Dim>(grid_.domain, blocks, comm.rank());
    cell_boxes_ = all_boxes<Dim>(comm, grid_.owned);
  } else {
    cell_boxes_ = {grid_.owned};
  }
  for (int a = 0; a < Dim; ++a)
    for (const IndexBox<Dim>& b : cell_boxes_) face_boxes_[static_cast<std::size_t>(a)].push_back(b.faces(a));
  const IndexBox<Dim>& cells = grid_.owned;
  Work& w = *w_;
  // Rows numbered axis 0 fastest; neighbours low and high along each axis in turn (W, E, S, N[, B, F]).
  w.e_solver = std::make_unique<StencilBicgstab<Dim>>(grid_, comm_);
  switch (config_.pressure_solver) {
    case PressureBackend::HyprePfmg: w.pressure = make_hypre_structured_solver<Dim>(grid_, kPressureTolerance); break;
    case PressureBackend::EigenCg:
      w.pressure = make_eigen_structured_solver<Dim>(grid_, PressureSolverKind::ConjugateGradient, kPressureTolerance);
      break;
    case PressureBackend::CgMultigrid:
      // Line sums: the TFM's blocks span x (its BiCGSTAB needs it too), and exact terms were 12% of a 3D step.
      w.pressure = make_multigrid_cg_solver<Dim>(grid_, comm_, {.tolerance = kPressureTolerance, .line_sums = true});
      break;
    case PressureBackend::Eigen:
      // The direct solve: a band factorisation where the rows couple within a narrow band (2D), else Eigen's
      // sparse Cholesky.
      w.pressure = make_band_structured_solver<Dim>(grid_);
      if (!w.pressure) w.pressure = make_eigen_structured_solver<Dim>(grid_);
      break;
  }
  for (FaceFields<Dim>* f : {&w.g0, &w.s0, &w.dg, &w.ds, &w.gs, &w.ss, &w.eg, &w.es, &w.a, &w.fs, &w.fs_unlimited,
                             &w.fs_corr, &w.fg_shift}) {
    *f = FaceFields<Dim>(cells, kGhost);
  }
  for (Field<Dim>* f : {&w.eps_s, &w.rhs_p, &w.p_corr, &p_s_, &mu_s_, &lambda_s_, &beta_c_, &dps_deps_, &s_.p,
                        &s_.theta, &w.e_field}) {
    *f = Field<Dim>(cells, kGhost);
  }
  for (int a = 0; a < Dim; ++a) w.usc[a] = Field<Dim>(cells, 1);  // the strain rate reads the neighbours
  s_.ug = FaceFields<Dim>(cells, kGhost);
  s_.us = FaceFields<Dim>(cells, kGhost);
  s_.eps = Field<Dim>(cells, kGhost, 1.0);
  if (comm.size() > 1) {
    // The initial bed integrates the pressure down whole columns: made on the whole grid, then each rank takes
    // its block (the same bits as one process).
    restore_state(TfmSolver<Dim>(config_, serial_comm()).save_state());
  } else {
    initial_bed();
  }
}

template <int Dim>
void TfmSolver<Dim>::initial_bed() {
  const IndexBox<Dim>& cells = grid_.domain;
  Work& w = *w_;
  const double dy = grid_.h[kUp];
  for_each(cells, [&](const Index<Dim>& c) {
    // Partly filled cells get the volume-weighted voidage, so the initial mass matches packed_height exactly.
    const double filled = std::clamp((config_.packed_height - c[kUp] * dy) / dy, 0.0, 1.0);
    s_.eps[c] = 1.0 - filled * (1.0 - config_.eps_initial);
  });
  if (config_.eps_noise > 0.0) {
    // Kept at or above eps*: a cell starting compacted would start on the frictional pressure (Eq. 21).
    for_each(cells, [&](const Index<Dim>& c) {
      if (s_.eps[c] >= 1.0) return;
      const double u = seeded_uniform(config_.seed, 1, static_cast<std::uint64_t>(cell_row(cells, c)));
      s_.eps[c] = std::clamp(s_.eps[c] + config_.eps_noise * (2.0 * u - 1.0), config_.eps_star, 1.0);
    });
  }
  fill_cell_ghosts(s_.eps, grid_.periodic);
  // Gas carries the background inflow at t = 0 (the start of an inlet ramp, src/fluid/gas_boundary.hpp):
  // superficial velocity over the face voidage the continuity equation uses, so the initial volume flux is
  // divergence-free.
  const double u_in = background_inlet_velocity(config_.boundary, 0.0);
  const bool top_open = config_.boundary.top == TopBoundary::PressureOutlet;
  {
    FaceFields<Dim> up(cells, kGhost);
    up[kUp].fill(1.0);
    tvd_face_values(grid_, config_.limiter, s_.eps, FaceVelocity<Dim>{up, grid_.periodic}, w.eg);
    for_each(cells.faces(kUp), [&](const Index<Dim>& f) {
      const bool closed = f[kUp] == cells.hi[kUp] && !top_open;
      s_.ug[kUp][f] = closed ? 0.0 : u_in / (f[kUp] == cells.lo[kUp] ? 1.0 : w.eg[kUp][f]);
    });
  }
  // Pressure from the steady gas momentum balance of every face (Eq. 17 without inertia), integrated down
  // from the top: in a bed at rest the drag then carries exactly what the gas flow can carry.
  const double g = std::abs(config_.domain.gravity.y);
  const int ny = grid_.n(kUp);
  const DragBetaFn beta_of = drag_beta_function(DragModel{config_.drag_law, config_.drag_switch});  // Eq. 13
  for_each_bottom([&](const Index<Dim>& bottom) {
    auto cell = [&](int j) { return with<Dim>(bottom, kUp, j); };
    auto drop_across = [&](int j) {  // P(below) - P(above) across the face j
      const double eg = j == ny ? s_.eps[cell(ny - 1)] : 0.5 * (s_.eps[cell(j - 1)] + s_.eps[cell(j)]);
      auto beta_at = [&](int jc) {
        DragInput in{std::min(s_.eps[cell(jc)], 1.0 - kEpsSFloor), config_.d_p, config_.rho_g, config_.mu_g,
                     0.5 * (vg_interstitial(cell(jc)) + s_.ug[kUp][cell(jc + 1)])};
        return beta_of(in);
      };
      const double beta = j == ny ? beta_at(ny - 1) : 0.5 * (beta_at(j - 1) + beta_at(j));
      return config_.rho_g * g * dy + beta * s_.ug[kUp][cell(j)] * dy / eg;
    };
    s_.p[cell(ny - 1)] = config_.boundary.top_pressure + (top_open ? 0.5 * drop_across(ny) : 0.0);
    for (int j = ny - 1; j > 0; --j) s_.p[cell(j - 1)] = s_.p[cell(j)] + drop_across(j);
  });
  tie(s_.p);
  tie(s_.ug);
}

template <int Dim>
TfmSolver<Dim>::~TfmSolver() = default;
template <int Dim>
TfmSolver<Dim>::TfmSolver(TfmSolver&&) noexcept = default;

template <int Dim>
IndexBox<Dim> TfmSolver<Dim>::bottom_cells() const {
  IndexBox<Dim> b = grid_.owned;
  b.hi[kUp] = grid_.owned.lo[kUp] == grid_.domain.lo[kUp] ? b.lo[kUp] + 1 : b.lo[kUp];
  return b;
}

template <int Dim>
template <class F>
void TfmSolver<Dim>::for_each_bottom(F&& f) const {
  for_each(bottom_cells(), f);
}

template <int Dim>
void TfmSolver<Dim>::tie(Field<Dim>& f) const {
  if (grid_.any_periodic()) fill_periodic_ghosts(grid_, f);
}

template <int Dim>
std::span<const IndexBox<Dim>> TfmSolver<Dim>::boxes_of(const Field<Dim>& f) const {
  for (int a = 0; a < Dim; ++a)
    if (f.box() == grid_.owned.faces(a)) return face_boxes_[static_cast<std::size_t>(a)];
  return cell_boxes_;
}

template <int Dim>
IndexBox<Dim> TfmSolver<Dim>::domain_of(const Field<Dim>& f) const {
  for (int a = 0; a < Dim; ++a)
    if (f.box() == grid_.owned.faces(a)) return grid_.domain.faces(a);
  return grid_.domain;
}

template <int Dim>
void TfmSolver<Dim>::halo(Field<Dim>& f) const {
  if (comm_.size() > 1) comm_.exchange_halo_among(f, boxes_of(f), HaloCells::All);
  tie(f);
}

template <int Dim>
void TfmSolver<Dim>::fill_ghosts(Field<Dim>& f) const {
  // The walls' zero gradient on every side of the domain (a face field's periodic sides too, as fill_face_ghosts),
  // then the periodic images (a face field's face n is face 0: fill_periodic_ghosts knows it).
  const bool cells = f.box() == grid_.owned;
  fill_block_ghosts<Dim>(f, domain_of(f), cells ? grid_.periodic : std::array<bool, Dim>{}, comm_, boxes_of(f));
  if (!cells) tie(f);
}

template <int Dim>
void TfmSolver<Dim>::fail_together(const std::optional<std::string>& local, double key) const {
  if (const auto first = comm_.first_failure(local, key)) throw_simulation_error(*first);
}

template <int Dim>
void TfmSolver<Dim>::tie(FaceFields<Dim>& f) const {
  for (int a = 0; a < Dim; ++a) tie(f[a]);
}

template <int Dim>
IndexBox<Dim> TfmSolver<Dim>::interior_faces(int a) const {
  IndexBox<Dim> faces = grid_.owned.faces(a);
  if (!periodic(a)) faces.lo[a] = std::max(faces.lo[a], grid_.domain.lo[a] + 1);
  faces.hi[a] = std::min(faces.hi[a], grid_.domain.hi[a]);  // face n: a wall, or face 0 again
  return faces;
}

template <int Dim>
double TfmSolver<Dim>::vg_interstitial(const Index<Dim>& c) const {
  // The distributor face stores the superficial inflow; inside the bottom cell the gas moves at U / eps.
  return c[kUp] == grid_.domain.lo[kUp] ? s_.ug[kUp][c] / s_.eps[c] : s_.ug[kUp][c];
}

template <int Dim>
double TfmSolver<Dim>::gravity_norm() const {
  const Vec3& g = config_.domain.gravity;
  if constexpr (Dim == 2) {
    return std::hypot(g.x, g.y);
  } else {
    return std::hypot(g.x, g.y, g.z);
  }
}

template <int Dim>
double TfmSolver<Dim>::bottom_area() const {
  double m = grid_.length(0);
  for (int a = 2; a < Dim; ++a) m *= grid_.length(a);
  return m;
}

// ---- The step: the paper's algorithm (section 2.2), one named stage per line.

template <int Dim>
double TfmSolver<Dim>::advance(double t_stop) {
  mask_trace_solids_velocity();    // a face without solids on one side takes the bed's velocity
  compute_closures();              // Eqs. 13, 19-26: beta, P_s, mu_s, lambda_s, Theta per cell
  const double dt = choose_dt(t_stop);  // Table 3 item 5: dt < cell / V_max, and the compaction rate
  linear_fallbacks_ = 0;
  predict_momentum(dt);            // Eqs. 17-18 per face, drag by partial elimination
  // Walls, distributor inflow and jets, lid. The inflow at the step's midpoint, as the CFD-DEM gas takes it: a jet
  // open over [start, end) blows in exactly the steps inside that span (at the step's end it lost its last step).
  set_boundary_faces(s_.time + 0.5 * dt);
  face_fractions();                // section 2.2.1: TVD face voidages of the step
  // Eqs. 15 + 16: mixture volume flux divergence-free (P'); the E' rows need only the face fractions and the
  // closures, so a second thread writes them meanwhile.
  // (One thread calls MPI: on several ranks the P' solve, which talks to them, runs first.)
  side_by_side(two_tasks(static_cast<long>(grid_.owned.count())) && comm_.size() == 1, [&] { correct_pressure(dt, false); },
               [&] { solids_fraction_rows(dt); });
  correct_solids_fraction(dt);     // Eq. 16 with P_s implicit (E'), then P' once more
  solids_continuity(dt);           // Eq. 16 implicit, packing limiter eps >= eps* - max_compaction
  close_gas_continuity(dt);        // Eq. 15: the gas takes the rest of the mixture flux; eps = 1 - eps_s
  s_.time += dt;
  // A step clipped to reach t_stop says little about the natural step; keep the rate of a full one.
  if (dt >= 0.5 * s_.dt || s_.steps == 0) {
    s_.dt = dt;
    s_.dense_change = w_->dense_change;
  }
  ++s_.steps;
  check_health(dt);
  return dt;
}

template <int Dim>
void TfmSolver<Dim>::mask_trace_solids_velocity() {
  // A face with (almost) no solids on one side has no meaningful solids velocity; it takes the velocity of the
  // next face into the solids (zero gradient), so stresses and convection at a bed surface see the bed only.
  for (int d = 0; d < Dim; ++d) {
    Field<Dim>& u0 = w_->s0[d];  // the velocities before masking (s0 is rewritten by the predictor later)
    u0.data() = s_.us[d].data();
    halo(u0);
    const int n = grid_.n(d);
    const bool per = periodic(d);
    const IndexBox<Dim> faces = interior_faces(d);
    const auto se = static_cast<std::ptrdiff_t>(s_.eps.stride(d)), su = static_cast<std::ptrdiff_t>(u0.stride(d));
    IndexBox<Dim> lines = faces;
    lines.hi[0] = lines.lo[0] + 1;
    for_each(lines, [&](Index<Dim> f) {
      const double* pe = s_.eps.data().data() + s_.eps.index(f);  // the cell above the face; pe[-se] below
      const double* pu = u0.data().data() + u0.index(f);
      double* out = s_.us[d].data().data() + s_.us[d].index(f);
      auto has = [](double eps) { return 1.0 - eps > kEpsSTrace; };
      for (int i = faces.lo[0]; i < faces.hi[0]; ++i, ++pe, ++pu, ++out) {
        f[0] = i;
        const bool l = has(pe[-se]), r = has(pe[0]);
        if (l && r) continue;
        double val = 0.0;
        if (l && (per || f[d] - 1 > 0) && has(pe[-2 * se])) val = pu[-su];
        if (r && (per || f[d] + 1 < n) && has(pe[se])) val = pu[su];
        *out = val;
      }
    });
    tie(s_.us[d]);
  }
}

template <int Dim>
void TfmSolver<Dim>::compute_closures() {
  // Rheology, frictional closure (the kinetic theory's only) and drag law chosen once per step; the cell loop is
  // compiled for each combination.
  with_rheology(config_.rheology, [this](auto r) {
    auto with_law = [this](auto f) {
      with_drag_law(DragModel{config_.drag_law, config_.drag_switch}, [this](auto law) {
        compute_closures_of<decltype(r)::value, decltype(f)::value, decltype(law)>();
      });
    };
    if constexpr (decltype(r)::value == SolidsRheology::KineticTheory) {
      with_frictional(config_.frictional, with_law);
    } else {
      with_law(std::integral_constant<FrictionalModel, FrictionalModel::Schaeffer>{});
    }
  });
}

template <int Dim>
template <SolidsRheology R, FrictionalModel F, class DragLawT>
void TfmSolver<Dim>::compute_closures_of() {
  const TfmConfig& c = config_;
  const GranularMaterial mat{c.d_p, c.rho_s, c.e};
  const double phi = c.phi_deg * 3.14159265358979323846 / 180.0;
  const IndexBox<Dim>& cells = grid_.owned;
  const IndexBox<Dim>& dom = grid_.domain;
  CellVectorField<Dim>& usc = w_->usc;
  solids_velocity_cells(usc);
  for (Field<Dim>& u : usc) halo(u);  // the strain rate of a cell on the block's edge reads the neighbour's
  // Velocity gradient of component `comp` along axis `along` from the cell centres: central inside, one-sided in
  // the outer layers (the strain rate's off-diagonal part).
  auto gradient = [&](const Index<Dim>& cell, int comp, int along) {
    if (periodic(along)) {  // central everywhere: the neighbours across face 0 are the other end's cells
      const int lo = grid_.wrap(along, cell[along] - 1), hi = grid_.wrap(along, cell[along] + 1);
      return (usc[comp][with<Dim>(cell, along, hi)] - usc[comp][with<Dim>(cell, along, lo)]) / (2 * grid_.h[along]);
    }
    const int lo = std::max(cell[along] - 1, dom.lo[along]);
    const int hi = std::min(cell[along] + 1, dom.hi[along] - 1);
    if (!(hi > lo)) return 0.0;
    return (usc[comp][with<Dim>(cell, along, hi)] - usc[comp][with<Dim>(cell, along, lo)]) / ((hi - lo) * grid_.h[along]);
  };
  auto close = [&](const Index<Dim>& cell) {
    const double eps = s_.eps[cell];
    const double eps_s = 1.0 - eps;
    std::array<double, Dim> rel{};
    for (int a = 0; a < Dim; ++a) {
      const double low = a == kUp ? vg_interstitial(cell) : s_.ug[a][cell];
      rel[a] = usc[a][cell] - 0.5 * (low + s_.ug[a][shifted<Dim>(cell, a, 1)]);
    }
    // Slip speeds are far from overflow: the plain root, not hypot's scaled one.
    double slip2 = rel[0] * rel[0];
    for (int a = 1; a < Dim; ++a) slip2 += rel[a] * rel[a];
    const double slip = std::sqrt(slip2);
    // The floor keeps beta / (eps_s rho_s) finite in empty cells.
    beta_c_[cell] = DragLawT::beta(DragInput{std::min(eps, 1.0 - kEpsSFloor), c.d_p, c.rho_g, c.mu_g, slip});

    auto strain_rate = [&] {
      StrainRate<Dim> d;
      for (int a = 0; a < Dim; ++a) d(a, a) = (s_.us[a][shifted<Dim>(cell, a, 1)] - s_.us[a][cell]) / grid_.h[a];
      for (int a = 0; a < Dim; ++a)
        for (int b = a + 1; b < Dim; ++b) d(a, b) = 0.5 * (gradient(cell, a, b) + gradient(cell, b, a));
      return d;
    };
    double mu = 0.0, lambda = 0.0, theta = 0.0;
    if constexpr (R == SolidsRheology::ConstantViscosity) {
      mu = std::min(c.mu_s_constant * std::min(1.0, eps_s / kEpsSBed), c.mu_s_max);
    } else if constexpr (R == SolidsRheology::Bingham) {
      // The constant-viscosity rheology plus a yield stress, both scaled down alike where the solids thin out.
      const double scale = std::min(1.0, eps_s / kEpsSBed);
      const double tau_y = c.yield == YieldStress::MohrCoulomb
                               ? modulus_pressure(c.modulus, eps, c.eps_star) * std::sin(phi)
                               : c.yield_stress * scale;
      const double shear_rate = 2.0 * std::sqrt(second_invariant(strain_rate()));
      mu = std::min(bingham_viscosity(c.mu_s_constant * scale, tau_y, c.yield_regularisation, shear_rate), c.mu_s_max);
    } else if constexpr (R == SolidsRheology::KineticTheory) {
      const StrainRate<Dim> d = strain_rate();
      if constexpr (F != FrictionalModel::Schaeffer) {
        // The kinetic theory everywhere, the frictional stress added above its onset.
        if (eps_s > 0.0) theta = algebraic_granular_temperature(mat, eps, d);
        const double p_f = jj_frictional_pressure(c.friction, eps_s);
        const double theta_d2 = F == FrictionalModel::SrivastavaSundaresan ? theta / (c.d_p * c.d_p) : 0.0;
        mu = std::min(kt_shear_viscosity(mat, eps, theta) + frictional_viscosity_on(p_f, phi, d, theta_d2, c.mu_s_max),
                      c.mu_s_max);
        lambda = std::clamp(kt_bulk_viscosity(mat, eps, theta), -c.mu_s_max, c.mu_s_max);
      } else if (eps <= c.eps_star) {
        mu = frictional_viscosity(eps, c.eps_star, phi, d, c.mu_s_max);
      } else if (eps_s > 0.0) {
        theta = algebraic_granular_temperature(mat, eps, d);
        mu = std::min(kt_shear_viscosity(mat, eps, theta), c.mu_s_max);
        lambda = std::clamp(kt_bulk_viscosity(mat, eps, theta), -c.mu_s_max, c.mu_s_max);
      }
    }
    mu_s_[cell] = mu;
    lambda_s_[cell] = lambda;
    s_.theta[cell] = theta;
    p_s_[cell] = solids_pressure_law<R, F>(c, mat, eps, theta);
    // dP_s/d eps_s sets the speed of compaction waves that the explicit solids pressure must resolve.
    const double h = 1e-7;
    const double p_lo = solids_pressure_law<R, F>(c, mat, eps - h, theta);
    const double p_hi = solids_pressure_law<R, F>(c, mat, eps + h, theta);
    dps_deps_[cell] = std::max(0.0, (p_lo - p_hi) / (2 * h));
  };
  // Each cell writes only its own closures: the same bits at any thread count. Below kParallelCells with two
  // threads, each takes one half of the lines (one fork).
  auto lines = [&](int first, int last) {
    for (int l = first; l < last; ++l)
      for (Index<Dim> cell = line_start(cells, l); cell[0] < cells.hi[0]; ++cell[0]) close(cell);
  };
  const long count = static_cast<long>(cells.count());
  if (two_tasks(count)) {
    const int n = line_count(cells);
    side_by_side(true, [&] { lines(0, n / 2); }, [&] { lines(n / 2, n); });
  } else {
    for_each_line_parallel(cells, [&](Index<Dim> cell) {
      for (; cell[0] < cells.hi[0]; ++cell[0]) close(cell);
    });
  }
  // The faces of a periodic axis's face 0 read the closures of the cell beyond it.
  for (Field<Dim>* f : {&beta_c_, &mu_s_, &lambda_s_, &p_s_, &dps_deps_, &s_.theta}) halo(*f);
}

template <int Dim>
double TfmSolver<Dim>::choose_dt(double t_stop) const {
  double vmax = 0.0;
  for (int a = 0; a < Dim; ++a)
    for_each(grid_.owned.faces(a), [&](const Index<Dim>& f) { vmax = std::max(vmax, std::abs(s_.ug[a][f])); });
  for (int a = 0; a < Dim; ++a)
    for_each(grid_.owned.faces(a), [&](const Index<Dim>& f) {
      // The ghost cell repeats the boundary cell, so a boundary face looks at its one cell twice.
      const double es = 1.0 - s_.eps[shifted<Dim>(f, a, -1)], es2 = 1.0 - s_.eps[f];
      if (std::min(es, es2) > kEpsSTrace) vmax = std::max(vmax, std::abs(s_.us[a][f]));
    });
  vmax = comm_.max(vmax);  // a maximum: exact, whatever the ranks
  // Paper Table 3 item 5: dt < dy / V_max. The solids pressure is implicit through the coupled correction,
  // so its compaction-wave speed does not enter.
  double h_min = grid_.h[0];
  for (int a = 1; a < Dim; ++a) h_min = std::min(h_min, grid_.h[a]);
  double dt = config_.dt_max;
  if (vmax > 0.0) dt = std::min(dt, config_.cfl * h_min / vmax);
  // Compaction rate of the last step, extrapolated: keeps cells from jumping deep past eps* in one step.
  if (s_.dense_change > 0.0 && s_.dt > 0.0) dt = std::min(dt, s_.dt * config_.max_dense_change / s_.dense_change);
  dt = std::min(dt, t_stop - s_.time);
  if (!(dt >= config_.dt_min) && t_stop - s_.time > config_.dt_min) {
    throw_simulation_error(fmt::format(
        "tfm at t = {:.6g} s (step {}): the time step {:.3g} s fell below tfm.dt_min = {:.3g} s (largest solids "
        "speed {:.4g} m/s, last compaction per step {:.3g}). Likely cause: the solids are running away (speed) or a "
        "cell is being compacted ever faster past eps*. Remedy: {}",
        s_.time, s_.steps, dt, config_.dt_min, max_solids_speed(), s_.dense_change, remedy()));
  }
  return dt;
}

template <int Dim>
void TfmSolver<Dim>::predict_momentum(double dt) {
  Work& w = *w_;
  // The velocities entering the step, with zero-gradient ghosts for the convection stencils. Gas enters the bed
  // through the distributor at its interstitial speed: the convection sees U / eps there.
  for (int a = 0; a < Dim; ++a) {
    w.g0[a].data() = s_.ug[a].data();
    w.s0[a].data() = s_.us[a].data();
  }
  for_each_bottom([&](const Index<Dim>& c) { w.g0[kUp][c] = s_.ug[kUp][c] / s_.eps[c]; });
  for (int a = 0; a < Dim; ++a) {
    // The owners' faces across a cut, zero gradient beyond a wall, the other side's across a periodic axis.
    fill_ghosts(w.g0[a]);
    fill_ghosts(w.s0[a]);
    for (FaceFields<Dim>* f : {&w.dg, &w.ds, &w.gs, &w.ss}) (*f)[a].fill(0.0);
  }
  // The solids stresses (Eq. 19) the momentum cells of both components share: the normal stress of each cell and
  // the shear stress of each interior cell edge, computed once a step.
  const IndexBox<Dim>& cells = grid_.owned;
  const Vec<Dim> h = grid_.h;
  const FaceFields<Dim>& s0 = w.s0;
  if (!(w.div_s.box() == cells)) {
    w.div_s = Field<Dim>(cells, 0);
    for (Field<Dim>& f : w.normal) f = Field<Dim>(cells, 1);  // a face 0 of a periodic axis reads the ghost
  }
  for_each(cells, [&](const Index<Dim>& cell) {
    double div = (s0[0][shifted<Dim>(cell, 0, 1)] - s0[0][cell]) / h[0];
    for (int a = 1; a < Dim; ++a) div += (s0[a][shifted<Dim>(cell, a, 1)] - s0[a][cell]) / h[a];
    w.div_s[cell] = div;
    for (int d = 0; d < Dim; ++d)
      w.normal[d][cell] = 2.0 * mu_s_[cell] * (s0[d][shifted<Dim>(cell, d, 1)] - s0[d][cell]) / h[d] + lambda_s_[cell] * div;
  });
  for (Field<Dim>& f : w.normal) halo(f);
  for (int p = 0; p < Dim; ++p)
    for (int q = p + 1; q < Dim; ++q) {
      Field<Dim>& mu = w.mu_edge[static_cast<std::size_t>(edge_plane(p, q))];
      Field<Dim>& shear = w.shear_edge[static_cast<std::size_t>(edge_plane(p, q))];
      IndexBox<Dim> edges = cells.faces(p).faces(q);
      if (!(mu.box() == edges)) {
        mu = Field<Dim>(edges, 0);
        shear = Field<Dim>(edges, 0);
      }
      // Edges on a wall are the wall's business; on a periodic axis edge 0 is interior and edge n is edge 0.
      for (int a : {p, q}) {
        if (!periodic(a)) edges.lo[a] = std::max(edges.lo[a], grid_.domain.lo[a] + 1);
        edges.hi[a] = std::min(edges.hi[a], grid_.domain.hi[a]);
      }
      for_each(edges, [&](const Index<Dim>& k) {
        const double mc = mu_corner(k, p, q);
        mu[k] = mc;
        shear[k] = mc * ((s0[p][k] - s0[p][shifted<Dim>(k, q, -1)]) / h[q] + (s0[q][k] - s0[q][shifted<Dim>(k, p, -1)]) / h[p]);
      });
      tie(mu);
      tie(shear);
    }
  if constexpr (Dim == 2) {
    // The two components read the same inputs and write disjoint outputs.
    side_by_side(two_tasks(static_cast<long>(grid_.owned.count())), [&] { predict_momentum_along<0>(dt); },
                 [&] { predict_momentum_along<1>(dt); });
  } else {
    predict_momentum_along<0>(dt);
    predict_momentum_along<1>(dt);
    predict_momentum_along<2>(dt);
  }
}

template <int Dim>
double TfmSolver<Dim>::mu_corner(const Index<Dim>& k, int p, int q) const {
  // Harmonic mean of the four cells around the cell edge k in the (p, q) plane: an edge touching an empty cell
  // carries no shear, so a dilute face is never driven by the viscosity of a dense diagonal neighbour (which the
  // explicit cross terms cannot bear).
  const Index<Dim> kq = shifted<Dim>(k, q, -1);
  const double m[4] = {mu_s_[shifted<Dim>(kq, p, -1)], mu_s_[kq], mu_s_[shifted<Dim>(k, p, -1)], mu_s_[k]};
  // Without branches (dilute and dense cells mix at random along a line): the sum in the same order as a loop
  // from 0, its value kept unless a cell has none (a NaN goes through, as it did).
  const double inv = (((0.0 + 1.0 / m[0]) + 1.0 / m[1]) + 1.0 / m[2]) + 1.0 / m[3];
  const bool none = (m[0] <= 0.0) | (m[1] <= 0.0) | (m[2] <= 0.0) | (m[3] <= 0.0);
  return none ? 0.0 : 4.0 / inv;
}

template <int Dim>
template <int d>
void TfmSolver<Dim>::predict_momentum_along(double dt) {
  const TfmConfig& c = config_;
  Work& w = *w_;
  const IndexBox<Dim>& cells = grid_.domain;
  const Vec<Dim> h = grid_.h;
  const double rho_g = c.rho_g, rho_s = c.rho_s;
  const double grav = c.domain.gravity_vector<Dim>()[d];
  const bool top_open = c.boundary.top == TopBoundary::PressureOutlet;
  const double mu_wall = c.solids_no_slip_walls ? 1.0 : 0.0;
  const Field<Dim>& eps = s_.eps;
  const Field<Dim>& p = s_.p;
  const FaceFields<Dim>& s0 = w.s0;
  const Field<Dim>& normal = w.normal[d];  // Eq. 19 normal stress of the momentum cell centred on a cell
  // Interior faces of component d and, along the vertical when open, the top face (a ghost pressure keeps P =
  // P_top there).
  IndexBox<Dim> faces = interior_faces(d);
  if (d == kUp && top_open && grid_.owned.hi[kUp] == cells.hi[kUp]) faces.hi[d] += 1;
  // Lines along axis 0; a thread takes a contiguous block of them. The advection of a line is computed first, as
  // vectorised runs, then the faces one by one.
  const int n = faces.extent(0);
  struct Lines {
    AdvectLine<Dim> g, s;
    std::vector<double> adv_g, adv_s;
  };
  auto face_update = [&](const Index<Dim>& f, double adv_g, double adv_s) {
    const bool top = d == kUp && f[d] == cells.hi[d];
    const Index<Dim> lo = shifted<Dim>(f, d, -1);  // the cell below the face; f names the one above
    const double eg = top ? eps[lo] : 0.5 * (eps[lo] + eps[f]);
    const double es = std::max(1.0 - eg, kEpsSFloor);
    const double beta = top ? beta_c_[lo] : 0.5 * (beta_c_[lo] + beta_c_[f]);
    const double p_above = top ? 2.0 * c.boundary.top_pressure - p[lo] : p[f];
    const double dpdx = (p_above - p[lo]) / h[d];
    const double a_g = eg * rho_g / dt;
    const double rhs_g = a_g * w.g0[d][f] - eg * rho_g * adv_g + eg * rho_g * grav - eg * dpdx;
    if (top || !(std::min(1.0 - eps[lo], 1.0 - eps[f]) > kEpsSTrace)) {
      // Solids cannot leave through the top; on a face with no solids on one side the solids velocity stays
      // as extrapolated from the bed. Only the gas row remains, with the drag of those solids.
      const double v_s = top ? 0.0 : s0[d][f];
      s_.ug[d][f] = (rhs_g + beta * v_s) / (a_g + beta);
      w.dg[d][f] = eg / (a_g + beta);
      s_.us[d][f] = v_s;
      w.ds[d][f] = 0.0;
      return;
    }
    const double dpsdx = (p_s_[f] - p_s_[lo]) / h[d];
    // Eq. 19 stress divergence; the Laplacian diagonal is taken implicitly (point-implicit) for stability.
    double diag = 2.0 * (mu_s_[f] + mu_s_[lo]) / (h[d] * h[d]);
    double visc = (normal[f] - normal[lo]) / h[d];
    for (int b = 0; b < Dim; ++b) {
      if (b == d) continue;
      const int pa = std::min(d, b), qa = std::max(d, b);
      double shear[2];
      for (int high = 0; high < 2; ++high) {
        const Index<Dim> k = high ? shifted<Dim>(f, b, 1) : f;  // the cell edge on this side
        if (!periodic(b) && (k[b] == cells.lo[b] || k[b] == cells.hi[b])) {
          if (b == kUp) {
            shear[high] = 0.0;  // bottom and top are free-slip for the solids
          } else {
            // Side walls slip, or no-slip with the wall half a cell from the face (a sliding wall: relative to it).
            const double mu_w = mu_wall * 0.5 * (mu_s_[lo] + mu_s_[f]);
            const double u_wall = high && b == kSlidingAxis ? c.sliding_wall[static_cast<std::size_t>(d)] : 0.0;
            shear[high] = (high ? -2.0 : 2.0) * mu_w * (s0[d][f] - u_wall) / h[b];
            diag += mu_wall * (mu_s_[lo] + mu_s_[f]) / (h[b] * h[b]);
          }
          continue;
        }
        const auto plane = static_cast<std::size_t>(edge_plane(pa, qa));
        shear[high] = w.shear_edge[plane][k];
        diag += w.mu_edge[plane][k] / (h[b] * h[b]);
      }
      visc += (shear[1] - shear[0]) / h[b];
    }
    visc += diag * s0[d][f];
    const double a_s = es * rho_s / dt;
    const double rhs_s = a_s * s0[d][f] - es * rho_s * adv_s + es * rho_s * grav - es * dpdx - dpsdx + visc;
    const FaceSolve fsol = solve_face(a_g, a_s + diag, beta, rhs_g, rhs_s, eg, es);
    s_.ug[d][f] = fsol.ug;
    s_.us[d][f] = fsol.us;
    w.dg[d][f] = fsol.dg;
    w.ds[d][f] = fsol.ds;
    w.gs[d][f] = fsol.gs;
    w.ss[d][f] = fsol.ss;
  };
  // Each face writes only its own velocities and coefficients: the bits do not depend on the thread count.
  for_each_line_parallel_with(
      faces, [&] { return Lines{AdvectLine<Dim>(n), AdvectLine<Dim>(n), std::vector<double>(n), std::vector<double>(n)}; },
      [&](Lines& l, Index<Dim> f) {
        l.g.template run<d>(c.limiter, w.g0, grid_, f, l.adv_g.data());
        l.s.template run<d>(c.limiter, s0, grid_, f, l.adv_s.data());
        for (int i = 0; i < n; ++i, ++f[0]) face_update(f, l.adv_g[static_cast<std::size_t>(i)], l.adv_s[static_cast<std::size_t>(i)]);
      });
  for (Field<Dim>* x : {&s_.ug[d], &s_.us[d], &w.dg[d], &w.ds[d], &w.gs[d], &w.ss[d]}) tie(*x);
}

template <int Dim>
void TfmSolver<Dim>::set_boundary_faces(double t) {
  const IndexBox<Dim>& cells = grid_.domain;
  const IndexBox<Dim>& own = grid_.owned;
  const bool top_open = config_.boundary.top == TopBoundary::PressureOutlet;
  // Jets, the start-up ramp and the distributor non-uniformity, as for the CFD-DEM gas (src/fluid/gas_boundary).
  std::vector<double>& inlet = w_->inlet;
  inlet_superficial_profile<Dim>(config_.boundary, grid_, t, inlet, w_->inlet_work);
  for (int a = 0; a < Dim; ++a)
    for (bool high : {false, true}) {
      if (periodic(a)) continue;  // no wall: face 0 is an unknown of the momentum step
      if (high ? own.hi[a] != cells.hi[a] : own.lo[a] != cells.lo[a]) continue;  // this block has no such side
      IndexBox<Dim> side = own.faces(a);
      side.lo[a] = high ? cells.hi[a] : cells.lo[a];
      side.hi[a] = side.lo[a] + 1;
      for_each(side, [&](const Index<Dim>& f) {
        if (a != kUp) {
          s_.ug[a][f] = s_.us[a][f] = 0.0;  // walls
        } else if (!high) {
          // The profile lists the domain's bottom faces x fastest (then z).
          std::size_t k = static_cast<std::size_t>(f[0] - cells.lo[0]);
          if constexpr (Dim == 3) k += static_cast<std::size_t>(cells.extent(0)) * static_cast<std::size_t>(f[2] - cells.lo[2]);
          s_.ug[a][f] = inlet[k];  // the distributor
          s_.us[a][f] = 0.0;
        } else {
          s_.us[a][f] = 0.0;
          if (!top_open) s_.ug[a][f] = 0.0;  // the lid
        }
      });
    }
}

template <int Dim>
void TfmSolver<Dim>::face_fractions() {
  // Face volume fractions are the TVD values the continuity uses.
  Work& w = *w_;
  std::vector<double>& es = w.eps_s.data();
  const std::vector<double>& e = s_.eps.data();
  for (std::size_t k = 0; k < es.size(); ++k) es[k] = 1.0 - e[k];  // the ghosts too: they repeat the boundary
  side_by_side(two_tasks(static_cast<long>(grid_.owned.count())),
               [&] { tvd_face_values(grid_, config_.limiter, s_.eps, FaceVelocity<Dim>{s_.ug, grid_.periodic}, w.eg); },
               [&] { tvd_face_values(grid_, config_.limiter, w.eps_s, FaceVelocity<Dim>{s_.us, grid_.periodic}, w.es); });
  for_each_bottom([&](const Index<Dim>& c) { w.eg[kUp][c] = 1.0; });  // gas enters through the distributor undiluted
}

template <int Dim>
void TfmSolver<Dim>::outflow(Eigen::VectorXd& out_g, Eigen::VectorXd& out_s) const {
  // Net outflow of gas and of solids volume from every cell with the current face velocities.
  const Work& w = *w_;
  const IndexBox<Dim>& cells = grid_.owned;
  const int n = static_cast<int>(cells.count());
  out_g.resize(n);
  out_s.resize(n);
  std::array<double, Dim> area{};
  for (int a = 0; a < Dim; ++a) area[a] = face_area(grid_, a);
  // Along lines of axis 0 (unit stride in every field, consecutive rows), each axis's four face fields read
  // through pointers at the line's start: the sums in axis order as cell by cell.
  const int n0 = cells.extent(0);
  IndexBox<Dim> lines = cells;
  lines.hi[0] = lines.lo[0] + 1;
  for_each(lines, [&](const Index<Dim>& c) {
    std::array<const double*, Dim> eg{}, ug{}, es{}, us{};
    std::array<std::ptrdiff_t, Dim> seg{}, sug{}, ses{}, sus{};  // each field's stride to the face above
    for (int a = 0; a < Dim; ++a) {
      eg[a] = w.eg[a].data().data() + w.eg[a].index(c);
      ug[a] = s_.ug[a].data().data() + s_.ug[a].index(c);
      es[a] = w.es[a].data().data() + w.es[a].index(c);
      us[a] = s_.us[a].data().data() + s_.us[a].index(c);
      seg[a] = static_cast<std::ptrdiff_t>(w.eg[a].stride(a));
      sug[a] = static_cast<std::ptrdiff_t>(s_.ug[a].stride(a));
      ses[a] = static_cast<std::ptrdiff_t>(w.es[a].stride(a));
      sus[a] = static_cast<std::ptrdiff_t>(s_.us[a].stride(a));
    }
    double* og_out = out_g.data() + cell_row(cells, c);
    double* os_out = out_s.data() + cell_row(cells, c);
    for (int i = 0; i < n0; ++i) {
      double og = 0.0, os = 0.0;
      for (int a = 0; a < Dim; ++a) {
        const double tg = area[a] * (eg[a][seg[a] + i] * ug[a][sug[a] + i] - eg[a][i] * ug[a][i]);
        const double ts = area[a] * (es[a][ses[a] + i] * us[a][sus[a] + i] - es[a][i] * us[a][i]);
        og = a == 0 ? tg : og + tg;
        os = a == 0 ? ts : os + ts;
      }
      og_out[i] = og;
      os_out[i] = os;
    }
  });
}

template <int Dim>
void TfmSolver<Dim>::correct_pressure(double dt, bool same_matrix) {
  // Both phases are incompressible, so the mixture volume flux must be divergence-free (Eqs. 15 + 16); that
  // fixes the gas-pressure correction P'. The second call (after the E' correction) has the same coefficients:
  // it reuses the first call's factorisation instead of factorising the same matrix again.
  Work& w = *w_;
  const IndexBox<Dim>& cells = grid_.owned;
  const bool top_open = config_.boundary.top == TopBoundary::PressureOutlet;
  auto top_faces = [&]() {  // the outlet's faces in this block (none below the top)
    IndexBox<Dim> top = cells.faces(kUp);
    top.lo[kUp] = grid_.domain.hi[kUp];
    top.hi[kUp] = cells.hi[kUp] == grid_.domain.hi[kUp] ? top.lo[kUp] + 1 : top.lo[kUp];
    return top;
  };
  if (!same_matrix) {
    // Interior faces couple neighbours; the open top couples to P' = 0 on the outlet face, half a cell above
    // the centre.
    for (int a = 0; a < Dim; ++a) {
      w.a[a].fill(0.0);
      const double ratio = face_area(grid_, a) / grid_.h[a];
      for_each(interior_faces(a), [&](const Index<Dim>& f) {
        w.a[a][f] = ratio * (w.eg[a][f] * w.dg[a][f] + w.es[a][f] * w.ds[a][f]);
      });
    }
    if (top_open) {
      const double area = face_area(grid_, kUp), dy = grid_.h[kUp];
      for_each(top_faces(), [&](const Index<Dim>& f) { w.a[kUp][f] = 2.0 * area * w.eg[kUp][f] * w.dg[kUp][f] / dy; });
    }
  }
  outflow(w.out_g, w.out_s);
  for_each(cells, [&](const Index<Dim>& c) {
    const int r = cell_row(cells, c);
    w.rhs_p[c] = -(w.out_g[r] + w.out_s[r]);
  });
  w.p_corr.fill(0.0);
  try {
    w.pressure->solve(w.a, w.rhs_p, w.p_corr, same_matrix);
  } catch (const Error& e) {
    throw_simulation_error(fmt::format(
        "{}: {} (mixture volume constraint, Eqs. 15 + 16). Likely cause: face velocities that are no longer finite "
        "(a solids stress or drag that overflowed). Remedy: {}", step_label(dt), e.what(), remedy()));
  }
  halo(w.p_corr);  // a face on the block's edge (or a periodic face 0) reads the cell beyond through the ghost
  const Field<Dim>& pc = w.p_corr;
  for (int a = 0; a < Dim; ++a) {
    for_each(interior_faces(a), [&](const Index<Dim>& f) {
      const double g = (pc[f] - pc[shifted<Dim>(f, a, -1)]) / grid_.h[a];
      s_.ug[a][f] -= w.dg[a][f] * g;
      s_.us[a][f] -= w.ds[a][f] * g;
    });
    tie(s_.ug[a]);
    tie(s_.us[a]);
  }
  if (top_open) {
    for_each(top_faces(), [&](const Index<Dim>& f) {
      const Index<Dim> below = shifted<Dim>(f, kUp, -1);
      const double g = (-pc[below] - pc[below]) / grid_.h[kUp];
      s_.ug[kUp][f] -= w.dg[kUp][f] * g;
      s_.us[kUp][f] -= w.ds[kUp][f] * g;
    });
  }
  for_each(cells, [&](const Index<Dim>& c) { s_.p[c] += pc[c]; });
  halo(s_.p);
}

template <int Dim>
void TfmSolver<Dim>::solids_fraction_rows(double dt) {
  // The solids pressure is made implicit by a solids volume fraction correction E' (as in MFIX): the solids
  // continuity (Eq. 16) must hold with P_s + K E', K = dP_s/d eps_s, so the stiff compaction limit does not limit
  // dt: (V/dt) E' - sum_faces es ss K grad E' = -(solids outflow). Solved for W = K E' the matrix would be
  // symmetric, but K vanishes in dilute cells, so E' is the unknown. Row of cell P:
  // (V/dt + K_P sum_f a_f) E'_P - sum_f a_f K_nb E'_nb, a_f the face's area / distance times its solids flux
  // response, written in place into the fixed pattern.
  Work& w = *w_;
  const IndexBox<Dim>& cells = grid_.owned;
  const IndexBox<Dim>& dom = grid_.domain;
  const double vol = grid_.cell_measure();
  std::array<double, Dim> ratio{};
  for (int a = 0; a < Dim; ++a) ratio[a] = face_area(grid_, a) / grid_.h[a];
  for_each(cells, [&](const Index<Dim>& cell) {
    std::array<double, 2 * Dim> coef{}, k{};
    for (int a = 0; a < Dim; ++a) {
      const Index<Dim> hi = shifted<Dim>(cell, a, 1);
      const bool has_lo = periodic(a) || cell[a] > dom.lo[a], has_hi = periodic(a) || cell[a] + 1 < dom.hi[a];
      coef[2 * a] = has_lo ? ratio[a] * w.es[a][cell] * w.ss[a][cell] : 0.0;
      coef[2 * a + 1] = has_hi ? ratio[a] * w.es[a][hi] * w.ss[a][hi] : 0.0;
      k[2 * a] = has_lo ? dps_deps_[shifted<Dim>(cell, a, -1)] : 0.0;
      k[2 * a + 1] = has_hi ? dps_deps_[hi] : 0.0;
    }
    double sum = coef[0];
    for (int m = 1; m < 2 * Dim; ++m) sum += coef[m];
    std::array<double, 2 * Dim> off{};
    for (int m = 0; m < 2 * Dim; ++m) off[m] = -coef[m] * k[m];
    w.e_solver->set_row(cell_row(cells, cell), vol / dt + dps_deps_[cell] * sum, off);
  });
}

template <int Dim>
void TfmSolver<Dim>::e_correction_failed(double dt, const LinearSolveOutcome& e_res) const {
  // Name the cell: the row that is not finite (a global row), else the stiffest cell (largest dP_s/d eps_s; the
  // smallest index among equals), found over every rank; its owner words the message.
  const IndexBox<Dim>& dom = grid_.domain;
  double key = e_res.bad_row;
  if (e_res.bad_row < 0) {
    double worst = -1.0, mine = 0.0;
    for_each(grid_.owned, [&](const Index<Dim>& x) {
      if (dps_deps_[x] > worst) {
        worst = dps_deps_[x];
        mine = cell_row(dom, x);
      }
    });
    const double top = comm_.max(worst);
    key = -comm_.max(worst == top ? -mine : -1e300);
  }
  const Index<Dim> bad = cell_at(dom, static_cast<long>(key));
  std::optional<std::string> msg;
  if (grid_.owned.contains(bad)) {
    msg = fmt::format(
        "{}: the solids-fraction correction (implicit solids pressure, E' equation) failed: {}. At {}: voidage "
        "{:.4g}, solids pressure {:.4g} Pa, dP_s/d eps_s {:.4g} Pa, granular temperature {:.4g} m^2/s^2. Likely "
        "cause: a solids pressure that is not finite or too stiff for the step (a voidage far below eps*, or a "
        "runaway granular temperature). Remedy: {}",
        step_label(dt), e_res.why, where(bad), s_.eps[bad], p_s_[bad], dps_deps_[bad], s_.theta[bad], remedy());
  }
  fail_together(msg, key);
  throw_simulation_error("tfm: the solids-fraction correction failed");  // not reached: one rank owns the cell
}

template <int Dim>
void TfmSolver<Dim>::correct_solids_fraction(double dt) {
  // The E' system (rows by solids_fraction_rows) with the solids outflow after the first P' correction.
  const TfmConfig& c = config_;
  Work& w = *w_;
  const IndexBox<Dim>& cells = grid_.owned;
  outflow(w.out_g, w.out_s);
  w.e_solver->set_tolerance(1e-12);
  w.e_solver->set_max_iterations(c.linear_max_iterations);
  w.e_rhs.resize(static_cast<std::size_t>(w.out_s.size()));
  for (std::size_t r = 0; r < w.e_rhs.size(); ++r) w.e_rhs[r] = -w.out_s[static_cast<Eigen::Index>(r)];
  std::vector<double>& e_corr = w.e_corr;
  e_corr.clear();  // a zero initial guess
  const LinearSolveOutcome e_res = w.e_solver->solve(w.e_rhs, e_corr);
  if (e_res.fell_back) ++linear_fallbacks_;
  if (!e_res.ok) e_correction_failed(dt, e_res);  // the same outcome on every rank
  for_each(cells, [&](const Index<Dim>& x) { w.e_field[x] = e_corr[static_cast<std::size_t>(cell_row(cells, x))]; });
  halo(w.e_field);  // the faces on the block's edge (and a periodic face 0) read the cell beyond
  auto wk = [&](const Index<Dim>& x) { return dps_deps_[x] * w.e_field[x]; };
  for (int a = 0; a < Dim; ++a) {
    for_each(interior_faces(a), [&](const Index<Dim>& f) {
      const double g = (wk(f) - wk(shifted<Dim>(f, a, -1))) / grid_.h[a];
      s_.ug[a][f] -= w.gs[a][f] * g;
      s_.us[a][f] -= w.ss[a][f] * g;
    });
    tie(s_.ug[a]);
    tie(s_.us[a]);
  }
  correct_pressure(dt, true);
}

template <int Dim>
void TfmSolver<Dim>::solids_continuity(double dt) {
  const TfmConfig& c = config_;
  Work& w = *w_;
  // Eq. 16, fully implicit with the limiter by deferred correction, as conservative face fluxes (per unit area).
  try {
    advance_scalar_implicit(grid_, c.limiter, w.eps_s, FaceVelocity<Dim>{s_.us, grid_.periodic}, dt, c.mass_corrections, w.fs,
                            c.linear_max_iterations, &linear_fallbacks_, &w.transport, comm_);
  } catch (const Error& e) {
    throw_simulation_error(fmt::format("{}: {}. Remedy: {}", step_label(dt), e.what(), remedy()));
  }
  for (int a = 0; a < Dim; ++a) w.fs_unlimited[a].data() = w.fs[a].data();
  // Packing limit (docs/model-tfm.md): eps >= eps* - max_compaction exactly. The solids pressure stiffens the bed
  // only through a linearisation, so the bound is kept on the fluxes: inflows into a cell that would pass it are
  // scaled down (Zalesak-type one-sided limiter, Jacobi sweeps: no dependence on a sweep order).
  packing_sweeps_ = limit_packing(grid_, w.eps_s, dt, 1.0 - (c.eps_star - packing_allowance(c)), w.fs, 1000, comm_).sweeps;
  w.eps_s_new = conservative_update(grid_, w.eps_s, w.fs, dt);
}

template <int Dim>
void TfmSolver<Dim>::close_gas_continuity(double dt) {
  // Face velocities follow the fluxes the continuity used, so momentum sees what the continuity did: a limited
  // solids face is slowed by its factor; the gas carries the mixture flux that the pressure correction made
  // divergence-free (with its face fractions eg, es) minus the solids flux actually moved, so Eq. 15 with
  // eps = 1 - eps_s closes on every cell (the gas takes up the difference between the face fractions of the
  // correction and of the implicit continuity as well as the volume the limiter held back).
  const TfmConfig& c = config_;
  Work& w = *w_;
  const IndexBox<Dim>& cells = grid_.owned;
  for (int a = 0; a < Dim; ++a) {
    w.fg_shift[a].fill(0.0);
    for_each(cells.faces(a), [&](const Index<Dim>& f) { w.fs_corr[a][f] = w.es[a][f] * s_.us[a][f]; });
  }
  transfer_to_gas(w.fs_corr, w.fs, w.fg_shift);
  for (int a = 0; a < Dim; ++a)
    for_each(cells.faces(a), [&](const Index<Dim>& f) {
      const double f_old = w.fs_unlimited[a][f], f_new = w.fs[a][f], shift = w.fg_shift[a][f];
      if (f_new != f_old && f_old != 0.0) s_.us[a][f] *= f_new / f_old;
      if (shift != 0.0) s_.ug[a][f] += shift / w.eg[a][f];
    });

  // Gas continuity residual of this step (Eq. 15 with the face voidages of the step), before eps is replaced.
  {
    const double vol = grid_.cell_measure();
    std::array<double, Dim> area{};
    for (int a = 0; a < Dim; ++a) area[a] = face_area(grid_, a);
    // Each x-line summed in order, the lines exactly: the same bits on any number of ranks (x is never cut).
    ExactSum sum;
    double line = 0.0;
    for_each(cells, [&](const Index<Dim>& x) {
      const double accumulation = vol * ((1.0 - w.eps_s_new[x]) - s_.eps[x]) / dt;
      double out = 0.0;
      for (int a = 0; a < Dim; ++a) {
        const Index<Dim> hi = shifted<Dim>(x, a, 1);
        const double t = area[a] * (w.eg[a][hi] * s_.ug[a][hi] - w.eg[a][x] * s_.ug[a][x]);
        out = a == 0 ? t : out + t;
      }
      line = x[0] == cells.lo[0] ? std::abs(accumulation + out) : line + std::abs(accumulation + out);
      if (x[0] == cells.hi[0] - 1) sum.add(line);
    });
    // Normalised as the gas solver's mass residual (src/fluid/gas_solver.cpp), in volume rather than mass:
    // by the largest of the inlet flow, the largest gas face speed times the bottom area, and a round-off floor.
    ExactSum inflow_sum;
    double speed = 0.0;
    for_each_bottom([&](const Index<Dim>& f) { inflow_sum.add(area[kUp] * s_.ug[kUp][f]); });
    for (int a = 0; a < Dim; ++a)
      for_each(cells.faces(a), [&](const Index<Dim>& f) { speed = std::max(speed, std::abs(s_.ug[a][f])); });
    const double residual = comm_.sum(sum), inflow = comm_.sum(inflow_sum);
    speed = comm_.max(speed);
    const double bottom = bottom_area();
    const double v_floor = std::max(1e-12, 1e-6 * std::sqrt(gravity_norm() * grid_.length(kUp)));
    s_.gas_residual = residual / std::max({std::abs(inflow), speed * bottom, v_floor * bottom});
  }

  // eps = 1 - eps_s closes Eq. 15.
  double dense_change = 0.0;
  for_each(cells, [&](const Index<Dim>& x) {
    const double eps_new = 1.0 - w.eps_s_new[x];
    // Only compaction below eps* matters: that is where the solids pressure stiffens exponentially.
    if (eps_new < c.eps_star) dense_change = std::max(dense_change, s_.eps[x] - eps_new);
    s_.eps[x] = eps_new;
  });
  fill_ghosts(s_.eps);
  w.dense_change = comm_.max(dense_change);
}

template <int Dim>
double TfmSolver<Dim>::reference_speed() const {
  const GasBoundaryConfig& b = config_.boundary;
  // The largest inflow any region's schedule reaches (pulses and tables included), noise on top.
  const double u_in = inlet_peak_velocity(b) * (1.0 + b.inlet_noise);
  // The fall along the domain's diagonal, its longest straight path: gravity may point along any axis (a periodic
  // channel driven along x has no height to fall).
  double diagonal2 = 0.0;
  for (int a = 0; a < Dim; ++a) diagonal2 += grid_.length(a) * grid_.length(a);
  // A sliding wall drags the solids at its own speed.
  double wall2 = 0.0;
  for (double v : config_.sliding_wall) wall2 += v * v;
  return u_in / config_.eps_star + std::sqrt(2.0 * gravity_norm() * std::sqrt(diagonal2)) + std::sqrt(wall2);
}

template <int Dim>
std::string TfmSolver<Dim>::step_label(double dt) const {
  return fmt::format("tfm at t = {:.6g} s (step {}, dt = {:.3g} s)", s_.time, s_.steps, dt);
}

template <int Dim>
std::string TfmSolver<Dim>::where(const Index<Dim>& c) const {
  std::string s = fmt::format("cell {} at x = {:.3f} m, y = {:.3f} m", index_name<Dim>(c), (c[0] + 0.5) * grid_.h[0],
                              (c[1] + 0.5) * grid_.h[1]);
  if constexpr (Dim == 3) s += fmt::format(", z = {:.3f} m", (c[2] + 0.5) * grid_.h[2]);
  return s;
}

template <int Dim>
std::string TfmSolver<Dim>::remedy() const {
  std::string r;
  if (config_.rheology == SolidsRheology::KineticTheory && config_.e > 0.95) {
    r = fmt::format("lower tfm.restitution (now {:g}; the paper: 0.9): nearly elastic particles dissipate almost no "
                    "granular energy (K4 ~ 1 - e^2, Eq. 25), so Theta and the solids pressure grow with the shear, "
                    "and a smaller time step does not cure it; otherwise ", config_.e);
  }
  return r + fmt::format("lower tfm.cfl (now {:g}) or tfm.dt_max (now {:g} s), and check the inlet and jet velocities "
                         "against the bed's minimum fluidization velocity", config_.cfl, config_.dt_max);
}

template <int Dim>
void TfmSolver<Dim>::check_health(double dt) const {
  const IndexBox<Dim>& cells = grid_.owned;
  const IndexBox<Dim>& dom = grid_.domain;
  const double t = s_.time;
  // The first failure in the order one process scans the domain (cells, then the faces axis by axis, then Theta):
  // each rank keeps its first with that position as key, and every rank reports the smallest (fail_together).
  std::optional<std::string> first;
  double first_key = 0.0;
  auto fail = [&](const std::string& what, const Index<Dim>& c, const std::string& cause, double key) {
    if (first) return;
    first = fmt::format("tfm: the run went bad at t = {:.6g} s (step {}, dt = {:.3g} s): {} in {}. Likely cause: {}. "
                        "Remedy: {}", t, s_.steps, dt, what, where(c), cause, remedy());
    first_key = key;
  };
  const double n_cells = static_cast<double>(dom.count());
  double n_faces = 0.0;
  for (int a = 0; a < Dim; ++a) n_faces = std::max(n_faces, static_cast<double>(dom.faces(a).count()));
  const char* overflow = "a solids pressure or viscosity that overflowed, or a linear solve fed with such values";
  // The deferred TVD correction of the implicit continuity undershoots a little at the bed surface (solids
  // fractions down to -1e-5 in the paper's case); below the trace level that carries no momentum it is a defect.
  constexpr double kVoidageSlack = kEpsSTrace;
  for_each(cells, [&](const Index<Dim>& c) {
    const double e = s_.eps[c];
    if (!std::isfinite(e) || !std::isfinite(s_.p[c]) || !std::isfinite(s_.theta[c])) {
      fail(fmt::format("a non-finite value (voidage {}, pressure {}, granular temperature {})", e, s_.p[c],
                       s_.theta[c]), c, overflow, cell_row(dom, c));
    }
    if (e < -kVoidageSlack || e > 1.0 + kVoidageSlack) {
      fail(fmt::format("the voidage is {:.9g}, outside [0, 1]", e), c,
           "a solids flux out of a cell larger than its content: the time step outran the solids velocity",
           cell_row(dom, c));
    }
  });
  const double v_ref = reference_speed();
  const double v_gas_max = 10.0 * v_ref;
  for (int a = 0; a < Dim; ++a)
    for_each(cells.faces(a), [&](const Index<Dim>& f) {
      const double ug = s_.ug[a][f], us = s_.us[a][f];
      // The common case first: finite and slower than both limits (no cell needs to be looked at).
      if (first || (std::abs(us) <= v_ref && std::abs(ug) <= v_gas_max)) return;
      const double key = n_cells + a * n_faces + cell_row(dom.faces(a), f);
      // The cell on the inner side of the face (the last cell for the high boundary face).
      const Index<Dim> ci = with<Dim>(f, a, std::min(f[a], dom.hi[a] - 1));
      if (!std::isfinite(ug) || !std::isfinite(us)) {
        fail(fmt::format("a non-finite face velocity (gas {}, solids {} m/s)", ug, us), ci, overflow, key);
      }
      // The ghost cell repeats the boundary cell, so a boundary face looks at its one cell twice.
      const bool carries = std::min(1.0 - s_.eps[shifted<Dim>(f, a, -1)], 1.0 - s_.eps[f]) > kEpsSTrace;
      if (carries && std::abs(us) > v_ref) {
        fail(fmt::format("the solids move at {:.4g} m/s, faster than anything that drives them ({:.3g} m/s: the "
                         "fastest interstitial inflow plus free fall along the domain's diagonal)", std::abs(us), v_ref),
             ci, "an instability of the solids momentum", key);
      }
      if (std::abs(ug) > v_gas_max) {
        fail(fmt::format("the gas moves at {:.4g} m/s, ten times the fastest interstitial inflow plus free fall "
                         "({:.3g} m/s)", std::abs(ug), v_ref), ci,
             "an instability of the coupled gas-solids momentum", key);
      }
    });
  // Theta is the mean square fluctuation velocity per direction: its root cannot exceed the speed scale either.
  for_each(cells, [&](const Index<Dim>& c) {
    if (1.0 - s_.eps[c] < kBedSolidsFraction || !(s_.theta[c] > v_ref * v_ref)) return;
    {
      fail(fmt::format("the granular temperature is {:.4g} m^2/s^2 (fluctuation speed {:.4g} m/s, above the {:.3g} "
                       "m/s that drives the bed) at solids fraction {:.3g}",
                       s_.theta[c], std::sqrt(s_.theta[c]), v_ref, 1.0 - s_.eps[c]),
           c, "a runaway granular temperature: production by shear outgrows the collisional dissipation",
           n_cells + Dim * n_faces + cell_row(dom, c));
    }
  });
  fail_together(first, first_key);
}

template <int Dim>
double TfmSolver<Dim>::bed_granular_temperature_max() const {
  double m = 0.0;
  for_each(grid_.owned, [&](const Index<Dim>& c) {
    if (1.0 - s_.eps[c] >= kBedSolidsFraction) m = std::max(m, s_.theta[c]);
  });
  return comm_.max(m);
}

template <int Dim>
double TfmSolver<Dim>::solids_mean_granular_temperature() const {
  ExactSum num_sum, den_sum;  // the same bits on any number of ranks
  for_each(grid_.owned, [&](const Index<Dim>& c) {
    const double es = 1.0 - s_.eps[c];
    num_sum.add(es * s_.theta[c]);
    den_sum.add(es);
  });
  const double num = comm_.sum(num_sum), den = comm_.sum(den_sum);
  return den > 0.0 ? num / den : 0.0;
}

template <int Dim>
void TfmSolver<Dim>::advance_to(double t) {
  // Stop within a rounding distance of t instead of taking a vanishing last step.
  while (t - s_.time > 1e-12 * std::max(1.0, std::abs(t))) advance(t);
}

template <int Dim>
double TfmSolver<Dim>::solids_mass() const {
  ExactSum solids;
  for_each(grid_.owned, [&](const Index<Dim>& c) { solids.add(1.0 - s_.eps[c]); });
  double m = comm_.sum(solids) * config_.rho_s;
  for (int a = 0; a < Dim; ++a) m *= grid_.h[a];
  return m;
}

template <int Dim>
double TfmSolver<Dim>::solids_kinetic_energy() const {
  ExactSum ke;
  for_each(grid_.owned, [&](const Index<Dim>& c) {
    double sq = 0.0;
    for (int a = 0; a < Dim; ++a) {
      const double u = 0.5 * (s_.us[a][c] + s_.us[a][shifted<Dim>(c, a, 1)]);
      sq = a == 0 ? u * u : sq + u * u;
    }
    double e = 0.5 * config_.rho_s * (1.0 - s_.eps[c]) * sq;
    for (int a = 0; a < Dim; ++a) e *= grid_.h[a];
    ke.add(e);
  });
  return comm_.sum(ke);
}

template <int Dim>
double TfmSolver<Dim>::pressure_drop() const {
  ExactSum bottom;
  const int ny = grid_.n(kUp);
  for_each_bottom([&](const Index<Dim>& c) {
    bottom.add(ny > 1 ? 1.5 * s_.p[c] - 0.5 * s_.p[shifted<Dim>(c, kUp, 1)] : s_.p[c]);
  });
  double count = 1.0;  // the bottom faces: nx (nz)
  for (int a = 0; a < Dim; ++a)
    if (a != kUp) count *= grid_.n(a);
  const double top = (config_.boundary.top == TopBoundary::PressureOutlet) ? config_.boundary.top_pressure : 0.0;
  return comm_.sum(bottom) / count - top;
}

template <int Dim>
double TfmSolver<Dim>::contents_weight_per_area() const {
  ExactSum contents;
  for_each(grid_.owned, [&](const Index<Dim>& c) {
    const double e = s_.eps[c];
    contents.add(e * config_.rho_g + (1.0 - e) * config_.rho_s);
  });
  double m = comm_.sum(contents);
  for (int a = 0; a < Dim; ++a) m *= grid_.h[a];
  return m * std::abs(config_.domain.gravity.y) / bottom_area();
}

template <int Dim>
double TfmSolver<Dim>::max_solids_speed() const {
  double vmax = 0.0;
  for (int a = 0; a < Dim; ++a) {
    for_each(interior_faces(a), [&](const Index<Dim>& f) {
      if (std::min(1.0 - s_.eps[shifted<Dim>(f, a, -1)], 1.0 - s_.eps[f]) > 1e-6) {
        vmax = std::max(vmax, std::abs(s_.us[a][f]));
      }
    });
  }
  return comm_.max(vmax);
}

template <int Dim>
double TfmSolver<Dim>::min_voidage() const {
  double m = s_.eps[grid_.owned.lo];
  for_each(grid_.owned, [&](const Index<Dim>& c) { m = std::min(m, s_.eps[c]); });
  return comm_.min(m);
}

template <int Dim>
void TfmSolver<Dim>::gas_velocity_cells(CellVectorField<Dim>& u) const {
  for (int a = 0; a < Dim; ++a) {
    if (!(u[a].box() == grid_.owned)) u[a] = Field<Dim>(grid_.owned, 1);
    for_each(grid_.owned, [&](const Index<Dim>& c) {
      const double low = a == kUp ? vg_interstitial(c) : s_.ug[a][c];
      u[a][c] = 0.5 * (low + s_.ug[a][shifted<Dim>(c, a, 1)]);
    });
  }
}

template <int Dim>
void TfmSolver<Dim>::solids_velocity_cells(CellVectorField<Dim>& u) const {
  for (int a = 0; a < Dim; ++a) {
    if (!(u[a].box() == grid_.owned)) u[a] = Field<Dim>(grid_.owned, 1);
    for_each(grid_.owned, [&](const Index<Dim>& c) { u[a][c] = 0.5 * (s_.us[a][c] + s_.us[a][shifted<Dim>(c, a, 1)]); });
  }
}

namespace {
constexpr const char* kGasNames[3] = {"ug", "vg", "wg"};
constexpr const char* kSolidsNames[3] = {"us", "vs", "ws"};

template <int Dim>
NamedArray named(const char* name, const Field<Dim>& f) {
  NamedArray a{name, f.box().extent(0), f.box().extent(1), f.interior(), 1};
  if constexpr (Dim == 3) a.nz = f.box().extent(2);
  return a;
}
NamedArray scalar(const char* name, double v) { return NamedArray{name, 1, 1, {v}, 1}; }


// The field over the whole domain (`whole`: its kind's domain box) from every rank's part of it (a face plane shared
// by two blocks holds the same bits on both).
template <int Dim>
Field<Dim> gathered(const Comm& comm, const Field<Dim>& f, const IndexBox<Dim>& whole) {
  Field<Dim> all(whole, 0);
  const Field<Dim>* from = &f;
  Field<Dim>* into = &all;
  gather_parts<Dim>(comm, f.box(), std::span(&from, 1), std::span(&into, 1));
  return all;
}
}  // namespace

template <int Dim>
std::vector<NamedArray> TfmSolver<Dim>::save_state() const {
  auto whole = [&](const char* name, const Field<Dim>& f) {
    return comm_.size() == 1 ? named(name, f) : named(name, gathered(comm_, f, domain_of(f)));
  };
  std::vector<NamedArray> out{whole("eps", s_.eps), whole("p", s_.p)};
  for (int a = 0; a < Dim; ++a) out.push_back(whole(kGasNames[a], s_.ug[a]));
  for (int a = 0; a < Dim; ++a) out.push_back(whole(kSolidsNames[a], s_.us[a]));
  out.push_back(whole("theta", s_.theta));
  out.push_back(scalar("time", s_.time));
  out.push_back(scalar("dt", s_.dt));
  out.push_back(scalar("steps", static_cast<double>(s_.steps)));
  out.push_back(scalar("dense_change", s_.dense_change));
  out.push_back(scalar("gas_residual", s_.gas_residual));
  return out;
}

template <int Dim>
void TfmSolver<Dim>::restore_state(const std::vector<NamedArray>& arrays) {
  TfmState<Dim> next = s_;
  auto find = [&](const char* name, int nx, int ny, int nz) -> const NamedArray& {
    for (const NamedArray& a : arrays) {
      if (a.name != name) continue;
      const std::size_t size = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
      if (a.nx != nx || a.ny != ny || a.nz != nz || a.values.size() != size) {
        throw_input_error(std::string("tfm restart: array '") + name + "' does not match the grid");
      }
      return a;
    }
    throw_input_error(std::string("tfm restart: array '") + name + "' is missing");
  };
  auto load = [&](const char* name, Field<Dim>& f) {
    // The arrays cover the domain; a rank takes its block.
    const IndexBox<Dim> b = domain_of(f);
    const std::vector<double>& v = find(name, b.extent(0), b.extent(1), Dim == 3 ? b.extent(Dim - 1) : 1).values;
    if (f.box() == b) {
      f.set_interior(v);
      return;
    }
    for_each(f.box(), [&](const Index<Dim>& c) { f[c] = v[static_cast<std::size_t>(cell_row(b, c))]; });
  };
  load("eps", next.eps);
  load("p", next.p);
  for (int a = 0; a < Dim; ++a) load(kGasNames[a], next.ug[a]);
  for (int a = 0; a < Dim; ++a) load(kSolidsNames[a], next.us[a]);
  load("theta", next.theta);
  next.time = find("time", 1, 1, 1).values[0];
  next.dt = find("dt", 1, 1, 1).values[0];
  next.steps = static_cast<long>(find("steps", 1, 1, 1).values[0]);
  next.dense_change = find("dense_change", 1, 1, 1).values[0];
  // Monitor only, and absent from checkpoints written before it existed: optional.
  next.gas_residual = 0.0;
  for (const NamedArray& a : arrays) {
    if (a.name == "gas_residual" && a.values.size() == 1) next.gas_residual = a.values[0];
  }
  s_ = std::move(next);
  // Checkpoints hold the domain only: the ghosts the step reads (the neighbours' and the periodic images) are
  // rebuilt from it.
  fill_ghosts(s_.eps);
  halo(s_.p);
  halo(s_.theta);
  tie(s_.ug);
  tie(s_.us);
}

template class TfmSolver<2>;
template class TfmSolver<3>;
template Index<2> tfm_blocks<2>(int, const Index<2>&, const std::array<bool, 2>&);
template Index<3> tfm_blocks<3>(int, const Index<3>&, const std::array<bool, 3>&);

}  // namespace fluidbed::tfm
