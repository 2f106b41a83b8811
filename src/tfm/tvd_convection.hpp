#pragma once
// Convection of a cell-centred scalar by face velocities on the staggered grid in Dim = 2 or 3 dimensions, with the
// shared TVD limiter family (paper section 2.2.1: upwind flux plus a limited 0.5|U|(phi_i - phi_{i-1}) correction).
// Fields carry kGhost ghost layers; stencils read them and never clamp (fill_cell_ghosts writes them).
#include <Eigen/Core>
#include <array>
#include <memory>
#include <span>
#include <vector>
#include <type_traits>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "numerics/tvd_limiter.hpp"
#include "numerics/stencil_bicgstab.hpp"
#include "numerics/stencil_matrix.hpp"

namespace fluidbed::tfm {

/// The shared TVD limiter family (also the gas solver's).
using Limiter = tvd::Limiter;

/// Ghost layers of the two-fluid model's cell and face fields: the TVD stencil reads two cells upwind of a face.
inline constexpr int kGhost = 2;

/// Staggered velocities that carry the scalar: u[a] on the faces normal to axis a. With periodic[a], face 0 and
/// face n of axis a are the same face (u[a] at face 0 is used for both) and the cells wrap around.
template <int Dim>
struct FaceVelocity {
  const FaceFields<Dim>& u;
  std::array<bool, Dim> periodic{};

  /// Velocity on face f of axis a (face n of a periodic axis is face 0).
  double at(int a, Index<Dim> f) const {
    if (periodic[a] && f[a] == u[a].box().hi[a] - 1) f[a] = u[a].box().lo[a];
    return u[a][f];
  }
};

/// Conservative face fluxes of a scalar per unit face area (face value times face velocity), component a on the
/// faces normal to axis a, positive along +a.
template <int Dim>
using FaceFluxes = FaceFields<Dim>;

/// Ghost layers of a cell field: each layer repeats the boundary cell (zero gradient, what a wall, an inlet or an
/// outlet leaves a convected scalar), or wraps around along a periodic axis.
template <int Dim>
void fill_cell_ghosts(Field<Dim>& phi, const std::type_identity_t<std::array<bool, Dim>>& periodic = {});
/// Zero-gradient ghost layers of a face field along every axis (the convected velocities beyond the domain).
template <int Dim>
void fill_face_ghosts(Field<Dim>& f);
/// The ghosts of a field on a rank's block: f.box() is this rank's box of that kind of field (its cells, or its
/// faces of an axis), `domain` that kind's box over the whole domain and boxes[r] rank r's. First the ghosts inside
/// the domain from the ranks that own them, then, axis by axis over the whole span of the other axes (their ghosts
/// included), the wall's zero gradient or the periodic image; a periodic axis must span the block (else an input
/// error). fill_cell_ghosts is this on one process with f.box() = domain.
template <int Dim>
void fill_block_ghosts(Field<Dim>& f, const IndexBox<Dim>& domain, const std::type_identity_t<std::array<bool, Dim>>& periodic,
                       const Comm& comm, std::span<const IndexBox<Dim>> boxes);

/// Limited face values of phi (ghosts filled) on every face. On a non-periodic boundary face the adjacent cell's
/// value is used (the wall flux is zero anyway; an inflow value is the caller's business).
template <int Dim>
void tvd_face_values(const Grid<Dim>& grid, Limiter limiter, const Field<Dim>& phi, const FaceVelocity<Dim>& vel,
                     FaceFields<Dim>& phi_f);

/// div(U phi) per unit volume in every cell (phi with ghosts filled), for explicit time stepping.
template <int Dim>
void convective_divergence(const Grid<Dim>& grid, Limiter limiter, const Field<Dim>& phi,
                           const FaceVelocity<Dim>& vel, Field<Dim>& out);

/// phi_old - dt div(F) in cell c, div(F) = sum over axes of (F_high - F_low) / h, axes in order.
template <int Dim>
inline double conservative_cell_update(const Grid<Dim>& g, const Field<Dim>& phi_old, const FaceFluxes<Dim>& f,
                                       const std::type_identity_t<Index<Dim>>& c, double dt) {
  double div = (f[0][shifted<Dim>(c, 0, 1)] - f[0][c]) / g.h[0];
  for (int a = 1; a < Dim; ++a) div += (f[a][shifted<Dim>(c, a, 1)] - f[a][c]) / g.h[a];
  return phi_old[c] - dt * div;
}

/// conservative_cell_update in every cell: sum(phi * volume) changes only by the boundary fluxes (to rounding).
template <int Dim>
Field<Dim> conservative_update(const Grid<Dim>& grid, const Field<Dim>& phi_old, const FaceFluxes<Dim>& flux,
                               double dt);

/// One backward-Euler step of d(phi)/dt + div(U phi) = 0. The upwind part is implicit; the limiter correction is
/// deferred and refreshed `corrections` times. The result is formed from conservative face fluxes (returned in
/// `flux`), so sum(phi * volume) is conserved to rounding whatever the solver tolerance. Each linear solve is
/// checked (StencilBicgstab: BiCGSTAB, a sparse LU when it stops short; at most `linear_max_iterations`
/// BiCGSTAB iterations, 0 for twice the cell count); a solve neither answers is a simulation error. `fallbacks`, when
/// given, counts the solves the LU answered. phi_old's ghosts are not read. On a rank's block (grid.owned, x spanned,
/// `comm` the ranks of the others) every owned cell and every face of the block is computed, the faces shared with a
/// neighbour from the same ghosts as the neighbour's: the same bits as on one process.
/// What advance_scalar_implicit keeps from one call to the next (matrix pattern, solver, work arrays), so that a
/// step allocates nothing: one per convected scalar. The results do not depend on it.
template <int Dim>
struct ImplicitTransportWork {
  IndexBox<Dim> box{};
  std::array<bool, Dim> periodic{};
  /// The rows' solver (StencilBicgstab: the same bits on any rank count); a periodic axis of one or two cells,
  /// where a row meets one neighbour through both faces, takes an assembled matrix and the checked Eigen solver.
  std::unique_ptr<StencilBicgstab<Dim>> stencil;
  std::vector<IndexBox<Dim>> cell_boxes;  ///< every rank's block (the halo partners of the solution's ghosts)
  CheckedSparseSolver solver;
  FaceFields<Dim> phi_f;
  std::vector<double> rhs, x;
};

template <int Dim>
Field<Dim> advance_scalar_implicit(const Grid<Dim>& grid, Limiter limiter, const Field<Dim>& phi_old,
                                   const FaceVelocity<Dim>& vel, double dt, int corrections, FaceFluxes<Dim>& flux,
                                   int linear_max_iterations = 0, int* fallbacks = nullptr,
                                   ImplicitTransportWork<Dim>* work = nullptr, const Comm& comm = serial_comm());
/// The same step without the fluxes.
template <int Dim>
Field<Dim> advance_scalar_implicit(const Grid<Dim>& grid, Limiter limiter, const Field<Dim>& phi_old,
                                   const FaceVelocity<Dim>& vel, double dt, int corrections = 2);

/// Area of a face normal to axis a (a length per metre of depth in 2D): the other cell sizes multiplied in axis
/// order, so that 2D keeps its single factor exactly.
template <int Dim>
inline double face_area(const Grid<Dim>& g, int a) {
  double m = 1.0;
  for (int b = 0; b < Dim; ++b)
    if (b != a) m *= g.h[b];
  return m;
}

}  // namespace fluidbed::tfm
