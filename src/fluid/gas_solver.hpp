#pragma once
// Locally averaged gas of Anderson & Jackson (Eqs. 11-12) on a staggered grid, advanced by backward Euler with
// SIMPLE/SIMPLEC pressure-velocity coupling. Voidage, beta and the solids velocity come from outside each step.
#include <memory>

#include "core/field2.hpp"
#include "core/grid2.hpp"
#include "core/vec2.hpp"
#include "fluid/gas_boundary.hpp"
#include "fluid/gas_config.hpp"
#include "fluid/pressure_correction.hpp"

namespace fluidbed {

/// What one gas step did. Mass flows are per metre of depth [kg/s/m].
struct GasStepReport {
  int simple_iterations = 0;
  double mass_residual = 0.0;        ///< normalised continuity residual of the last predicted velocities
  double reference_mass_flow = 0.0;  ///< the normalisation of mass_residual (see GasConfig::mass_tolerance)
  double mass_in = 0.0;              ///< through the bottom
  double mass_out = 0.0;             ///< through the top
  double accumulation = 0.0;         ///< rho_g sum (eps_new - eps_old) V / dt
  double mass_balance = 0.0;         ///< mass_out - mass_in + accumulation (zero when gas mass is conserved)
  double mass_balance_relative = 0.0;///< |mass_balance| / reference_mass_flow
  /// Momentum solves of the step whose BiCGSTAB stopped short of its tolerance and that a sparse LU answered
  /// (a solve neither answers fails the step).
  int linear_fallbacks = 0;
};

class GasSolver {
 public:
  /// Validates the configuration (input error on bad values); fields start at rest with P = 0.
  GasSolver(const Grid2& grid, const GasConfig& config,
            PressureSolverKind pressure_solver = PressureSolverKind::Direct);
  ~GasSolver();
  GasSolver(GasSolver&&) noexcept;
  GasSolver& operator=(GasSolver&&) noexcept;

  /// One backward-Euler step from t_new - dt to t_new. All inputs are cell-centred (nx x ny): voidage at the start
  /// and end of the step, beta [kg/m^3/s] and the solids velocity (us, vs). Jets are switched at mid-step.
  /// Throws a simulation error when an input is out of range (eps outside (0, 1], beta < 0, NaN), when SIMPLE does
  /// not converge within max_simple_iterations, or when a field turns NaN; an input error on wrong field sizes.
  GasStepReport advance(double t_new, double dt, const Field2& eps_old, const Field2& eps_new, const Field2& beta,
                        const Field2& us, const Field2& vs);

  const Grid2& grid() const;
  const GasConfig& config() const;
  const StaggeredFields& fields() const;
  /// Mutable access for initial conditions and restarts.
  StaggeredFields& fields();

  /// Gas (interstitial) velocity at a point, bilinear from the faces.
  Vec2 velocity_at(Vec2 x) const;
  /// Pressure gradient at a point (see interpolate_pressure_gradient).
  Vec2 pressure_gradient_at(Vec2 x) const;
  /// Cell-centred gas velocity.
  void cell_velocity(Field2& ug, Field2& vg) const;
  /// Cell-centred pressure gradient.
  void cell_pressure_gradient(Field2& dpdx, Field2& dpdy) const;
  /// Mean pressure of the bottom cell row minus that of the top cell row [Pa].
  double pressure_drop() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fluidbed
