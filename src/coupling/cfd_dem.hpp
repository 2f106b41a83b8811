#pragma once
// Two-way CFD-DEM (paper section 2.1): DEM sub-steps with frozen gas, then voidage and interphase momentum
// deposited on the grid, then one gas step (Eqs. 11-12), then the new fluid force on every particle.
#include <optional>
#include <vector>

#include "core/field2.hpp"
#include "coupling/coupling_config.hpp"
#include "coupling/voidage.hpp"
#include "dem/dem_solver.hpp"
#include "fluid/gas_solver.hpp"

namespace fluidbed {

class CfdDemSimulation {
 public:
  /// With no gas the simulation is the DEM alone, in vacuum.
  CfdDemSimulation(DemSolver dem, std::optional<GasSolver<2>> gas, CouplingConfig coupling);

  /// Deposit the initial voidage and solve the gas once for the bed at rest, so that the first particle step
  /// already feels the gas (time does not advance). Call once for a fresh run, not after a restart.
  void initialize();
  /// One gas step: `dem_substeps` DEM steps, then the gas. Without gas: one DEM step.
  void advance() { advance(macro_dt()); }
  /// The same step of length h <= macro_dt() (a shortened last step): the DEM sub-steps share h equally.
  void advance(double h);
  double time() const { return dem_.time(); }
  double macro_dt() const { return dem_.config().dt * (gas_ ? coupling_.dem_substeps : 1); }

  DemSolver& dem() { return dem_; }
  const DemSolver& dem() const { return dem_; }
  bool has_gas() const { return gas_.has_value(); }
  GasSolver<2>& gas() { return *gas_; }
  const GasSolver<2>& gas() const { return *gas_; }
  const CouplingConfig& coupling() const { return coupling_; }
  const GasStepReport& last_gas_report() const { return report_; }
  std::uint64_t gas_steps() const { return gas_steps_; }

  /// Cell fields of the last gas step: voidage as counted (unclipped), gas velocity at cell centres, mean
  /// particle velocity.
  const Field2& voidage() const { return eps_; }
  const Field2& gas_u() const { return ug_; }
  const Field2& gas_v() const { return vg_; }
  const Field2& solids_u() const { return us_; }
  const Field2& solids_v() const { return vs_; }
  double min_voidage() const;
  /// Net force of the gas on all particles (drag + pressure), N: for momentum-balance monitoring.
  Vec2 total_fluid_force() const;

  /// Net force of the gas on the particles as the gas sees it (sum of beta (u_g - u_s) V over cells), N.
  Vec2 total_gas_reaction() const;
  /// Restore the coupling fields after the DEM and gas states were restored from a checkpoint.
  void restore(Field2 eps, std::uint64_t gas_steps);

 private:
  /// The voidage the gas and the drag see: the counted one clipped to [eps_min, 1].
  void clip_voidage();
  void deposit();
  void update_particle_forces();

  DemSolver dem_;
  std::optional<GasSolver<2>> gas_;
  CouplingConfig coupling_;
  double depth_ = 0.0;
  // us_, vs_: volume-weighted mean particle velocity (observers); us_gas_, vs_gas_: drag-weighted (the gas).
  Field2 eps_, eps_gas_old_, eps_gas_, beta_, us_, vs_, us_gas_, vs_gas_, ug_, vg_;
  std::vector<CellWeights> weights_;  ///< kernel weights of the particles at the last deposit
  GasStepReport report_{};
  std::uint64_t gas_steps_ = 0;
};

}  // namespace fluidbed
