#pragma once
// A direct solve of a pressure correction (the TFM's and the CFD-DEM gas's) for grids whose rows couple only within
// a narrow band: the 2D case (bandwidth = the cells along axis 0, 30 in the paper's bed) and thin 3D slabs. A dense
// band LDL^T factorisation (Golub & Van Loan, Matrix Computations, 4th ed., Alg. 4.3.5) walks contiguous memory and
// vectorises; on the 30 x 50 grid it costs about half of Eigen's sparse LDL^T with AMD ordering, although it does
// about as many operations (docs/performance.md section 17).
#include <memory>

#include "core/grid.hpp"
#include "numerics/pressure_correction.hpp"

namespace fluidbed {

/// Widest band (the product of the cell counts of every axis but the slowest-numbered) for which the band solver
/// is used.
inline constexpr int kMaxPressureBand = 64;

/// What a solve with `reuse_factorisation` does with the last factorisation.
enum class BandReuse {
  /// Substitutes with it and accepts the answer only if it is backward stable for the new coefficients, else
  /// factorises them: exact, for a caller whose second solve has the same matrix (the TFM's E').
  SameMatrix,
  /// Conjugate gradients preconditioned by it, from the caller's guess, to the relative residual of
  /// set_tolerance; a factorisation of the new coefficients when that has not converged within
  /// kBandReuseIterations (the coefficients moved too far): the SIMPLE loop of the CFD-DEM gas, whose
  /// coefficients move a little at every iteration of a step.
  Preconditioner,
};

/// The most preconditioned iterations a Preconditioner solve spends before it factorises instead (a factorisation
/// costs about five substitutions on the paper's grid, docs/performance.md section 35).
inline constexpr int kBandReuseIterations = 8;

/// The StructuredSolver problem (see fluid/pressure_correction.hpp) solved by a band LDL^T of its matrix, rows
/// numbered axis 0 fastest where that band is at most kMaxPressureBand (the 2D beds), else with the longest axis
/// slowest (a thin 3D slab: 30 x 50 x 2 cells have band 60). `reuse` says what a solve with
/// `reuse_factorisation` does; `tolerance` is the Preconditioner reuse's relative residual until set_tolerance
/// changes it. nullptr when no such band is narrow enough, an axis is periodic or the owned box is not the whole
/// domain.
template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_band_structured_solver(const Grid<Dim>& grid,
                                                                   BandReuse reuse = BandReuse::SameMatrix,
                                                                   double tolerance = 1e-12);

}  // namespace fluidbed
