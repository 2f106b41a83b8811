#pragma once
// Configuration of the two-fluid model (paper section 2.2, Table 1 TFM column); defaults are the paper's case.
#include <array>
#include <cstdint>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/domain.hpp"
#include "numerics/tvd_limiter.hpp"
#include "closures/drag.hpp"
#include "fluid/gas_config.hpp"
#include "tfm/solids_stress.hpp"

namespace fluidbed::tfm {

/// The shared TVD limiter family (also the gas solver's).
using Limiter = tvd::Limiter;

/// Solids rheology of Eq. 19, the paper's three cases.
enum class SolidsRheology {
  ConstantViscosity,  ///< mu_s = mu_s_constant, P_s from Eq. 20
  Inviscid,           ///< mu_s = 0, P_s from Eq. 20
  KineticTheory,      ///< Eqs. 23-26 with algebraic Theta above eps*, frictional Eqs. 21-22 at or below eps*
  /// The paper's anticipated viscoplastic solids (its closing remarks): mu_s from the regularised Bingham law
  /// (bingham_viscosity) with the plastic viscosity mu_s_constant and a yield stress, P_s from Eq. 20
  Bingham,
};

/// The kinetic theory's dense-bed closure.
enum class FrictionalModel {
  Schaeffer,             ///< the paper's: Eqs. 21-22 alone at or below eps*, the kinetic theory alone above
  JohnsonJackson,        ///< jj_frictional_pressure added to the kinetic theory above its onset, Schaeffer's viscosity
  SrivastavaSundaresan,  ///< the same pressure, the viscosity regularised by Theta / d_p^2
};

/// Calls f(std::integral_constant<FrictionalModel, F>{}) for the model m, as with_rheology does for the rheology.
template <class F>
decltype(auto) with_frictional(FrictionalModel m, F&& f) {
  switch (m) {
    case FrictionalModel::JohnsonJackson:
      return std::forward<F>(f)(std::integral_constant<FrictionalModel, FrictionalModel::JohnsonJackson>{});
    case FrictionalModel::SrivastavaSundaresan:
      return std::forward<F>(f)(std::integral_constant<FrictionalModel, FrictionalModel::SrivastavaSundaresan>{});
    case FrictionalModel::Schaeffer: break;
  }
  return std::forward<F>(f)(std::integral_constant<FrictionalModel, FrictionalModel::Schaeffer>{});
}

/// Where the Bingham rheology's yield stress comes from.
enum class YieldStress {
  Given,         ///< yield_stress [Pa] in the bed, scaled down with the solids fraction below eps_s = 0.05
  MohrCoulomb,   ///< tau_y = P_s sin(phi): the Eq. 20 solids pressure and the friction angle (Eq. 21's yield)
};

/// The axis whose high side wall may slide (TfmConfig::sliding_wall): z in 3D, x in 2D.
constexpr int sliding_wall_axis(int dimension) { return dimension == 3 ? 2 : 0; }

/// Calls f(std::integral_constant<SolidsRheology, R>{}) for the rheology r: the one run-time switch, taken before
/// a loop that is compiled once per rheology.
template <class F>
decltype(auto) with_rheology(SolidsRheology r, F&& f) {
  switch (r) {
    case SolidsRheology::ConstantViscosity:
      return std::forward<F>(f)(std::integral_constant<SolidsRheology, SolidsRheology::ConstantViscosity>{});
    case SolidsRheology::Inviscid:
      return std::forward<F>(f)(std::integral_constant<SolidsRheology, SolidsRheology::Inviscid>{});
    case SolidsRheology::Bingham:
      return std::forward<F>(f)(std::integral_constant<SolidsRheology, SolidsRheology::Bingham>{});
    case SolidsRheology::KineticTheory: break;
  }
  return std::forward<F>(f)(std::integral_constant<SolidsRheology, SolidsRheology::KineticTheory>{});
}

struct TfmConfig {
  /// Dimension, box and gravity, shared with the DEM and the gas ([case] and [domain]; Table 1: 0.6 x 1.0 m).
  DomainConfig domain{};
  double cell_size = 0.02;     ///< [m], cubic (square in 2D) cells (Table 1: 0.02 m)
  // Particles and gas (Table 1).
  double d_p = 0.004;          ///< [m]
  double rho_s = 2700.0;       ///< [kg/m^3]
  double e = 0.9;              ///< coefficient of restitution
  double phi_deg = 40.0;       ///< angle of internal friction [deg]
  double rho_g = 1.205;        ///< [kg/m^3], constant (incompressible gas)
  double mu_g = 1.8e-5;        ///< [Pa s]
  DragLaw drag_law = DragLaw::ErgunWenYu;  ///< the shared drag library (src/fluid/drag.hpp)
  DragSwitch drag_switch = DragSwitch::Sharp;
  // Initial bed (Table 1): uniform voidage up to the packed height, gas above.
  double eps_initial = 0.431;
  double packed_height = 0.54; ///< [m]
  double eps_star = 0.43;      ///< compaction voidage eps*
  // Rheology.
  SolidsRheology rheology = SolidsRheology::KineticTheory;
  double mu_s_constant = 0.5;  ///< [Pa s] for ConstantViscosity, the plastic viscosity of Bingham; the paper gives none
  YieldStress yield = YieldStress::Given;  ///< Bingham: how tau_y is set
  double yield_stress = 10.0;  ///< [Pa] Bingham, YieldStress::Given: tau_y in the bed (the paper gives no value)
  double yield_regularisation = 100.0;  ///< [s] Bingham: Papanastasiou's m (exact Bingham as m -> infinity)
  FrictionalModel frictional = FrictionalModel::Schaeffer;  ///< KineticTheory: the dense-bed closure
  FrictionalParams friction{};  ///< JohnsonJackson and SrivastavaSundaresan: the frictional pressure's constants
  double mu_s_max = 100.0;     ///< [Pa s] cap on the solids viscosity (frictional viscosity diverges at rest)
  ModulusParams modulus{};     ///< Eq. 20 for ConstantViscosity, Inviscid and Bingham
  // Numerics.
  Limiter limiter = Limiter::Superbee;
  double cfl = 0.5;            ///< dt = cfl * cell / max(velocity, solids-pressure wave speed); 0.5 keeps TVD
  double dt_max = 1e-3;        ///< [s]
  /// Largest voidage decrease per step of a cell that ends below eps* (steers dt): far past eps* the solids
  /// pressure is much stiffer than its linearisation in the E' correction. With the packing limiter as the hard
  /// floor 0.03 is stable (0.05 lets the sedimentation column's packed layer break up; docs/model-tfm.md).
  double max_dense_change = 0.03;
  /// Largest compaction below eps* the packing limiter allows: eps >= eps* - max_compaction in every cell, exactly
  /// (fluxes into a cell that would pass it are cut; docs/model-tfm.md). Unset: the rheology's default
  /// (default_max_compaction).
  std::optional<double> max_compaction;
  double dt_min = 1e-8;        ///< [s]; below this the run fails
  int mass_corrections = 2;    ///< deferred-correction passes of the implicit solids continuity
  /// Gas boundaries, shared with the gas solver: distributor inflow and jets, side walls, top outlet or lid
  /// (the TFM gas has no viscous stress, so the gas wall kinds do not enter; a moving lid is not supported).
  GasBoundaryConfig boundary;
  bool solids_no_slip_walls = false;  ///< solids tangential condition on the side walls (default free slip)
  /// Velocity of the side wall at the high end of the last horizontal axis (z in 3D, x in 2D) [m/s], tangential
  /// (its normal component zero): the solids stick to it (solids_no_slip_walls) and are sheared between it and the
  /// wall opposite, as in a shear cell or plane Couette flow. The gas has no viscous stress and does not feel it.
  std::array<double, 3> sliding_wall{};
  // Seeded symmetry breaking (a perfectly symmetric bed never bubbles): off by default, as in the paper.
  /// Initial voidage noise: every cell of the initial bed gets eps + eps_noise (2u - 1), u uniform in [0, 1),
  /// kept within [eps*, 1].
  double eps_noise = 0.0;
  /// (The distributor non-uniformity is the inlet's, boundary.inlet_noise, shared with the CFD-DEM gas.)
  std::uint64_t seed = 1998;  ///< seed of eps_noise (case.seed)
  /// BiCGSTAB iterations of the solids-fraction correction and the implicit continuity at most; 0: Eigen's
  /// default (twice the cell count). A solve that stops short falls back to a sparse LU (tests cap it).
  int linear_max_iterations = 0;
  /// Backend of the gas-pressure correction (the case's gas.pressure_solver): Eigen's sparse Cholesky (the 2D
  /// default), incomplete-Cholesky CG or hypre PFMG. The iterative ones solve to kPressureTolerance, since the
  /// mixture volume constraint closes Eq. 15 to rounding; in 3D the Cholesky factorisation dominates the cost.
  PressureBackend pressure_solver = PressureBackend::Eigen;
};

/// Relative residual to which an iterative pressure backend solves the TFM's P' equation.
inline constexpr double kPressureTolerance = 1e-12;

/// The limiter is a backstop below the working range of the solids pressure, not a substitute for it (it stops
/// solids but transmits no force): its default bound lies just below the voidage at which the rheology's solids
/// pressure carries the paper's bed (twice its buoyant weight, 8 kPa): 0.419 with Eqs. 21-22, hence 0.015
/// (eps >= 0.415); 0.403 with the Eq. 20 modulus, hence 0.03 (eps >= 0.40). A bound above that voidage leaves
/// the whole bed resting on the limiter, and the jet no longer blows a bubble (docs/model-tfm.md).
constexpr double default_max_compaction(SolidsRheology r) {
  return r == SolidsRheology::KineticTheory ? 0.015 : 0.03;
}

/// max_compaction if set, else default_max_compaction(rheology).
inline double packing_allowance(const TfmConfig& c) {
  return c.max_compaction.value_or(default_max_compaction(c.rheology));
}

/// Throws an input error naming the offending setting.
void validate(const TfmConfig& config);

}  // namespace fluidbed::tfm
