#pragma once
// hypre's structured multigrid behind the StructuredSolver interface: conjugate gradients preconditioned by one
// PFMG V-cycle (semi-coarsening multigrid, Ashby and Falgout 1996) on hypre's Struct interface, which takes the
// (2 Dim + 1)-point stencil of the pressure correction as it is. Optional at configure time (FLUIDBED_HAVE_HYPRE).
#include <memory>

#include "numerics/pressure_correction.hpp"

namespace fluidbed {

/// Whether this build has the hypre backend.
bool hypre_available();

/// The hypre PFMG-preconditioned CG backend on the grid's owned box, to a relative residual `tolerance`,
/// warm-started from x. The multigrid hierarchy is set up at the first solve of a gas step and kept for the
/// solves with `reuse_factorisation` (a preconditioner of a nearby matrix; CG still solves the new one).
/// Debian's hypre is built with MPI: MPI is initialised once (MPI_COMM_SELF, one process) if the program has not
/// done so. Throws an input error when the build has no hypre.
template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_hypre_structured_solver(const Grid<Dim>& grid, double tolerance = 1e-12);

}  // namespace fluidbed
