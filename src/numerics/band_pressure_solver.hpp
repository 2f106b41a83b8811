#pragma once
// A direct solve of the TFM's gas-pressure correction for grids whose rows couple only within a narrow band: the
// 2D case (bandwidth = the cells along axis 0, 30 in the paper's bed) and thin 3D slabs. A dense band
// LDL^T factorisation (Golub & Van Loan, Matrix Computations, 4th ed., Alg. 4.3.5) walks contiguous memory and
// vectorises; on the 30 x 50 grid it costs about half of Eigen's sparse LDL^T with AMD ordering, although it does
// about as many operations (docs/performance.md section 17).
#include <memory>

#include "core/grid.hpp"
#include "numerics/pressure_correction.hpp"

namespace fluidbed::tfm {

/// Widest band (the product of the cell counts of every axis but the slowest-numbered) for which the band solver
/// is used.
inline constexpr int kMaxPressureBand = 64;

/// The StructuredSolver problem (see fluid/pressure_correction.hpp) solved by a band LDL^T of its matrix, rows
/// numbered axis 0 fastest where that band is at most kMaxPressureBand (the 2D beds), else with the longest axis
/// slowest (a thin 3D slab: 30 x 50 x 2 cells have band 60). `reuse_factorisation` solves with the last
/// factorisation and accepts the answer only if it is backward stable for the new coefficients (else it
/// factorises them). nullptr when no such band is narrow enough, an axis is periodic or the owned box is not the
/// whole domain.
template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_band_structured_solver(const Grid<Dim>& grid);

}  // namespace fluidbed::tfm
