#pragma once
// Boundary-condition helpers of the gas phase, shared by the CFD-DEM gas solver and the two-fluid model.
#include <cstdint>
#include <string>
#include <vector>

#include "parallel/comm.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"
#include "fluid/gas_config.hpp"

namespace fluidbed {

/// Superficial velocity [m/s] at time t of a region whose velocity is u0 under schedule s (ScheduleKind gives each
/// formula); pure, so the step's value is one call per region, never one per face.
double schedule_velocity(const InletSchedule& s, double u0, double t);

/// Background superficial inlet velocity at time t (outside the jets), m/s: the background schedule of
/// inlet_velocity, or (Constant) inlet_velocity reached from ramp_from by a linear ramp over [0, ramp_time].
/// Every model takes its background inflow from here.
double background_inlet_velocity(const GasBoundaryConfig& bc, double t);

/// Every inlet region's superficial velocity at one instant: evaluated once per gas step, then read per face.
struct InletVelocities {
  double background = 0.0;          ///< [m/s]
  std::vector<double> jet;          ///< jet k's velocity from its schedule (0 while closed) [m/s]
  std::vector<std::uint8_t> active; ///< 1 while jet k is open, t_start <= t < t_end
};
InletVelocities inlet_velocities(const GasBoundaryConfig& bc, double t);
/// The same into `out`, whose vectors keep their room between gas steps.
void inlet_velocities(const GasBoundaryConfig& bc, double t, InletVelocities& out);

/// The largest |superficial velocity| any region reaches at any time (the background before its distributor
/// factors), for time-step and sanity limits [m/s].
double inlet_peak_velocity(const GasBoundaryConfig& bc);

/// Superficial inlet velocity averaged over the bottom face [x_lo, x_hi] at time t: the background velocity,
/// replaced by each active jet over the fraction of the face it covers (so the jet's volume flux is exact).
double inlet_superficial_velocity(const GasBoundaryConfig& bc, double x_lo, double x_hi, double t);
/// The same from the step's region velocities.
double inlet_superficial_velocity(const GasBoundaryConfig& bc, const InletVelocities& v, double x_lo, double x_hi);

/// The fixed distributor factors of the nx bottom faces (all 1 without inlet_noise), mean exactly 1 up to rounding.
std::vector<double> inlet_noise_factors(const GasBoundaryConfig& bc, int nx);
/// The same into `f` (resized to nx).
void inlet_noise_factors(const GasBoundaryConfig& bc, int nx, std::vector<double>& f);

/// The holes of a perforated plate as jets (2D: slots; 3D: discs), row by row in z, x fastest.
std::vector<InletJet> perforated_plate_holes(const PerforatedPlate& plate, int dimension);

/// Area of the jet's region (Slot: the strip |x - x_centre| <= width / 2 over the whole depth; Rectangle; Disc)
/// inside the rectangle [x_lo, x_hi] x [z_lo, z_hi] of a 3D bed's bottom face, m^2 (exact, also for a disc).
double jet_overlap_area(const InletJet& jet, double x_lo, double x_hi, double z_lo, double z_hi);

/// Superficial inlet velocity of every bottom face of the grid's domain at time t, axis 0 fastest (then z in 3D).
/// 2D: inlet_superficial_velocity of each face, its background part scaled by the distributor factors (slots
/// only). 3D: each active jet replaces the background velocity over the area of the face it covers
/// (jet_overlap_area), and the background part of face (i, k) is scaled by the distributor factor i + nx k of
/// inlet_noise_factors(bc, nx nz).
template <int Dim>
void inlet_superficial_profile(const GasBoundaryConfig& bc, const Grid<Dim>& grid, double t, std::vector<double>& out);

/// The work arrays of a profile, kept by a model between its gas steps so that a step allocates nothing.
struct InletWork {
  InletVelocities v;
  std::vector<double> noise, fraction, flux, covered;
};
/// The same profile with the caller's work arrays.
template <int Dim>
void inlet_superficial_profile(const GasBoundaryConfig& bc, const Grid<Dim>& grid, double t, std::vector<double>& out,
                               InletWork& work);
/// The same from the step's region velocities (inlet_velocities).
template <int Dim>
void inlet_superficial_profile(const GasBoundaryConfig& bc, const InletVelocities& v, const Grid<Dim>& grid,
                               std::vector<double>& out);

/// The bottom's mean superficial inlet velocity at time t: the volume flow through the distributor over its area,
/// as the profile delivers it (the monitor's inlet_velocity_m_s) [m/s].
template <int Dim>
double inlet_mean_velocity(const GasBoundaryConfig& bc, const Grid<Dim>& grid, double t);

// ---- Ghost layers of the gas unknowns. Each function fills the ghosts of one side (axis e, `high`) of a field;
// the caller applies it only where Grid::at_domain_side says the side is physical, so a sub-domain's internal
// sides are left to Comm::exchange_halo. A periodic axis has no physical side (Grid::at_domain_side is false there):
// fill_velocity_ghosts and fill_pressure_ghosts copy its ghosts from the opposite side (fill_periodic_ghosts).

/// Tangential velocity beyond a wall, layer k mirrored about the side onto the k-th layer inside: u_g = 2 u_wall - u
/// (no-slip: the mean of the pair is the wall's speed) or u_g = u (slip: no shear across the wall).
template <int Dim>
void fill_wall_tangential(Field<Dim>& u, int e, bool high, WallKind kind, double u_wall);

/// Zero gradient beyond the side: every ghost layer repeats the field's boundary layer (the tangential velocity at
/// the outlet; the normal velocity beyond a wall, inflow or outlet face, so that a TVD limiter reaching across
/// the side sees no slope and falls back to upwind; P at walls and the distributor).
template <int Dim>
void fill_zero_gradient(Field<Dim>& f, int e, bool high);

/// Cell pressure beyond a pressure outlet, mirrored: P_g = 2 P_out - P (the pair averages to P_out on the face).
template <int Dim>
void fill_pressure_outlet(Field<Dim>& p, int e, bool high, double p_out);

/// The wall faces' normal velocity fixed at zero: component a on its faces at side `high` of axis a.
template <int Dim>
void fix_wall_normal(Field<Dim>& u_a, int a, bool high);

/// The ghosts of every velocity component on the physical sides of grid's owned block, then the halo exchange:
/// side walls (axis 0) and front/back walls (axis 2, 3D) of kind side_walls / front_back_walls, the distributor
/// (axis 1 low) of kind bottom_wall, the top a pressure outlet (zero gradient) or a wall of kind top_wall moving at
/// lid_velocity along axis 0. Normal components: zero gradient beyond every side.
template <int Dim>
void fill_velocity_ghosts(const Grid<Dim>& grid, const GasBoundaryConfig& bc, const Comm& comm, FaceFields<Dim>& u);

/// The pressure ghosts on the physical sides: mirrored about top_pressure at a pressure outlet, zero gradient at
/// walls, the distributor and a lid; then the halo exchange.
template <int Dim>
void fill_pressure_ghosts(const Grid<Dim>& grid, const GasBoundaryConfig& bc, const Comm& comm, Field<Dim>& p);

/// Throws an input error naming the offending setting.
void validate(const GasConfig& config);
/// Throws an input error naming the region ("background", "jet") and the offending schedule setting.
void validate(const InletSchedule& schedule, const std::string& region);

}  // namespace fluidbed
