#pragma once
// A direct solve of the TFM's gas-pressure correction for grids whose rows, numbered axis 0 fastest, couple only
// within a narrow band: the 2D case (bandwidth = the cells along axis 0, 30 in the paper's bed). A dense band
// LDL^T factorisation (Golub & Van Loan, Matrix Computations, 4th ed., Alg. 4.3.5) walks contiguous memory and
// vectorises; on the 30 x 50 grid it costs about half of Eigen's sparse LDL^T with AMD ordering, although it does
// about as many operations (docs/performance.md section 17).
#include <memory>

#include "core/grid.hpp"
#include "fluid/pressure_correction.hpp"

namespace fluidbed::tfm {

/// Widest band (cells along axis 0 times those of every axis but the last) for which the band solver is used.
inline constexpr int kMaxPressureBand = 64;

/// The StructuredSolver problem (see fluid/pressure_correction.hpp) solved by a band LDL^T of its matrix, rows
/// numbered axis 0 fastest. `reuse_factorisation` solves with the last factorisation and accepts the answer only
/// if it is backward stable for the new coefficients (else it factorises them). nullptr when the grid's band is
/// wider than kMaxPressureBand, an axis is periodic or the owned box is not the whole domain.
template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_band_structured_solver(const Grid<Dim>& grid);

}  // namespace fluidbed::tfm
