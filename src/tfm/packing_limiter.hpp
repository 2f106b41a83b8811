#pragma once
// Packing limiter on conservative solids volume fluxes (one-sided flux-corrected transport, Zalesak 1979,
// J. Comput. Phys. 31:335): face fluxes into a cell that would pass the packing bound are scaled down until the
// cell lands on the bound, and fluxes out of a cell that would go negative until it lands on zero. Only magnitudes
// shrink, never signs, so the update stays conservative and a zero flux is always feasible. Two-fluid codes bound the phase fraction at its packing limit the same way
// (e.g. OpenFOAM's MULES limiter with alphaMax).
#include "core/field.hpp"
#include "core/grid.hpp"
#include "tfm/tvd_convection.hpp"

namespace fluidbed::tfm {

struct PackingLimitResult {
  int sweeps = 0;         ///< sweeps over the grid, the last one finding no cell over its bound
  int faces_limited = 0;  ///< face scalings applied (a face scaled twice counts twice)
};

/// Scales down the inflow faces of every cell whose conservative update (conservative_update) would exceed
/// max(phi_max, phi_old) (cells already above phi_max may not grow): such a cell ends on that bound, 1e-14 below
/// it so that rounding cannot leave it above. Likewise the outflow faces of a cell whose update would fall below
/// zero (an undershoot of the implicit step's deferred high-order correction; 1 - phi would exceed 1): it ends on
/// zero. Each sweep first finds the factors of every cell from the fluxes the previous sweep left (a Jacobi sweep),
/// then cuts each face by the smaller of its receiving cell's inflow factor and its donor's outflow factor (a face
/// has exactly one of each): the result does not depend on the order of the cells, so the limiter can run on
/// sub-domains with a halo exchange between sweeps. Cutting a face also changes its other cell, so sweeps repeat
/// until no cell is out of its bounds at all (the check has no tolerance, and uses the very expression of
/// conservative_update); after max_sweeps the run fails (simulation error). Where cut cells form a loop of flow,
/// each cut returns to the cell that started it, so the sweeps converge geometrically; the default cap leaves a
/// wide margin. On a periodic axis of the grid face n is face 0 (the same flux on entry): both take the same cut.
/// On a rank's block (grid.owned; `comm` the ranks of the others) the factors' ghosts come from their owners between
/// sweeps and a face shared with a neighbour takes the cut the neighbour gives it: the same bits as on one process.
template <int Dim>
PackingLimitResult limit_packing(const Grid<Dim>& grid, const Field<Dim>& phi_old, double dt, double phi_max,
                                 FaceFluxes<Dim>& flux, int max_sweeps = 1000, const Comm& comm = serial_comm());

/// Keeps the mixture volume flux F_g + F_s of every face when the solids flux changes from `solids_before` to
/// `solids_after`: F_g += solids_before - solids_after, face by face.
template <int Dim>
void transfer_to_gas(const FaceFluxes<Dim>& solids_before, const FaceFluxes<Dim>& solids_after, FaceFluxes<Dim>& gas);

}  // namespace fluidbed::tfm
