#pragma once
// Two-way CFD-DEM (paper section 2.1): DEM sub-steps with frozen gas, then voidage and interphase momentum
// deposited on the grid, then one gas step (Eqs. 11-12), then the new fluid force on every particle. One code for
// 2D monolayers and 3D beds (template <int Dim>).
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/field.hpp"
#include "coupling/coupling_config.hpp"
#include "coupling/deposition.hpp"
#include "coupling/voidage.hpp"
#include "dem/dem_solver.hpp"
#include "fluid/gas_solver.hpp"

namespace fluidbed {

template <int Dim>
class CfdDemSimulation {
 public:
  /// With no gas the simulation is the DEM alone, in vacuum.
  CfdDemSimulation(DemSolver<Dim> dem, std::optional<GasSolver<Dim>> gas, CouplingConfig coupling);

  /// Deposit the initial voidage and solve the gas once for the bed at rest, so that the first particle step
  /// already feels the gas (time does not advance). Call once for a fresh run, not after a restart.
  void initialize();
  /// One gas step: `dem_substeps` DEM steps, then the gas. Without gas: one DEM step.
  void advance() { advance(macro_dt()); }
  /// The same step of length h <= macro_dt() (a shortened last step): the DEM sub-steps share h equally.
  void advance(double h);

  double time() const { return dem_.time(); }
  double macro_dt() const { return dem_.config().dt * (gas_ ? coupling_.dem_substeps : 1); }
  DemSolver<Dim>& dem() { return dem_; }
  const DemSolver<Dim>& dem() const { return dem_; }
  bool has_gas() const { return gas_.has_value(); }
  GasSolver<Dim>& gas() { return *gas_; }
  const GasSolver<Dim>& gas() const { return *gas_; }
  const CouplingConfig& coupling() const { return coupling_; }
  const GasStepReport& last_gas_report() const { return report_; }
  std::uint64_t gas_steps() const { return gas_steps_; }
  /// Depth of the 2D monolayer that turns particle volume into a volume fraction (unused in 3D), m.
  double depth() const { return depth_; }

  /// Cell fields of the last gas step on the grid's owned box without ghosts (contiguous, axis 0 fastest):
  /// voidage as counted (unclipped), gas velocity at cell centres, mean particle velocity.
  const Field<Dim>& voidage() const { return eps_; }
  const std::array<Field<Dim>, Dim>& gas_velocity() const { return ug_; }
  const std::array<Field<Dim>, Dim>& solids_velocity() const { return us_; }
  double min_voidage() const;

  /// Net force of the gas on all particles (drag + pressure), N (per metre of depth in 2D: the particles' own).
  Vec<Dim> total_fluid_force() const;
  /// Net force of the gas on the particles as the gas sees it (sum of beta (u_g - u_s) V over cells), N.
  Vec<Dim> total_gas_reaction() const;

  /// Restore the coupling fields after the DEM and gas states were restored from a checkpoint.
  void restore(Field<Dim> eps, std::uint64_t gas_steps);

 private:
  /// The voidage the gas and the drag see: the counted one clipped to [eps_min, 1].
  void clip_voidage();
  void refuse_negative_voidage() const;
  double largest_diameter() const;
  void deposit();
  void update_particle_forces();
  /// The slots of the DEM store in the canonical order of the per-cell sums (DemSolver::canonical_order).
  std::span<const std::uint32_t> id_order();
  /// Distributed: every rank's own cells (those of its blocks) of these fields to every rank, so that each holds
  /// the whole grid (the gas is solved on every rank, the same way).
  void share_owned_cells(std::span<Field<Dim>* const> fields) const;

  DemSolver<Dim> dem_;
  std::optional<GasSolver<Dim>> gas_;
  CouplingConfig coupling_;
  double depth_ = 0.0;
  // us_: volume-weighted mean particle velocity (observers); us_gas_: drag-weighted (the gas).
  Field<Dim> eps_, eps_gas_old_, eps_gas_, beta_;
  std::array<Field<Dim>, Dim> us_, us_gas_, ug_;
  std::array<Field<Dim>, Dim> grad_p_;     ///< cell-centred pressure gradient of the last gas step
  std::vector<CellWeights<Dim>> weights_;  ///< kernel weights of the particles at the last deposit
  std::vector<CellWeights<Dim>> interp_weights_;  ///< multilinear weights for the gather when the deposition counts
  Deposition<Dim> deposition_;
  GasStepReport report_{};
  std::uint64_t gas_steps_ = 0;
};

extern template class CfdDemSimulation<2>;
extern template class CfdDemSimulation<3>;

}  // namespace fluidbed
