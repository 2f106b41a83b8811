#pragma once
// Configuration of the two-fluid model (paper section 2.2, Table 1 TFM column); defaults are the paper's case.
#include <vector>

#include "core/vec2.hpp"
#include "fluid/drag.hpp"
#include "fluid/gas_config.hpp"
#include "tfm/flux_limiter.hpp"
#include "tfm/solids_stress.hpp"

namespace fluidbed::tfm {

/// Solids rheology of Eq. 19, the paper's three cases.
enum class SolidsRheology {
  ConstantViscosity,  ///< mu_s = mu_s_constant, P_s from Eq. 20
  Inviscid,           ///< mu_s = 0, P_s from Eq. 20
  KineticTheory,      ///< Eqs. 23-26 with algebraic Theta above eps*, frictional Eqs. 21-22 at or below eps*
};

struct TfmConfig {
  // Domain and grid (Table 1: 0.6 x 1.0 m, 0.02 x 0.02 m cells).
  double width = 0.6;          ///< [m]
  double height = 1.0;         ///< [m]
  double cell_size = 0.02;     ///< [m], square cells
  // Particles and gas (Table 1).
  double d_p = 0.004;          ///< [m]
  double rho_s = 2700.0;       ///< [kg/m^3]
  double e = 0.9;              ///< coefficient of restitution
  double phi_deg = 40.0;       ///< angle of internal friction [deg]
  double rho_g = 1.205;        ///< [kg/m^3], constant (incompressible gas)
  double mu_g = 1.8e-5;        ///< [Pa s]
  Vec2 gravity{0.0, -9.81};    ///< [m/s^2]
  DragSwitch drag_switch = DragSwitch::Sharp;
  // Initial bed (Table 1): uniform voidage up to the packed height, gas above.
  double eps_initial = 0.431;
  double packed_height = 0.54; ///< [m]
  double eps_star = 0.43;      ///< compaction voidage eps*
  // Rheology.
  SolidsRheology rheology = SolidsRheology::KineticTheory;
  double mu_s_constant = 0.5;  ///< [Pa s] for ConstantViscosity; the paper gives no value
  double mu_s_max = 100.0;     ///< [Pa s] cap on the solids viscosity (frictional viscosity diverges at rest)
  ModulusParams modulus{};     ///< Eq. 20 for ConstantViscosity and Inviscid
  // Numerics.
  Limiter limiter = Limiter::Superbee;
  double cfl = 0.5;            ///< dt = cfl * cell / max(velocity, solids-pressure wave speed); 0.5 keeps TVD
  double dt_max = 1e-3;        ///< [s]
  /// Largest compaction below eps* (voidage decrease) allowed per step: a step that compacts far past eps*
  /// lands where the solids pressure is orders of magnitude stiffer than its linearisation.
  double max_dense_change = 0.002;
  double dt_min = 1e-8;        ///< [s]; below this the run fails
  int mass_corrections = 2;    ///< deferred-correction passes of the implicit solids continuity
  /// Gas boundaries, shared with the gas solver: distributor inflow and jets, side walls, top outlet or lid
  /// (the TFM gas has no viscous stress, so the gas wall kinds do not enter; a moving lid is not supported).
  GasBoundaryConfig boundary;
  bool solids_no_slip_walls = false;  ///< solids tangential condition on the side walls (default free slip)
};

/// Throws an input error naming the offending setting.
void validate(const TfmConfig& config);

}  // namespace fluidbed::tfm
