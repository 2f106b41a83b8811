#pragma once
// Convection of a cell-centred scalar by face velocities on the staggered grid, with a TVD limiter
// (paper section 2.2.1: upwind flux plus a limited 0.5|U|(phi_i - phi_{i-1}) correction).
#include "core/field2.hpp"
#include "core/grid2.hpp"
#include "core/tvd_limiter.hpp"

namespace fluidbed::tfm {

/// The shared TVD limiter family (also the gas solver's).
using Limiter = tvd::Limiter;

/// Staggered velocities that carry the scalar: u on vertical faces ((nx+1) x ny), v on horizontal faces
/// (nx x (ny+1)). With periodic_x, face 0 and face nx are the same face (u(0, j) is used for both).
struct FaceVelocity {
  const Field2& u;
  const Field2& v;
  bool periodic_x = false;
};

/// Limited face values of phi: phi_x on vertical faces, phi_y on horizontal faces. On a non-periodic
/// boundary face the adjacent interior cell value is used (the wall flux is zero anyway; an inflow value
/// is the caller's business).
void tvd_face_values(const Grid2& grid, Limiter limiter, const Field2& phi, const FaceVelocity& vel,
                     Field2& phi_x, Field2& phi_y);

/// div(U phi) per unit volume in every cell, for explicit time stepping.
void convective_divergence(const Grid2& grid, Limiter limiter, const Field2& phi, const FaceVelocity& vel,
                           Field2& out);

/// Conservative face fluxes of a scalar per unit face area (face value times face velocity): x on vertical
/// faces ((nx+1) x ny), y on horizontal faces (nx x (ny+1)), positive in +x / +y.
struct FaceFluxes {
  Field2 x, y;
};

/// One cell of conservative_update, from its east, west, north and south face fluxes.
inline double conservative_cell_update(double phi_old, double fe, double fw, double fn, double fs, double dt, double dx,
                                       double dy) {
  return phi_old - dt * ((fe - fw) / dx + (fn - fs) / dy);
}

/// phi_old - dt div(F) in every cell, div(F) = (F_e - F_w)/dx + (F_n - F_s)/dy: sum(phi * volume) changes only
/// by the boundary fluxes (to rounding).
Field2 conservative_update(const Grid2& grid, const Field2& phi_old, const FaceFluxes& flux, double dt);

/// One backward-Euler step of d(phi)/dt + div(U phi) = 0. The upwind part is implicit; the limiter
/// correction is deferred and refreshed `corrections` times. The result is finally formed from
/// conservative face fluxes, so sum(phi * volume) is conserved to rounding whatever the solver tolerance.
Field2 advance_scalar_implicit(const Grid2& grid, Limiter limiter, const Field2& phi_old, const FaceVelocity& vel,
                               double dt, int corrections = 2);

/// The same step, returning the final face fluxes too: the result equals conservative_update(phi_old, flux, dt).
/// Each linear solve is checked (CheckedSparseSolver: BiCGSTAB, a sparse LU when it stops short; at most
/// `linear_max_iterations` BiCGSTAB iterations, 0 for Eigen's default); a solve neither answers is a simulation
/// error. `fallbacks`, when given, counts the solves the LU answered.
Field2 advance_scalar_implicit(const Grid2& grid, Limiter limiter, const Field2& phi_old, const FaceVelocity& vel,
                               double dt, int corrections, FaceFluxes& flux, int linear_max_iterations = 0,
                               int* fallbacks = nullptr);

}  // namespace fluidbed::tfm
