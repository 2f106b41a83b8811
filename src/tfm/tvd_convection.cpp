#include "tfm/tvd_convection.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "fluid/stencil_matrix.hpp"

namespace fluidbed::tfm {

template <int Dim>
void fill_cell_ghosts(Field<Dim>& phi, const std::type_identity_t<std::array<bool, Dim>>& periodic) {
  const IndexBox<Dim>& b = phi.box();
  const int g = phi.ghost();
  // Axis by axis over the layers already filled along the earlier axes, so that edges and corners are filled too.
  IndexBox<Dim> span = b;
  for (int a = 0; a < Dim; ++a) {
    const int n = b.extent(a);
    for (bool high : {false, true}) {
      for_each(span.outside(a, high, g), [&](const Index<Dim>& c) {
        Index<Dim> src = c;
        if (periodic[a]) {
          src[a] = b.lo[a] + ((c[a] - b.lo[a]) % n + n) % n;
        } else {
          src[a] = high ? b.hi[a] - 1 : b.lo[a];
        }
        phi[c] = phi[src];
      });
    }
    span = span.grown(a, g);
  }
}

template <int Dim>
void fill_face_ghosts(Field<Dim>& f) {
  fill_cell_ghosts<Dim>(f);
}

namespace {

// Net outward flux difference div(U phi) from face values.
template <int Dim>
void divergence_from_faces(const Grid<Dim>& g, const FaceVelocity<Dim>& vel, const FaceFields<Dim>& phi_f,
                           Field<Dim>& out) {
  for_each(g.domain, [&](const Index<Dim>& c) {
    double div = 0.0;
    for (int a = 0; a < Dim; ++a) {
      const Index<Dim> hi = shifted<Dim>(c, a, 1);
      const double term = (vel.at(a, hi) * phi_f[a][hi] - vel.at(a, c) * phi_f[a][c]) / g.h[a];
      div = a == 0 ? term : div + term;
    }
    out[c] = div;
  });
}

// The face loops, compiled once per limiter law.
template <int Dim, class Law>
void tvd_face_values_of(const Grid<Dim>& g, const Field<Dim>& phi, const FaceVelocity<Dim>& vel,
                        FaceFields<Dim>& phi_f) {
  for (int a = 0; a < Dim; ++a) {
    const bool per = vel.periodic[a];
    const int lo = g.domain.lo[a], hi = g.domain.hi[a];
    for_each(g.domain.faces(a), [&](const Index<Dim>& f) {
      if (!per && (f[a] == lo || f[a] == hi)) {
        phi_f[a][f] = phi[f[a] == lo ? f : shifted<Dim>(f, a, -1)];
        return;
      }
      phi_f[a][f] = tvd::face_value<Law>(vel.at(a, f), phi[shifted<Dim>(f, a, -2)], phi[shifted<Dim>(f, a, -1)],
                                         phi[f], phi[shifted<Dim>(f, a, 1)]);
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
  ensure_faces(g.domain, phi_f);
  tvd::with_limiter(limiter, [&](auto law) { tvd_face_values_of<Dim, decltype(law)>(g, phi, vel, phi_f); });
}

template <int Dim>
void convective_divergence(const Grid<Dim>& g, Limiter limiter, const Field<Dim>& phi, const FaceVelocity<Dim>& vel,
                           Field<Dim>& out) {
  FaceFields<Dim> phi_f;
  tvd_face_values(g, limiter, phi, vel, phi_f);
  if (!(out.box() == g.domain)) out = Field<Dim>(g.domain, kGhost);
  divergence_from_faces(g, vel, phi_f, out);
}

template <int Dim>
Field<Dim> conservative_update(const Grid<Dim>& g, const Field<Dim>& phi_old, const FaceFluxes<Dim>& f, double dt) {
  Field<Dim> out(g.domain, kGhost);
  for_each(g.domain, [&](const Index<Dim>& c) { out[c] = conservative_cell_update(g, phi_old, f, c, dt); });
  return out;
}

template <int Dim>
Field<Dim> advance_scalar_implicit(const Grid<Dim>& g, Limiter limiter, const Field<Dim>& phi_old,
                                   const FaceVelocity<Dim>& vel, double dt, int corrections) {
  FaceFluxes<Dim> flux;
  return advance_scalar_implicit(g, limiter, phi_old, vel, dt, corrections, flux);
}

template <int Dim>
Field<Dim> advance_scalar_implicit(const Grid<Dim>& g, Limiter limiter, const Field<Dim>& phi_old,
                                   const FaceVelocity<Dim>& vel, double dt, int corrections, FaceFluxes<Dim>& flux,
                                   int linear_max_iterations, int* fallbacks) {
  const IndexBox<Dim>& box = g.domain;
  const int n = static_cast<int>(box.count());
  // Row of the neighbour across the face on side `high` of axis a (wrapped when periodic), -1 beyond a boundary.
  auto neighbour = [&](Index<Dim> c, int a, bool high) {
    c[a] += high ? 1 : -1;
    if (vel.periodic[a]) {
      const int m = box.extent(a);
      c[a] = box.lo[a] + ((c[a] - box.lo[a]) % m + m) % m;
    } else if (c[a] < box.lo[a] || c[a] >= box.hi[a]) {
      return -1;
    }
    return cell_row(box, c);
  };
  // Upwind matrix: (1/dt) phi_P + sum_faces (F+ phi_P - F- phi_nb), per unit volume.
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(n) * (2 * Dim + 1));
  Eigen::VectorXd diag = Eigen::VectorXd::Constant(n, 1.0 / dt);
  auto add_face = [&](int p, int nb, double flux_out) {
    // flux_out: velocity / length leaving cell p through this face. A boundary face takes the cell's own value
    // (zero-gradient ghost), so it always lands on the diagonal.
    if (flux_out > 0.0 || nb < 0) {
      diag[p] += flux_out;
    } else {
      trip.emplace_back(p, nb, flux_out);
    }
  };
  for_each(box, [&](const Index<Dim>& c) {
    const int p = cell_row(box, c);
    for (int a = 0; a < Dim; ++a) {
      add_face(p, neighbour(c, a, true), vel.at(a, shifted<Dim>(c, a, 1)) / g.h[a]);
      add_face(p, neighbour(c, a, false), -vel.at(a, c) / g.h[a]);
    }
  });
  for (int p = 0; p < n; ++p) trip.emplace_back(p, p, diag[p]);
  Eigen::SparseMatrix<double, Eigen::RowMajor> mat(n, n);
  mat.setFromTriplets(trip.begin(), trip.end());

  CheckedSparseSolver solver;
  solver.set_tolerance(1e-12);
  solver.set_max_iterations(linear_max_iterations);

  Field<Dim> phi(box, kGhost);
  for_each(box, [&](const Index<Dim>& c) { phi[c] = phi_old[c]; });
  fill_cell_ghosts(phi, vel.periodic);
  Field<Dim> corr_div(box, kGhost);
  FaceFields<Dim> phi_f;
  Eigen::VectorXd rhs(n), x(n);
  for (int pass = 0; pass <= corrections; ++pass) {
    // Deferred correction: the limited part of the face flux, lagged, moves to the right-hand side.
    corr_div.fill(0.0);
    if (limiter != Limiter::Upwind && pass > 0) {
      // Limited face values less their upwind part: only the limiter's correction remains on each face.
      tvd_face_values(g, limiter, phi, vel, phi_f);
      for (int a = 0; a < Dim; ++a) {
        for_each(box.faces(a), [&](const Index<Dim>& f) {
          if (!vel.periodic[a] && (f[a] == box.lo[a] || f[a] == box.hi[a])) {
            phi_f[a][f] = 0.0;  // boundary faces carry the adjacent cell value in both schemes
            return;
          }
          phi_f[a][f] -= vel.at(a, f) >= 0.0 ? phi[shifted<Dim>(f, a, -1)] : phi[f];
        });
      }
      divergence_from_faces(g, vel, phi_f, corr_div);
    }
    for_each(box, [&](const Index<Dim>& c) {
      const int p = cell_row(box, c);
      rhs[p] = phi_old[c] / dt - corr_div[c];
      x[p] = phi[c];
    });
    const LinearSolveOutcome res = solver.solve(mat, rhs, x);
    if (res.fell_back && fallbacks) ++*fallbacks;
    if (!res.ok) {
      std::string cell;
      if (res.bad_row >= 0) {
        int r = res.bad_row;
        cell = " (cell (";
        for (int a = 0; a < Dim; ++a) {
          cell += (a > 0 ? ", " : "") + std::to_string(box.lo[a] + r % box.extent(a));
          r /= box.extent(a);
        }
        cell += "))";
      }
      throw_simulation_error("implicit transport of the solids fraction (Eq. 16), pass " + std::to_string(pass) +
                             ": " + res.why + cell +
                             "; the face velocities or dt that build the matrix are not finite or not usable");
    }
    for_each(box, [&](const Index<Dim>& c) { phi[c] = x[cell_row(box, c)]; });
    fill_cell_ghosts(phi, vel.periodic);
    if (limiter == Limiter::Upwind && pass == 0) break;
  }
  // Final face fluxes from the limited face values of the converged phi; a periodic face n repeats face 0.
  tvd_face_values(g, limiter, phi, vel, phi_f);
  ensure_faces(box, flux);
  for (int a = 0; a < Dim; ++a)
    for_each(box.faces(a), [&](const Index<Dim>& f) { flux[a][f] = vel.at(a, f) * phi_f[a][f]; });
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
                                               double, int, FaceFluxes<D>&, int, int*);
FLUIDBED_TVD_INSTANTIATE(2)
FLUIDBED_TVD_INSTANTIATE(3)
#undef FLUIDBED_TVD_INSTANTIATE

}  // namespace fluidbed::tfm
