#pragma once
// Two-fluid model solver (paper Eqs. 15-26) on the staggered MAC grid: P, eps, Theta at cell centres,
// u on vertical faces ((nx+1) x ny), v on horizontal faces (nx x (ny+1)).
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "core/field2.hpp"
#include "core/grid2.hpp"
#include "fluid/pressure_correction.hpp"
#include "fluid/stencil_matrix.hpp"
#include "tfm/tfm_config.hpp"

namespace fluidbed::tfm {

/// One named array of the solver state (restart files store these as they are).
struct NamedArray {
  std::string name;
  int nx = 0;
  int ny = 0;
  std::vector<double> values;
};

/// The complete state: fields plus time, last time step and step count.
struct TfmState {
  Field2 eps;     ///< voidage (gas volume fraction), cells
  Field2 p;       ///< gas pressure [Pa], cells
  Field2 ug, vg;  ///< gas velocity [m/s], faces
  Field2 us, vs;  ///< solids velocity [m/s], faces
  Field2 theta;   ///< granular temperature [m^2/s^2], cells (zero unless kinetic theory)
  double time = 0.0;
  double dt = 0.0;
  long steps = 0;
  /// Largest compaction (voidage decrease) of a cell below eps* in the last full step; steers the next dt.
  double dense_change = 0.0;
  /// Gas continuity residual of the last step, normalised (see TfmSolver::gas_volume_residual); monitor only.
  double gas_residual = 0.0;
};

class TfmSolver {
 public:
  /// Validates the config, sets up the grid and the initial bed: uniform eps_initial below packed_height, gas
  /// above, gas at the background inflow, P from the steady gas momentum balance. Throws an input error.
  explicit TfmSolver(const TfmConfig& config);

  /// Advances one adaptive time step (never past t_stop); returns the step taken.
  double step(double t_stop);
  /// Steps until the time reaches t.
  void advance_to(double t);

  const TfmConfig& config() const { return config_; }
  const Grid2& grid() const { return grid_; }
  const TfmState& state() const { return s_; }
  double time() const { return s_.time; }

  /// Solids mass per unit depth [kg/m].
  double solids_mass() const;
  /// Gas pressure on the bottom face (linear extrapolation, width-averaged) minus the top pressure [Pa].
  double pressure_drop() const;
  /// Weight of the contents per unit area (solids and gas, width-averaged) [Pa]: the static pressure drop.
  double contents_weight_per_area() const;
  /// Largest solids speed over faces carrying solids (eps_s > 1e-6 on both sides) [m/s].
  double max_solids_speed() const;
  /// Smallest voidage in the domain.
  double min_voidage() const;
  /// Gas continuity residual (Eq. 15) of the last step: sum over cells of |V (eps_new - eps_old)/dt + net gas
  /// volume outflow| with the face voidages of the step, over the largest of the inlet volume flow, the largest
  /// gas face speed times the width and a round-off floor (the gas solver's normalisation); 0 before a step.
  double gas_volume_residual() const { return s_.gas_residual; }

  /// Sweeps the packing limiter needed in the last step (1: nothing to limit); diagnostics, not state.
  int packing_sweeps() const { return packing_sweeps_; }
  /// Linear solves of the last step that BiCGSTAB did not converge and the sparse LU answered; diagnostics.
  int linear_fallbacks() const { return linear_fallbacks_; }

  /// The fastest speed the bed's drivers can give it [m/s]: the fastest interstitial inflow (the largest inlet
  /// or jet superficial velocity over eps*) plus the free-fall speed over the domain height, sqrt(2 g H).
  /// Solids are driven only by the gas drag and gravity, so a solids speed (or a fluctuation speed sqrt(Theta))
  /// above it means the numerics, not the physics, produced it.
  double reference_speed() const;
  /// Largest granular temperature over cells in the bed (solids fraction >= kBedSolidsFraction) [m^2/s^2]; the
  /// algebraic Theta diverges as eps_s -> 0 (dilute limit of Eq. 26), so cells without solids are left out.
  double bed_granular_temperature_max() const;
  /// Solids-volume-weighted mean granular temperature, sum(eps_s Theta) / sum(eps_s) [m^2/s^2].
  double solids_mean_granular_temperature() const;
  /// Solids fraction from which a cell counts as "in the bed" for the granular-temperature monitors and checks.
  static constexpr double kBedSolidsFraction = 0.05;

  /// Solids pressure [Pa] and solids shear viscosity [Pa s] of the last step, cells.
  const Field2& solids_pressure() const { return p_s_; }
  const Field2& solids_viscosity() const { return mu_s_; }

  /// Cell-centred velocities (mean of the two faces of each cell).
  void gas_velocity_cells(Field2& u, Field2& v) const;
  void solids_velocity_cells(Field2& u, Field2& v) const;

  /// The complete state as named arrays, for checkpoints; restoring it gives a bit-identical continuation.
  std::vector<NamedArray> save_state() const;
  /// Restores save_state() output; throws an input error if a name or a size does not match this grid.
  void restore_state(const std::vector<NamedArray>& arrays);

 private:
  double vg_interstitial(int i, int j) const;
  void mask_trace_solids_velocity();
  void compute_cell_closures();
  /// compute_cell_closures for one rheology (chosen once, outside the cell loop).
  template <SolidsRheology R>
  void compute_cell_closures_of();
  double choose_dt(double t_stop) const;
  /// Throws a simulation error with a diagnosis (time, cell, what, likely cause, remedy) when the state just
  /// reached is not physical: non-finite values, voidage outside [0, 1], speeds above reference_speed().
  void check_health(double dt) const;
  std::string where(int i, int j) const;
  std::string remedy() const;

  TfmConfig config_;
  Grid2 grid_;
  TfmState s_;
  // Work arrays (derived each step, not state).
  Field2 p_s_, mu_s_, lambda_s_, beta_c_, dps_deps_;
  int packing_sweeps_ = 0;
  int linear_fallbacks_ = 0;
  PressureCorrectionSolver pressure_solver_;  // shared with the gas solver (src/fluid)
  StencilMatrix e_matrix_;  ///< solids-fraction correction, five-point pattern fixed at construction
  CheckedSparseSolver solids_solver_;
};

}  // namespace fluidbed::tfm
