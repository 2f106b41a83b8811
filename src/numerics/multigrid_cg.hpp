#pragma once
// The pressure backend of a decomposed grid: conjugate gradients preconditioned by a geometric multigrid V-cycle,
// whose iterates are the same bits on any number of ranks and any block layout. What makes them so:
//  - every inner product is summed exactly (ExactSum, reduced exactly over ranks) and rounded once;
//  - the matrix-vector product, the smoother and the transfers compute each cell's value from its own stencil in a
//    fixed order, reading the neighbours' values from ghost layers filled by the halo exchange: the same arithmetic
//    whoever owns the cell;
//  - the smoother is red-black Gauss-Seidel (a cell's colour is the parity of its global index, so the colouring
//    does not depend on the cut), each colour's new values computed from the values before that colour's sweep;
//  - a coarse cell is computed by the rank that owns its first child, from all its children in a fixed order
//    (the other children read from the halo); coarse levels stay split among the ranks while every rank's part
//    keeps 2 cells per axis, and the levels below are solved alike on every rank from the same gathered values;
//  - the chain of levels depends on the domain only.
// The levels are cell-centred aggregates of 2 cells per axis with the scaled Galerkin operator 0.5 P^T A P of
// piecewise-constant prolongation (Braess, "Towards algebraic multigrid for elliptic problems of second order",
// Computing 55, 1995: the factor counters the aggregates' too-weak coarse correction), pre-smoothed red then black
// and post-smoothed black then red, so the preconditioner is symmetric and CG applies (Tatebe, "The multigrid
// preconditioned conjugate gradient method", NASA CP-3224, 1993). The coarsest level (at most 128 cells, and at
// least one level below the grid) is solved by a dense LDL^T factorisation.
#include <memory>

#include "core/grid.hpp"
#include "numerics/pressure_correction.hpp"
#include "parallel/comm.hpp"

namespace fluidbed {

struct MultigridCgOptions {
  double tolerance = 1e-10;   ///< stop at |r| <= tolerance |b| (2-norm, as Eigen's CG)
  int max_iterations = 500;   ///< a solve that has not converged by then fails the run (every rank at once)
  int smoothing_sweeps = 2;   ///< red-black sweep pairs before and after the coarse correction
  /// Inner products as whole lines along x summed in one order (line_dot) and the line sums added exactly, instead
  /// of every term exactly: about ten times cheaper a term, the same bits on any rank count as long as no rank
  /// cuts x (refused by name). The two-fluid model's choice (its blocks span x); the CFD-DEM gas keeps exact terms.
  bool line_sums = false;
};

/// What the last solve did (the same on every rank).
struct MultigridCgStats {
  int iterations = 0;
  double relative_residual = 0.0;
  int levels = 0;  ///< multigrid levels, the fine one and the coarsest included
};

/// The backend over `grid`'s owned box on the ranks of `comm` (which must outlive it). Periodic axes are supported
/// where the owned box spans the domain along them; a periodic axis cut across ranks is refused by name.
template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_multigrid_cg_solver(const Grid<Dim>& grid, const Comm& comm,
                                                                MultigridCgOptions options = {});

/// The statistics of a solver made by make_multigrid_cg_solver (a test and the benchmarks read them).
template <int Dim>
MultigridCgStats multigrid_cg_stats(const StructuredSolver<Dim>& solver);

}  // namespace fluidbed
