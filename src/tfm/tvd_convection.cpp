#include "tfm/tvd_convection.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "numerics/tvd_lines.hpp"
#include "numerics/stencil_matrix.hpp"
#include "numerics/line_loop.hpp"

namespace fluidbed::tfm {

template <int Dim>
void fill_cell_ghosts(Field<Dim>& phi, const std::type_identity_t<std::array<bool, Dim>>& periodic) {
  // One process holding the whole box: the block fill with no owner to ask.
  fill_block_ghosts<Dim>(phi, phi.box(), periodic, serial_comm(), {});
}

template <int Dim>
void fill_face_ghosts(Field<Dim>& f) {
  fill_cell_ghosts<Dim>(f);
}

template <int Dim>
void fill_block_ghosts(Field<Dim>& f, const IndexBox<Dim>& domain, const std::type_identity_t<std::array<bool, Dim>>& periodic,
                       const Comm& comm, std::span<const IndexBox<Dim>> boxes) {
  if (comm.size() > 1) comm.exchange_halo_among(f, boxes, HaloCells::All);
  const IndexBox<Dim>& b = f.box();
  const int g = f.ghost();
  // Axis by axis over the whole span of the other axes (their ghosts included: those inside the domain came from
  // the owners above), so that the edges and corners get what one process gives them.
  for (int a = 0; a < Dim; ++a) {
    const bool per = periodic[static_cast<std::size_t>(a)];
    if (per && (b.lo[a] != domain.lo[a] || b.hi[a] != domain.hi[a]))
      throw_input_error("periodic axis " + std::to_string(a) + " is cut across ranks: cut the other axes");
    const int n = domain.extent(a);
    for (bool high : {false, true}) {
      if (high ? b.hi[a] != domain.hi[a] : b.lo[a] != domain.lo[a]) continue;  // a cut: the owner filled it
      IndexBox<Dim> side = f.allocated();
      side.lo[a] = high ? b.hi[a] : b.lo[a] - g;
      side.hi[a] = high ? b.hi[a] + g : b.lo[a];
      auto source = [&](int i) { return per ? domain.lo[a] + ((i - domain.lo[a]) % n + n) % n : (high ? b.hi[a] - 1 : b.lo[a]); };
      double* v = f.data().data();
      IndexBox<Dim> lines = side;
      lines.hi[0] = lines.lo[0] + 1;
      const int len = side.extent(0);
      for_each(lines, [&](const Index<Dim>& c) {
        double* line = v + f.index(c);  // line[i]: the entry at c[0] + i (axis 0 has unit stride)
        if (a == 0) {
          for (int i = 0; i < len; ++i) line[i] = line[source(c[0] + i) - c[0]];
          return;
        }
        Index<Dim> src = c;
        src[a] = source(c[a]);
        std::copy_n(v + f.index(src), len, line);
      });
    }
  }
}

namespace {

// Net outward flux difference div(U phi) from face values.
template <int Dim>
void divergence_from_faces(const Grid<Dim>& g, const FaceVelocity<Dim>& vel, const FaceFields<Dim>& phi_f,
                           Field<Dim>& out) {
  bool periodic = false;
  for (int a = 0; a < Dim; ++a) periodic = periodic || vel.periodic[a];
  const IndexBox<Dim>& own = g.owned;
  IndexBox<Dim> lines = own;
  lines.hi[0] = lines.lo[0] + 1;
  for_each(lines, [&](Index<Dim> c) {
    std::array<const double*, Dim> pu{}, pf{};
    std::array<std::ptrdiff_t, Dim> su{}, sf{};
    for (int a = 0; a < Dim; ++a) {
      pu[a] = vel.u[a].data().data() + vel.u[a].index(c);
      pf[a] = phi_f[a].data().data() + phi_f[a].index(c);
      su[a] = static_cast<std::ptrdiff_t>(vel.u[a].stride(a));
      sf[a] = static_cast<std::ptrdiff_t>(phi_f[a].stride(a));
    }
    double* o = out.data().data() + out.index(c);
    for (int i = own.lo[0]; i < own.hi[0]; ++i, ++o) {
      c[0] = i;
      double div = 0.0;
      for (int a = 0; a < Dim; ++a) {
        const std::ptrdiff_t k = i - own.lo[0];
        const double u_lo = pu[a][k], u_hi = periodic ? vel.at(a, shifted<Dim>(c, a, 1)) : pu[a][k + su[a]];
        const double term = (u_hi * pf[a][k + sf[a]] - u_lo * pf[a][k]) / g.h[a];
        div = a == 0 ? term : div + term;
      }
      *o = div;
    }
  });
}

// The face loops: each line along axis 0 (unit stride in every field) takes its boundary faces one by one and its
// interior faces as one vectorised run (tvd::face_values), the most frequent stencil of a step.
template <int Dim>
void tvd_face_values_of(const Grid<Dim>& g, Limiter limiter, const Field<Dim>& phi, const FaceVelocity<Dim>& vel,
                        FaceFields<Dim>& phi_f) {
  for (int a = 0; a < Dim; ++a) {
    const bool per = vel.periodic[a];
    const int lo = g.domain.lo[a], hi = g.domain.hi[a];  // the walls (a rank's block computes its cut faces)
    const IndexBox<Dim> faces = g.owned.faces(a);
    const Field<Dim>& u = vel.u[a];
    const auto sp = static_cast<std::ptrdiff_t>(phi.stride(a));
    // A periodic axis reads face n's velocity from face 0.
    const auto wrap = static_cast<std::ptrdiff_t>(u.stride(a)) * (hi - lo);
    const int n = faces.extent(0);
    // Each face writes only its own value: the same bits at any thread count.
    for_each_line_parallel(faces, [&](const Index<Dim>& f) {
      const double* p = phi.data().data() + phi.index(f);
      const double* v = u.data().data() + u.index(f);
      double* out = phi_f[a].data().data() + phi_f[a].index(f);
      if (a != 0) {
        if (!per && (f[a] == lo || f[a] == hi)) {  // a line of boundary faces: the cell inside
          const double* q = f[a] == lo ? p : p - sp;
          for (int i = 0; i < n; ++i) out[i] = q[i];
        } else {
          tvd::face_values(limiter, n, (per && f[a] == hi) ? v - wrap : v, p, sp, out);
        }
        return;
      }
      // Along axis 0 the first and last faces of the line are the boundary ones.
      if (per) {
        for (int i : {0, n - 1}) {
          const double vf = i == n - 1 ? v[i - wrap] : v[i];
          out[i] = tvd::face_value(limiter, vf, p[i - 2], p[i - 1], p[i], p[i + 1]);
        }
      } else {
        out[0] = p[0];
        out[n - 1] = p[n - 2];
      }
      tvd::face_values(limiter, n - 2, v + 1, p + 1, 1, out + 1);
    });
  }
}

template <int Dim>
void ensure_faces(const IndexBox<Dim>& cells, FaceFields<Dim>& f) {
  if (!(f[0].box() == cells.faces(0)) || f[0].ghost() != kGhost) f = FaceFields<Dim>(cells, kGhost);
}

}  // namespace

template <int Dim>
void tvd_face_values(const Grid<Dim>& g, Limiter limiter, const Field<Dim>& phi, const FaceVelocity<Dim>& vel,
                     FaceFields<Dim>& phi_f) {
  ensure_faces(g.owned, phi_f);
  tvd_face_values_of<Dim>(g, limiter, phi, vel, phi_f);
}

template <int Dim>
void convective_divergence(const Grid<Dim>& g, Limiter limiter, const Field<Dim>& phi, const FaceVelocity<Dim>& vel,
                           Field<Dim>& out) {
  FaceFields<Dim> phi_f;
  tvd_face_values(g, limiter, phi, vel, phi_f);
  if (!(out.box() == g.owned)) out = Field<Dim>(g.owned, kGhost);
  divergence_from_faces(g, vel, phi_f, out);
}

template <int Dim>
Field<Dim> conservative_update(const Grid<Dim>& g, const Field<Dim>& phi_old, const FaceFluxes<Dim>& f, double dt) {
  Field<Dim> out(g.owned, kGhost);
  for_each(g.owned, [&](const Index<Dim>& c) { out[c] = conservative_cell_update(g, phi_old, f, c, dt); });
  return out;
}

template <int Dim>
Field<Dim> advance_scalar_implicit(const Grid<Dim>& g, Limiter limiter, const Field<Dim>& phi_old,
                                   const FaceVelocity<Dim>& vel, double dt, int corrections) {
  FaceFluxes<Dim> flux;
  return advance_scalar_implicit(g, limiter, phi_old, vel, dt, corrections, flux);
}

namespace {

// Rows of the implicit transport matrix: cells in storage order, the neighbour across the face on side `high` of
// axis a (wrapped when periodic), -1 beyond a boundary.
template <int Dim>
struct TransportRows {
  IndexBox<Dim> box;
  std::array<bool, Dim> periodic{};
  std::array<int, Dim> stride{};
  TransportRows(const IndexBox<Dim>& b, const std::array<bool, Dim>& per) : box(b), periodic(per) {
    for (int a = 0, st = 1; a < Dim; ++a) {
      stride[a] = st;
      st *= box.extent(a);
    }
  }
  int neighbour(const Index<Dim>& c, int p, int a, bool high) const {
    const int m = box.extent(a);
    const int k = c[a] - box.lo[a] + (high ? 1 : -1);
    if (k >= 0 && k < m) return p + (high ? stride[a] : -stride[a]);
    if (!periodic[a]) return -1;
    return p + (high ? -(m - 1) : (m - 1)) * stride[a];
  }
};

// Upwind rows: (1/dt) phi_P + sum_faces (F+ phi_P - F- phi_nb), per unit volume. A boundary face takes the cell's
// own value (zero-gradient ghost), so it always lands on the diagonal; flux_out is the velocity / length leaving the
// cell through the face. The rows go to the stencil solver kept in `w` (true), unless a periodic axis of one or two
// cells meets the same neighbour through both faces (or the cell itself): the entries then add up, in `tmat`.
template <int Dim>
bool upwind_rows(const Grid<Dim>& g, const FaceVelocity<Dim>& vel, double dt, ImplicitTransportWork<Dim>& w,
                 Eigen::SparseMatrix<double, Eigen::RowMajor>& tmat, const Comm& comm) {
  const IndexBox<Dim>& box = g.owned;
  const IndexBox<Dim>& dom = g.domain;
  const int n = static_cast<int>(box.count());
  bool stencil = true;
  for (int a = 0; a < Dim; ++a) stencil = stencil && !(vel.periodic[a] && dom.extent(a) <= 2);
  if (stencil) {
    if (!w.stencil || !(w.box == box) || w.periodic != vel.periodic) {
      Grid<Dim> rows_grid = g;
      rows_grid.periodic = vel.periodic;
      w.stencil = std::make_unique<StencilBicgstab<Dim>>(rows_grid, comm);
      w.box = box;
      w.periodic = vel.periodic;
      w.cell_boxes = comm.size() > 1 ? all_boxes<Dim>(comm, box) : std::vector<IndexBox<Dim>>{box};
    }
    int p = 0;
    for_each(box, [&](const Index<Dim>& c) {
      double diag = 1.0 / dt;
      std::array<double, 2 * Dim> off{};
      for (int a = 0; a < Dim; ++a) {
        for (bool high : {true, false}) {
          const double flux_out = high ? vel.at(a, shifted<Dim>(c, a, 1)) / g.h[a] : -vel.at(a, c) / g.h[a];
          // A wall of the domain has no neighbour; a cut between ranks has one, on the other rank.
          const bool wall = !vel.periodic[a] && c[a] == (high ? dom.hi[a] - 1 : dom.lo[a]);
          if (flux_out > 0.0 || wall) {
            diag += flux_out;
          } else {
            off[2 * a + (high ? 1 : 0)] = flux_out;
          }
        }
      }
      w.stencil->set_row(p++, diag, off);
    });
    return true;
  }
  if (comm.size() > 1 || !(box == dom))
    throw_input_error("implicit transport: a periodic axis of one or two cells runs on one process only");
  const TransportRows<Dim> rows(box, vel.periodic);
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(n) * (2 * Dim + 1));
  Eigen::VectorXd diag = Eigen::VectorXd::Constant(n, 1.0 / dt);
  auto add_face = [&](int p, int nb, double flux_out) {
    if (flux_out > 0.0 || nb < 0) {
      diag[p] += flux_out;
    } else {
      trip.emplace_back(p, nb, flux_out);
    }
  };
  int row = 0;
  for_each(box, [&](const Index<Dim>& c) {
    const int p = row++;  // for_each runs in row order
    for (int a = 0; a < Dim; ++a) {
      add_face(p, rows.neighbour(c, p, a, true), vel.at(a, shifted<Dim>(c, a, 1)) / g.h[a]);
      add_face(p, rows.neighbour(c, p, a, false), -vel.at(a, c) / g.h[a]);
    }
  });
  for (int p = 0; p < n; ++p) trip.emplace_back(p, p, diag[p]);
  tmat.resize(n, n);
  tmat.setFromTriplets(trip.begin(), trip.end());
  return false;
}

// Deferred correction: the divergence of the limited face values less their upwind part (only the limiter's
// correction remains on each face), lagged on the right-hand side.
template <int Dim>
void limiter_correction(const Grid<Dim>& g, Limiter limiter, const Field<Dim>& phi, const FaceVelocity<Dim>& vel,
                        FaceFields<Dim>& phi_f, Field<Dim>& corr_div) {
  const IndexBox<Dim>& box = g.domain;  // the walls; the faces are the block's
  tvd_face_values(g, limiter, phi, vel, phi_f);
  for (int a = 0; a < Dim; ++a) {
    const IndexBox<Dim> faces = g.owned.faces(a);
    const auto sp = static_cast<std::ptrdiff_t>(phi.stride(a));
    const auto wrap = static_cast<std::ptrdiff_t>(vel.u[a].stride(a)) * box.extent(a);
    const bool per = vel.periodic[a];
    IndexBox<Dim> lines = faces;
    lines.hi[0] = lines.lo[0] + 1;
    for_each(lines, [&](Index<Dim> f) {
      const double* p = phi.data().data() + phi.index(f);
      const double* v = vel.u[a].data().data() + vel.u[a].index(f);
      double* out = phi_f[a].data().data() + phi_f[a].index(f);
      for (int i = faces.lo[0]; i < faces.hi[0]; ++i, ++p, ++v, ++out) {
        f[0] = i;
        if (!per && (f[a] == box.lo[a] || f[a] == box.hi[a])) {
          *out = 0.0;  // boundary faces carry the adjacent cell value in both schemes
          continue;
        }
        const double vf = (per && f[a] == box.hi[a]) ? v[-wrap] : v[0];
        *out -= vf >= 0.0 ? p[-sp] : p[0];
      }
    });
  }
  divergence_from_faces(g, vel, phi_f, corr_div);
}

// A failed solve of a pass, with the cell of its bad row.
template <int Dim>
[[noreturn]] void transport_failed(const IndexBox<Dim>& box, const LinearSolveOutcome& res, int pass) {
  std::string cell;
  if (res.bad_row >= 0) {
    const Index<Dim> c = cell_at(box, res.bad_row);
    cell = " (cell (";
    for (int a = 0; a < Dim; ++a) cell += (a > 0 ? ", " : "") + std::to_string(c[a]);
    cell += "))";
  }
  throw_simulation_error("implicit transport of the solids fraction (Eq. 16), pass " + std::to_string(pass) + ": " +
                         res.why + cell + "; the face velocities or dt that build the matrix are not finite or not usable");
}

// Final face fluxes from the limited face values of the converged phi; a periodic face n repeats face 0.
template <int Dim>
void final_fluxes(const Grid<Dim>& g, Limiter limiter, const Field<Dim>& phi, const FaceVelocity<Dim>& vel,
                  FaceFields<Dim>& phi_f, FaceFluxes<Dim>& flux) {
  const IndexBox<Dim>& box = g.owned;
  tvd_face_values(g, limiter, phi, vel, phi_f);
  ensure_faces(box, flux);
  for (int a = 0; a < Dim; ++a) {
    if (vel.periodic[a]) {
      for_each(box.faces(a), [&](const Index<Dim>& f) { flux[a][f] = vel.at(a, f) * phi_f[a][f]; });
      continue;
    }
    // Same layout (faces of axis a, kGhost layers): one pass over the stored arrays, ghosts included.
    std::vector<double>& out = flux[a].data();
    const std::vector<double>& u = vel.u[a].data();
    const std::vector<double>& v = phi_f[a].data();
    if (vel.u[a].ghost() == kGhost && vel.u[a].box() == flux[a].box()) {
      for (std::size_t k = 0; k < out.size(); ++k) out[k] = u[k] * v[k];
    } else {
      for_each(box.faces(a), [&](const Index<Dim>& f) { flux[a][f] = vel.u[a][f] * phi_f[a][f]; });
    }
  }
}

}  // namespace

template <int Dim>
Field<Dim> advance_scalar_implicit(const Grid<Dim>& g, Limiter limiter, const Field<Dim>& phi_old,
                                   const FaceVelocity<Dim>& vel, double dt, int corrections, FaceFluxes<Dim>& flux,
                                   int linear_max_iterations, int* fallbacks, ImplicitTransportWork<Dim>* work,
                                   const Comm& comm) {
  const IndexBox<Dim>& box = g.owned;
  const int n = static_cast<int>(box.count());
  std::unique_ptr<ImplicitTransportWork<Dim>> local;  // a caller without its own buffers gets fresh ones
  if (!work) {
    local = std::make_unique<ImplicitTransportWork<Dim>>();
    work = local.get();
  }
  ImplicitTransportWork<Dim>& w = *work;
  Eigen::SparseMatrix<double, Eigen::RowMajor> tmat;
  const bool stencil = upwind_rows<Dim>(g, vel, dt, w, tmat, comm);
  // The solution's ghosts: from the ranks that own them, else the walls' zero gradient or the periodic image (one
  // process without the stencil solver: no owner to ask).
  auto fill = [&](Field<Dim>& f) { fill_block_ghosts<Dim>(f, g.domain, vel.periodic, comm, w.cell_boxes); };
  if (stencil) {
    w.stencil->set_tolerance(1e-12);
    w.stencil->set_max_iterations(linear_max_iterations);
  }
  w.solver.set_tolerance(1e-12);
  w.solver.set_max_iterations(linear_max_iterations);
  auto solve = [&](const std::vector<double>& b, std::vector<double>& x) {
    if (stencil) return w.stencil->solve(b, x);
    Eigen::VectorXd xe = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
    const LinearSolveOutcome res =
        w.solver.solve(tmat, Eigen::Map<const Eigen::VectorXd>(b.data(), static_cast<Eigen::Index>(b.size())), xe);
    std::copy_n(xe.data(), x.size(), x.data());
    return res;
  };
  w.rhs.resize(static_cast<std::size_t>(n));
  w.x.resize(static_cast<std::size_t>(n));
  Field<Dim> phi(box, kGhost);
  for_each(box, [&](const Index<Dim>& c) { phi[c] = phi_old[c]; });
  fill(phi);
  Field<Dim> corr_div(box, kGhost);
  FaceFields<Dim>& phi_f = w.phi_f;  // its ghost faces are never written: they stay zero
  std::vector<double>& rhs = w.rhs;
  std::vector<double>& x = w.x;
  for (int pass = 0; pass <= corrections; ++pass) {
    corr_div.fill(0.0);
    if (limiter != Limiter::Upwind && pass > 0) limiter_correction<Dim>(g, limiter, phi, vel, phi_f, corr_div);
    std::size_t r = 0;
    for_each(box, [&](const Index<Dim>& c) {
      rhs[r] = phi_old[c] / dt - corr_div[c];
      x[r++] = phi[c];
    });
    const LinearSolveOutcome res = solve(rhs, x);
    if (res.fell_back && fallbacks) ++*fallbacks;
    if (!res.ok) transport_failed<Dim>(g.domain, res, pass);  // bad_row counts the domain's cells
    r = 0;
    for_each(box, [&](const Index<Dim>& c) { phi[c] = x[r++]; });
    fill(phi);
    if (limiter == Limiter::Upwind && pass == 0) break;
  }
  final_fluxes<Dim>(g, limiter, phi, vel, phi_f, flux);
  return conservative_update(g, phi_old, flux, dt);
}

#define FLUIDBED_TVD_INSTANTIATE(D)                                                                                 \
  template void fill_cell_ghosts<D>(Field<D>&, const std::array<bool, D>&);                                         \
  template void fill_face_ghosts<D>(Field<D>&);                                                                     \
  template void tvd_face_values<D>(const Grid<D>&, Limiter, const Field<D>&, const FaceVelocity<D>&,                \
                                   FaceFields<D>&);                                                                 \
  template void convective_divergence<D>(const Grid<D>&, Limiter, const Field<D>&, const FaceVelocity<D>&,          \
                                         Field<D>&);                                                                \
  template Field<D> conservative_update<D>(const Grid<D>&, const Field<D>&, const FaceFluxes<D>&, double);          \
  template Field<D> advance_scalar_implicit<D>(const Grid<D>&, Limiter, const Field<D>&, const FaceVelocity<D>&,    \
                                               double, int);                                                        \
  template Field<D> advance_scalar_implicit<D>(const Grid<D>&, Limiter, const Field<D>&, const FaceVelocity<D>&,    \
                                               double, int, FaceFluxes<D>&, int, int*, ImplicitTransportWork<D>*,  \
                                               const Comm&);                                                        \
  template void fill_block_ghosts<D>(Field<D>&, const IndexBox<D>&, const std::array<bool, D>&, const Comm&,        \
                                     std::span<const IndexBox<D>>);
FLUIDBED_TVD_INSTANTIATE(2)
FLUIDBED_TVD_INSTANTIATE(3)
#undef FLUIDBED_TVD_INSTANTIATE

}  // namespace fluidbed::tfm
