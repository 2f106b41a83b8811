#pragma once
// Configuration of the gas phase (Eqs. 11-12) and its boundaries; defaults are the paper's case (Table 1).
#include <cstdint>
#include <vector>

#include "numerics/tvd_limiter.hpp"
#include "core/vec.hpp"

namespace fluidbed {

/// Tangential condition on a wall.
enum class WallKind { Slip, NoSlip };

/// Top boundary of the domain.
enum class TopBoundary {
  PressureOutlet,  ///< P = top_pressure on the top face, zero-gradient velocity
  Wall,            ///< impermeable; may slide tangentially at lid_velocity (lid-driven cavity)
};

/// Face-value scheme for the convection terms (higher orders by deferred correction on an upwind matrix).
using ConvectionScheme = tvd::Limiter;

/// Viscous stress in the gas momentum equation.
enum class ViscousStress {
  Off,        ///< the paper's inviscid gas (default)
  Laplacian,  ///< div(eps mu_g grad u): the transpose part of the stress is dropped
  Full,       ///< div(eps mu_g (grad u + grad u^T)), the transpose part lagged by deferred correction
};

/// Backend of the pressure-correction solve (src/fluid/pressure_correction.hpp, structured_solver_hypre.hpp).
enum class PressureBackend {
  Eigen,      ///< Eigen's sparse Cholesky, reused as CG preconditioner within a step (the default)
  EigenCg,    ///< Eigen's incomplete-Cholesky CG, warm-started
  HyprePfmg,  ///< hypre's PFMG-preconditioned CG (structured multigrid), warm-started
  CgMultigrid,  ///< our multigrid-preconditioned CG, the same bits on any rank count (numerics/multigrid_cg.hpp)
};

/// Pressure-velocity coupling of the outer iterations.
enum class PressureCoupling { Simple, Simplec };

/// How an inlet region's superficial velocity varies in time; U0 is the region's velocity (inlet_velocity of the
/// background, InletJet::velocity of a jet).
enum class ScheduleKind {
  Constant,  ///< U0
  Ramp,      ///< ramp_from until ramp_start, linear to U0 at ramp_start + ramp_time, then U0
  Table,     ///< (times, velocities) pairs, linear between them, the end values held beyond them (U0 unused)
  Sine,      ///< U0 + amplitude sin(2 pi frequency t + phase), the pulsed bed of NETL's challenge problems
  Square,    ///< on/off pulsation: U0 + amplitude over the first `duty` of each period (phase shifts it), else U0
};

/// A region's superficial velocity as a function of time, evaluated once per gas step (inlet_velocities).
struct InletSchedule {
  ScheduleKind kind = ScheduleKind::Constant;
  double ramp_from = 0.0;   ///< Ramp: velocity before and at ramp_start [m/s]
  double ramp_start = 0.0;  ///< Ramp [s]
  double ramp_time = 0.0;   ///< Ramp: duration, > 0 [s]
  double amplitude = 0.0;   ///< Sine, Square [m/s]
  double frequency = 0.0;   ///< Sine, Square, > 0 [Hz]
  double phase = 0.0;       ///< Sine, Square [rad]
  double duty = 0.5;        ///< Square: the "on" fraction of each period, in (0, 1)
  std::vector<double> times;       ///< Table: strictly increasing [s]
  std::vector<double> velocities;  ///< Table: as many as times [m/s]
};

/// The region of the bottom face a jet blows through: a slot across the whole depth (2D, or a 3D slab's slot),
/// a rectangle or a disc of the bottom face of a 3D bed.
enum class InletShape { Slot, Rectangle, Disc };

/// A jet through the bottom distributor, active for t_start <= t < t_end. A bottom face takes the jet's velocity
/// over the fraction of its area the region covers (exact overlap: a length in 2D, an area in 3D), the background
/// velocity over the rest, so the jet's volume flux is exact at any resolution.
struct InletJet {
  double x_centre = 0.3;  ///< [m]
  double width = 0.02;    ///< x extent of a Slot or Rectangle, diameter of a Disc [m]
  double velocity = 30.0; ///< superficial velocity through the jet [m/s]
  double t_start = 0.0;   ///< [s]
  double t_end = 0.4;     ///< [s]
  InletShape shape = InletShape::Slot;
  double z_centre = 0.0;  ///< [m], Rectangle and Disc (3D)
  double depth = 0.0;     ///< z extent of a Rectangle [m]
  InletSchedule schedule{}; ///< velocity in time while active; Constant: `velocity`
};

/// Square or triangular (equilateral, alternate rows shifted by half a pitch) arrangement of a plate's holes.
enum class HolePitch { Square, Triangular };

/// A perforated distributor plate: a block of equal holes, each an InletJet (perforated_plate_holes). 2D: n_x slots
/// of `hole` width, pitch apart in x. 3D: n_x x n_z discs of diameter `hole`, rows pitch apart in z (triangular:
/// pitch sqrt(3)/2 apart, odd rows shifted by pitch / 2); the block is centred on (x_centre, z_centre).
struct PerforatedPlate {
  int n_x = 1;
  int n_z = 1;              ///< rows in z (3D)
  double hole = 0.002;      ///< slot width (2D) or disc diameter (3D) [m]
  double pitch = 0.01;      ///< centre-to-centre distance of neighbouring holes, >= hole [m]
  HolePitch layout = HolePitch::Square;
  double x_centre = 0.0;    ///< [m]
  double z_centre = 0.0;    ///< [m], 3D
  double velocity = 10.0;   ///< superficial velocity through each hole (U0 of the schedule) [m/s]
  double t_start = 0.0;     ///< [s]
  double t_end = 1e30;      ///< [s]
  InletSchedule schedule{};
};

struct GasBoundaryConfig {
  /// Superficial (volume flux per area) velocity through the whole bottom [m/s]; paper: U_mf = 1.8.
  double inlet_velocity = 1.8;
  /// Start-up ramp of that background velocity: linear from ramp_from at t = 0 to inlet_velocity at
  /// t = ramp_time [s] (0: no ramp, the inflow starts at inlet_velocity), as a bed is brought to its operating
  /// point by opening the valve.
  double ramp_from = 0.0;  ///< [m/s]
  double ramp_time = 0.0;  ///< [s]
  /// The background's velocity in time when not Constant (then ramp_from / ramp_time are unused): U0 = inlet_velocity.
  InletSchedule schedule{};
  /// Distributor non-uniformity: the background inflow of bottom face i is scaled by a fixed factor
  /// 1 + inlet_noise (2 u_i - 1), u_i uniform in [0, 1) from noise_seed, renormalised so that the total inflow is
  /// unchanged. A perfectly uniform distributor lifts a packed bed as a plug; real ones seed bubbles.
  double inlet_noise = 0.0;
  std::uint64_t noise_seed = 1998;
  /// Jets replacing the background inflow over their width; paper: one 0.02 m jet at the centre, 30 m/s, 0-0.4 s.
  std::vector<InletJet> jets = std::vector<InletJet>(1);
  TopBoundary top = TopBoundary::PressureOutlet;
  double top_pressure = 0.0;  ///< [Pa], PressureOutlet only
  double lid_velocity = 0.0;  ///< tangential speed of a top Wall [m/s]
  WallKind side_walls = WallKind::NoSlip;
  WallKind bottom_wall = WallKind::NoSlip;  ///< tangential condition along the distributor
  WallKind top_wall = WallKind::NoSlip;     ///< top Wall only
  WallKind front_back_walls = WallKind::NoSlip;  ///< the walls normal to z (3D only)
};

/// Gas phase: physical properties, discretisation and the SIMPLE loop.
struct GasConfig {
  double rho_g = 1.205;          ///< [kg/m^3]
  double mu_g = 1.8e-5;          ///< [Pa s]
  Vec3 gravity{0.0, -9.81, 0.0}; ///< [m/s^2], the domain's (a 2D solver reads x and y)
  ViscousStress viscous = ViscousStress::Off;
  ConvectionScheme convection = ConvectionScheme::VanLeer;
  PressureCoupling coupling = PressureCoupling::Simplec;
  PressureBackend pressure_solver = PressureBackend::Eigen;
  double relax_velocity = 0.8;   ///< momentum under-relaxation (0, 1]
  double relax_pressure = 1.0;   ///< pressure under-relaxation (0, 1]; about 0.3 with Simple
  int max_simple_iterations = 200;
  /// Converged when sum over cells |mass imbalance of the predicted velocities| / reference mass flow is below this;
  /// reference = max(inlet mass flow, rho_g * largest face speed * domain width) ...
  double mass_tolerance = 1e-8;
  /// ... and the normalised momentum residual of the iterate entering the iteration (GasStepReport::
  /// momentum_residual) below this, so that loose inner solves cannot end SIMPLE on a stalled iterate.
  double momentum_tolerance = 1e-8;
  /// ... or, from the fourth iteration, the iterate's estimated distance to the converged answer (the last
  /// iteration's move of the mass flux, times r / (1 - r) where the slowest contraction r seen exceeds 1/2) below
  /// this fraction of the step's change of the mass flux (GasStepReport::flux_change): in CFD-DEM the particles
  /// feel the gas one step late, so the coupling already errs by about that change, and converging SIMPLE far
  /// below it buys nothing (docs/model-gas.md). 0 (a gas on its own, whose steps may be pseudo-time): the two
  /// tolerances above only; a CFD-DEM case's default is 0.01.
  double coupling_tolerance = 0.0;
  /// Each momentum solve reduces the residual of its iterate by this factor (it solves for the increment), so its
  /// precision follows the outer residual down (inexact Newton, Dembo et al. 1982) rather than a fixed 1e-10.
  double momentum_solver_tolerance = 1e-4;
  /// The pressure-correction solves after the step's first (direct) one: relative residual of the warm CG.
  double pressure_solver_tolerance = 1e-3;
  int momentum_solver_max_iterations = 500;
  GasBoundaryConfig boundary;
};

}  // namespace fluidbed
