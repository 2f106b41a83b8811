#pragma once
// Locally averaged gas of Anderson & Jackson (Eqs. 11-12) on a staggered grid in Dim = 2 or 3 dimensions,
// advanced by backward Euler with SIMPLE/SIMPLEC pressure-velocity coupling. Voidage, beta and the solids
// velocity come from outside each step. Axis 1 is vertical (the distributor at its low side, the outlet or lid at
// its high side); axis 0 and, in 3D, axis 2 end at walls or are periodic (Grid::periodic). Mass flows are per metre of depth [kg/s/m] in 2D and
// [kg/s] in 3D.
#include <array>
#include <memory>

#include "parallel/comm.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/vec.hpp"
#include "fluid/gas_boundary.hpp"
#include "fluid/gas_config.hpp"
#include "numerics/pressure_correction.hpp"

namespace fluidbed {

/// What one gas step did. Mass flows are per metre of depth [kg/s/m] in 2D, [kg/s] in 3D.
struct GasStepReport {
  int simple_iterations = 0;
  double mass_residual = 0.0;        ///< normalised continuity residual of the last predicted velocities
  /// Normalised momentum residual of the last iterate entering SIMPLE, the largest over the components:
  /// sum_faces |b - A u| / (U_ref sum_faces a_P), U_ref = reference_mass_flow / (rho_g x cross-section).
  double momentum_residual = 0.0;
  double reference_mass_flow = 0.0;  ///< the normalisation of mass_residual (see GasConfig::mass_tolerance)
  /// With GasConfig::coupling_tolerance, after the last correction: sum_faces rho_g eps A |u - u_old| /
  /// reference_mass_flow, the step's change of the mass flux (the scale of the coupling's one-step lag) ...
  double flux_change = 0.0;
  /// ... and the same sum of |u - u_prev|, the change of the last SIMPLE iteration.
  double iterate_change = 0.0;
  /// ... and the largest ratio of one iteration's change to the one before's, from the third iteration on (0
  /// before): SIMPLE's observed contraction.
  double contraction = 0.0;
  /// True when the step ended on the coupling bound, iterate_change x max(1, r / (1 - r)) < coupling_tolerance x
  /// flux_change with r the contraction, not on the fixed tolerances.
  bool stopped_on_coupling = false;
  double mass_in = 0.0;              ///< through the bottom
  double mass_out = 0.0;             ///< through the top
  double accumulation = 0.0;         ///< rho_g sum (eps_new - eps_old) V / dt
  double mass_balance = 0.0;         ///< mass_out - mass_in + accumulation (zero when gas mass is conserved)
  double mass_balance_relative = 0.0;///< |mass_balance| / reference_mass_flow
  /// Momentum solves of the step whose BiCGSTAB stopped short of its tolerance and that a sparse LU answered
  /// (a solve neither answers fails the step).
  int linear_fallbacks = 0;
};

/// The gas unknowns on the staggered (MAC) grid: P at cell centres, u[a] on the faces normal to axis a (face i
/// of axis a at origin + i h), both with the grid's ghost layers.
template <int Dim>
struct GasFields {
  Field<Dim> p;
  FaceFields<Dim> u;
};

/// A vector quantity at cell centres, one cell field per axis.
template <int Dim>
using CellVector = std::array<Field<Dim>, Dim>;

template <int Dim>
class GasSolver {
 public:
  /// Validates the configuration (input error on bad values); fields start at rest with P = 0. The grid needs at
  /// least 2 cells per axis; reductions go through comm (the owned block must be the whole domain until the
  /// pressure backend is distributed).
  GasSolver(const Grid<Dim>& grid, const GasConfig& config,
            PressureSolverKind pressure_solver = PressureSolverKind::Direct, const Comm& comm = serial_comm());
  ~GasSolver();
  GasSolver(GasSolver&&) noexcept;
  GasSolver& operator=(GasSolver&&) noexcept;

  /// One backward-Euler step from t_new - dt to t_new. The inputs are cell fields on the grid's owned box (any
  /// ghost width; ghosts are not read): voidage at the start and end of the step, beta [kg/m^3/s] and the solids
  /// velocity, one field per axis. Jets are switched at mid-step. Throws a simulation error when an input is out
  /// of range (eps outside (0, 1], beta < 0, NaN), when SIMPLE does not converge within max_simple_iterations, or
  /// when a field turns NaN; an input error on fields of the wrong box.
  GasStepReport advance(double t_new, double dt, const Field<Dim>& eps_old, const Field<Dim>& eps_new,
                        const Field<Dim>& beta, const CellVector<Dim>& us);

  const Grid<Dim>& grid() const;
  const GasConfig& config() const;
  const GasFields<Dim>& fields() const;
  /// Mutable access for initial conditions and restarts (the values on the boxes; ghosts are derived).
  GasFields<Dim>& fields();

  /// Gas (interstitial) velocity at a point, multilinear from the faces, clamped to the outermost face nodes.
  Vec<Dim> velocity_at(const Vec<Dim>& x) const;
  /// Pressure gradient at a point: the cell-centred gradient (central inside, one-sided in the outer layers),
  /// multilinear between the 2^Dim surrounding cell centres.
  Vec<Dim> pressure_gradient_at(const Vec<Dim>& x) const;
  /// Cell-centred gas velocity (mean of the two faces of each cell), fields on the owned box without ghosts.
  void cell_velocity(CellVector<Dim>& u) const;
  /// Cell-centred pressure gradient (as in pressure_gradient_at), fields on the owned box without ghosts.
  void cell_pressure_gradient(CellVector<Dim>& grad) const;
  /// Mean pressure of the bottom cell layer minus that of the top cell layer [Pa].
  double pressure_drop() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

extern template class GasSolver<2>;
extern template class GasSolver<3>;

}  // namespace fluidbed
