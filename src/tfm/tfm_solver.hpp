#pragma once
// Two-fluid model solver (paper Eqs. 15-26) on the staggered MAC grid in Dim = 2 or 3 dimensions: P, eps, Theta
// at cell centres, the velocity component along axis a of each phase on the faces normal to a. Axis 1 is
// vertical (distributor at its low side, outlet or lid at its high side); axis 0 and, in 3D, axis 2 end at walls.
// Every field carries kGhost ghost layers, filled by the boundary conditions, so no stencil clamps an index.
#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "numerics/pressure_correction.hpp"
#include "numerics/stencil_matrix.hpp"
#include "parallel/comm.hpp"
#include "tfm/tfm_config.hpp"
#include "tfm/tvd_convection.hpp"

namespace fluidbed::tfm {

/// One named array of the solver state (restart files store these as they are): the values of a field's box,
/// axis 0 fastest, and the box's extent per axis (nz = 1 in 2D).
struct NamedArray {
  std::string name;
  int nx = 0;
  int ny = 0;
  std::vector<double> values;
  int nz = 1;
};

/// The complete state: fields plus time, last time step and step count.
/// The blocks per axis of a TFM grid of n cells on `ranks` ranks: x never cut (the inner products of the solves sum
/// whole x-lines), a periodic axis never cut (its images stay on the rank), of the rest the cut with the fewest cell
/// faces between blocks; all zeros when the ranks cannot be placed so.
template <int Dim>
Index<Dim> tfm_blocks(int ranks, const Index<Dim>& n, const std::array<bool, Dim>& periodic);

template <int Dim>
struct TfmState {
  Field<Dim> eps;        ///< voidage (gas volume fraction), cells
  Field<Dim> p;          ///< gas pressure [Pa], cells
  FaceFields<Dim> ug;    ///< gas velocity [m/s], faces (superficial on the distributor face, interstitial elsewhere)
  FaceFields<Dim> us;    ///< solids velocity [m/s], faces
  Field<Dim> theta;      ///< granular temperature [m^2/s^2], cells (zero unless kinetic theory)
  double time = 0.0;
  double dt = 0.0;
  long steps = 0;
  /// Largest compaction (voidage decrease) of a cell below eps* in the last full step; steers the next dt.
  double dense_change = 0.0;
  /// Gas continuity residual of the last step, normalised (see TfmSolver::gas_volume_residual); monitor only.
  double gas_residual = 0.0;
};

/// Cell-centred vector: one cell field per axis.
template <int Dim>
using CellVectorField = std::array<Field<Dim>, Dim>;

template <int Dim>
class TfmSolver {
 public:
  /// The vertical axis (gravity, distributor at its low side).
  static constexpr int kUp = 1;
  static constexpr int kSlidingAxis = sliding_wall_axis(Dim);

  /// Validates the config (its domain must have this Dim), sets up the grid and the initial bed: uniform
  /// eps_initial below packed_height, gas above, gas at the background inflow, P from the steady gas momentum
  /// balance. Throws an input error. On the ranks of `comm` (which must outlive the solver) each holds a block of
  /// the grid (tfm_blocks: x never cut) and the run is the same bits as on one process; above one rank the pressure
  /// backend must be cg-multigrid (refused by name otherwise).
  explicit TfmSolver(const TfmConfig& config, const Comm& comm = serial_comm());
  ~TfmSolver();
  TfmSolver(TfmSolver&&) noexcept;

  /// Advances one adaptive time step (never past t_stop) through the stages of the paper's algorithm; returns the
  /// step taken.
  double advance(double t_stop);
  /// The same as advance (the name the drivers and tests use).
  double step(double t_stop) { return advance(t_stop); }
  /// Steps until the time reaches t.
  void advance_to(double t);

  const TfmConfig& config() const { return config_; }
  const Grid<Dim>& grid() const { return grid_; }
  const TfmState<Dim>& state() const { return s_; }
  double time() const { return s_.time; }

  /// Solids mass [kg per metre of depth in 2D, kg in 3D].
  double solids_mass() const;
  /// Kinetic energy of the solids' mean motion from cell-centred velocities (the faces' mean) [J per metre of depth
  /// in 2D, J in 3D]; an exact sum, the same on any number of ranks.
  double solids_kinetic_energy() const;
  /// Gas pressure on the bottom face (linear extrapolation, averaged over the bottom) minus the top pressure [Pa].
  double pressure_drop() const;
  /// Weight of the contents per unit bottom area (solids and gas) [Pa]: the static pressure drop.
  double contents_weight_per_area() const;
  /// Largest solids speed over interior faces carrying solids (eps_s > 1e-6 on both sides) [m/s].
  double max_solids_speed() const;
  /// Smallest voidage in the domain.
  double min_voidage() const;
  /// Gas continuity residual (Eq. 15) of the last step: sum over cells of |V (eps_new - eps_old)/dt + net gas
  /// volume outflow| with the face voidages of the step, over the largest of the inlet volume flow, the largest
  /// gas face speed times the bottom area and a round-off floor (the gas solver's normalisation); 0 before a step.
  double gas_volume_residual() const { return s_.gas_residual; }

  /// Sweeps the packing limiter needed in the last step (1: nothing to limit); diagnostics, not state.
  int packing_sweeps() const { return packing_sweeps_; }
  /// Linear solves of the last step that BiCGSTAB did not converge and the sparse LU answered; diagnostics.
  int linear_fallbacks() const { return linear_fallbacks_; }

  /// The fastest speed the bed's drivers can give it [m/s]: the fastest interstitial inflow (the largest inlet
  /// or jet superficial velocity over eps*) plus the free-fall speed along the domain's diagonal L, sqrt(2 g L), plus
  /// the speed of a sliding wall.
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
  const Field<Dim>& solids_pressure() const { return p_s_; }
  const Field<Dim>& solids_viscosity() const { return mu_s_; }

  /// Cell-centred velocities (mean of the two faces of each cell; the gas interstitial), fields on the domain.
  void gas_velocity_cells(CellVectorField<Dim>& u) const;
  void solids_velocity_cells(CellVectorField<Dim>& u) const;

  /// The complete state as named arrays over the whole domain (gathered from every rank's block, on every rank),
  /// for checkpoints; restoring it gives a bit-identical continuation, on any number of ranks.
  std::vector<NamedArray> save_state() const;
  /// Restores save_state() output (each rank takes its block); throws an input error if a name or a size does not
  /// match this grid.
  void restore_state(const std::vector<NamedArray>& arrays);
  /// The ranks this solver runs on.
  const Comm& comm() const { return comm_; }

 private:
  struct Work;

  /// The bed at t = 0 on one process (the whole grid): eps_initial below packed_height (with the seeded noise),
  /// the background inflow, the pressure of the steady gas momentum balance integrated down each column.
  void initial_bed();
  // The stages of advance(), in order.
  void mask_trace_solids_velocity();
  void compute_closures();
  template <SolidsRheology R, FrictionalModel F, class DragLawT>
  void compute_closures_of();
  double choose_dt(double t_stop) const;
  void predict_momentum(double dt);
  template <int d>
  void predict_momentum_along(double dt);
  void set_boundary_faces(double t);
  void face_fractions();
  void correct_pressure(double dt, bool same_matrix);
  void solids_fraction_rows(double dt);
  void correct_solids_fraction(double dt);
  [[noreturn]] void e_correction_failed(double dt, const LinearSolveOutcome& outcome) const;
  void solids_continuity(double dt);
  void close_gas_continuity(double dt);

  // Pieces the stages share.
  double vg_interstitial(const Index<Dim>& c) const;
  double mu_corner(const Index<Dim>& k, int p, int q) const;
  void outflow(Eigen::VectorXd& out_g, Eigen::VectorXd& out_s) const;
  /// Throws a simulation error with a diagnosis (time, cell, what, likely cause, remedy) when the state just
  /// reached is not physical: non-finite values, voidage outside [0, 1], speeds above reference_speed().
  void check_health(double dt) const;
  std::string where(const Index<Dim>& c) const;
  std::string remedy() const;
  std::string step_label(double dt) const;
  double gravity_norm() const;
  double bottom_area() const;
  /// Axis a is periodic (domain.periodic): no walls there, face 0 is an unknown and face n is the same plane.
  bool periodic(int a) const { return grid_.periodic[static_cast<std::size_t>(a)]; }
  /// The ghosts of f along the periodic axes (face n of a face field included) from their images in the domain.
  void tie(Field<Dim>& f) const;
  void tie(FaceFields<Dim>& f) const;
  /// The faces of axis a between two cells, of this rank's block: 1 .. n - 1 on a walled axis, 0 .. n - 1 on a
  /// periodic one (face 0 joins the last cell to the first; face n is face 0 and is set by tie()), within the
  /// block's faces (a face plane shared with a neighbour rank is computed by both, from the same ghosts).
  IndexBox<Dim> interior_faces(int a) const;
  /// tie(f) after the ghosts inside the domain came from the ranks that own them (f: cells or faces of the block).
  void halo(Field<Dim>& f) const;
  /// The ghosts of a cell or face field of the block: the owners', then the walls' zero gradient and the periodic
  /// images (the voidage, the velocities entering the step).
  void fill_ghosts(Field<Dim>& f) const;
  /// Every rank's box of a field of the kind of f (cells, or the faces of one axis).
  std::span<const IndexBox<Dim>> boxes_of(const Field<Dim>& f) const;
  /// The domain's box of f's kind.
  IndexBox<Dim> domain_of(const Field<Dim>& f) const;
  /// The cells of the domain's bottom row in this rank's block (empty when the block does not reach the bottom).
  IndexBox<Dim> bottom_cells() const;
  /// A failure some ranks may have found, reported alike on every rank: the message of the smallest key (the global
  /// index of the cell) wins.
  void fail_together(const std::optional<std::string>& local, double key) const;
  template <class F>
  void for_each_bottom(F&& f) const;

  TfmConfig config_;
  const Comm& comm_;
  Grid<Dim> grid_;
  std::vector<IndexBox<Dim>> cell_boxes_;                  ///< every rank's block
  std::array<std::vector<IndexBox<Dim>>, Dim> face_boxes_;  ///< every rank's faces of each axis
  TfmState<Dim> s_;
  // Closures of the step (derived each step, not state).
  Field<Dim> p_s_, mu_s_, lambda_s_, beta_c_, dps_deps_;
  int packing_sweeps_ = 0;
  int linear_fallbacks_ = 0;
  std::unique_ptr<Work> w_;
};

extern template class TfmSolver<2>;
extern template class TfmSolver<3>;

}  // namespace fluidbed::tfm
