#include "tfm/tvd_convection.hpp"

#include <algorithm>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <vector>

#include "core/error.hpp"
#include "fluid/stencil_matrix.hpp"

namespace fluidbed::tfm {
namespace {

// Cell value with periodic wrap in x or zero-gradient ghosts (clamped indices).
double cell(const Field2& phi, int i, int j, bool periodic_x) {
  if (periodic_x) {
    i = (i % phi.nx + phi.nx) % phi.nx;
  } else {
    i = std::clamp(i, 0, phi.nx - 1);
  }
  j = std::clamp(j, 0, phi.ny - 1);
  return phi(i, j);
}

double face_u(const FaceVelocity& vel, int i, int j) {
  if (vel.periodic_x && i == vel.u.nx - 1) return vel.u(0, j);
  return vel.u(i, j);
}

// Net outward volumetric flux difference div(U phi) from face values.
void divergence_from_faces(const Grid2& g, const FaceVelocity& vel, const Field2& phi_x, const Field2& phi_y,
                           Field2& out) {
  out = Field2(g.nx, g.ny);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double fe = face_u(vel, i + 1, j) * phi_x(i + 1, j);
      const double fw = face_u(vel, i, j) * phi_x(i, j);
      const double fn = vel.v(i, j + 1) * phi_y(i, j + 1);
      const double fs = vel.v(i, j) * phi_y(i, j);
      out(i, j) = (fe - fw) / g.dx + (fn - fs) / g.dy;
    }
  }
}

}  // namespace

namespace {

// The face loops, compiled once per limiter law.
template <class Law>
void tvd_face_values_of(const Grid2& g, const Field2& phi, const FaceVelocity& vel, Field2& phi_x, Field2& phi_y) {
  const bool per = vel.periodic_x;
  phi_x = Field2(g.nx + 1, g.ny);
  phi_y = Field2(g.nx, g.ny + 1);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      if (!per && (i == 0 || i == g.nx)) {
        phi_x(i, j) = phi(i == 0 ? 0 : g.nx - 1, j);
        continue;
      }
      phi_x(i, j) = tvd::face_value<Law>(face_u(vel, i, j), cell(phi, i - 2, j, per), cell(phi, i - 1, j, per),
                                         cell(phi, i, j, per), cell(phi, i + 1, j, per));
    }
  }
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      if (j == 0 || j == g.ny) {
        phi_y(i, j) = phi(i, j == 0 ? 0 : g.ny - 1);
        continue;
      }
      phi_y(i, j) = tvd::face_value<Law>(vel.v(i, j), cell(phi, i, j - 2, per), cell(phi, i, j - 1, per),
                                         cell(phi, i, j, per), cell(phi, i, j + 1, per));
    }
  }
}

}  // namespace

void tvd_face_values(const Grid2& g, Limiter limiter, const Field2& phi, const FaceVelocity& vel, Field2& phi_x,
                     Field2& phi_y) {
  tvd::with_limiter(limiter, [&](auto law) { tvd_face_values_of<decltype(law)>(g, phi, vel, phi_x, phi_y); });
}

void convective_divergence(const Grid2& g, Limiter limiter, const Field2& phi, const FaceVelocity& vel,
                           Field2& out) {
  Field2 phi_x, phi_y;
  tvd_face_values(g, limiter, phi, vel, phi_x, phi_y);
  divergence_from_faces(g, vel, phi_x, phi_y, out);
}

Field2 conservative_update(const Grid2& g, const Field2& phi_old, const FaceFluxes& f, double dt) {
  Field2 out(g.nx, g.ny);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double fe = f.x(i + 1, j), fw = f.x(i, j), fn = f.y(i, j + 1), fs = f.y(i, j);
      out(i, j) = conservative_cell_update(phi_old(i, j), fe, fw, fn, fs, dt, g.dx, g.dy);
    }
  }
  return out;
}

Field2 advance_scalar_implicit(const Grid2& g, Limiter limiter, const Field2& phi_old, const FaceVelocity& vel,
                               double dt, int corrections) {
  FaceFluxes flux;
  return advance_scalar_implicit(g, limiter, phi_old, vel, dt, corrections, flux);
}

Field2 advance_scalar_implicit(const Grid2& g, Limiter limiter, const Field2& phi_old, const FaceVelocity& vel,
                               double dt, int corrections, FaceFluxes& flux, int linear_max_iterations,
                               int* fallbacks) {
  const int n = g.nx * g.ny;
  const bool per = vel.periodic_x;
  auto id = [&](int i, int j) {
    if (per) i = (i % g.nx + g.nx) % g.nx;
    return static_cast<int>(g.index(i, j));
  };
  // Upwind matrix: (1/dt) phi_P + sum_faces (F+ phi_P - F- phi_nb) / volume-normalised.
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(n) * 5);
  Eigen::VectorXd diag = Eigen::VectorXd::Constant(n, 1.0 / dt);
  auto add_face = [&](int p, int nb, double flux_out) {
    // flux_out: velocity / length leaving cell p through this face.
    // A boundary face takes the cell's own value (zero-gradient ghost), so it always lands on the diagonal.
    if (flux_out > 0.0 || nb < 0) {
      diag[p] += flux_out;
    } else {
      trip.emplace_back(p, nb, flux_out);
    }
  };
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const int p = id(i, j);
      const bool west_bnd = !per && i == 0;
      const bool east_bnd = !per && i == g.nx - 1;
      add_face(p, east_bnd ? -1 : id(i + 1, j), face_u(vel, i + 1, j) / g.dx);
      add_face(p, west_bnd ? -1 : id(i - 1, j), -face_u(vel, i, j) / g.dx);
      add_face(p, j == g.ny - 1 ? -1 : id(i, j + 1), vel.v(i, j + 1) / g.dy);
      add_face(p, j == 0 ? -1 : id(i, j - 1), -vel.v(i, j) / g.dy);
    }
  }
  for (int p = 0; p < n; ++p) trip.emplace_back(p, p, diag[p]);
  Eigen::SparseMatrix<double, Eigen::RowMajor> a(n, n);
  a.setFromTriplets(trip.begin(), trip.end());

  CheckedSparseSolver solver;
  solver.set_tolerance(1e-12);
  solver.set_max_iterations(linear_max_iterations);

  Field2 phi = phi_old;
  for (int pass = 0; pass <= corrections; ++pass) {
    Eigen::VectorXd rhs(n);
    // Deferred correction: the limited part of the face flux, lagged, moves to the right-hand side.
    Field2 corr_div(g.nx, g.ny);
    if (limiter != Limiter::Upwind && pass > 0) {
      // Limited face values less their upwind part: only the limiter's correction remains on each face.
      Field2 phi_x, phi_y;
      tvd_face_values(g, limiter, phi, vel, phi_x, phi_y);
      for (int j = 0; j < g.ny; ++j) {
        for (int i = 0; i <= g.nx; ++i) {
          if (!per && (i == 0 || i == g.nx)) {
            phi_x(i, j) = 0.0;  // boundary faces carry the adjacent cell value in both schemes
            continue;
          }
          phi_x(i, j) -= face_u(vel, i, j) >= 0.0 ? cell(phi, i - 1, j, per) : cell(phi, i, j, per);
        }
      }
      for (int j = 0; j <= g.ny; ++j) {
        for (int i = 0; i < g.nx; ++i) {
          if (j == 0 || j == g.ny) {
            phi_y(i, j) = 0.0;
            continue;
          }
          phi_y(i, j) -= vel.v(i, j) >= 0.0 ? cell(phi, i, j - 1, per) : cell(phi, i, j, per);
        }
      }
      divergence_from_faces(g, vel, phi_x, phi_y, corr_div);
    }
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const int p = id(i, j);
        rhs[p] = phi_old(i, j) / dt - corr_div(i, j);
      }
    }
    Eigen::VectorXd x0(n);
    for (int p = 0; p < n; ++p) x0[p] = phi.v[static_cast<std::size_t>(p)];
    Eigen::VectorXd x = x0;
    const LinearSolveOutcome res = solver.solve(a, rhs, x);
    if (res.fell_back && fallbacks) ++*fallbacks;
    if (!res.ok) {
      const int r = res.bad_row;
      throw_simulation_error(
          "implicit transport of the solids fraction (Eq. 16), pass " + std::to_string(pass) + ": " + res.why +
          (r >= 0 ? " (cell (" + std::to_string(r % g.nx) + ", " + std::to_string(r / g.nx) + "))" : std::string()) +
          "; the face velocities or dt that build the matrix are not finite or not usable");
    }
    for (int p = 0; p < n; ++p) phi.v[static_cast<std::size_t>(p)] = x[p];
    if (limiter == Limiter::Upwind && pass == 0) break;
  }
  // Final face fluxes from the limited face values of the converged phi; with periodic_x face nx repeats face 0.
  Field2 phi_x, phi_y;
  tvd_face_values(g, limiter, phi, vel, phi_x, phi_y);
  flux.x = Field2(g.nx + 1, g.ny);
  flux.y = Field2(g.nx, g.ny + 1);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i <= g.nx; ++i) flux.x(i, j) = face_u(vel, i, j) * phi_x(i, j);
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) flux.y(i, j) = vel.v(i, j) * phi_y(i, j);
  return conservative_update(g, phi_old, flux, dt);
}

}  // namespace fluidbed::tfm
