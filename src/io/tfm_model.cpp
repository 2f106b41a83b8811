#include "io/tfm_model.hpp"

#include <cmath>
#include <fmt/format.h>
#include <utility>

#include "core/error.hpp"
#include "fluid/gas_boundary.hpp"
#include "io/hdf5_file.hpp"
#include "tfm/tfm_solver.hpp"

namespace fluidbed {

namespace {

class TfmModel final : public ModelRun {
 public:
  explicit TfmModel(const CaseConfig& c) : config_(c), solver_(c.tfm) {
    const Grid2& g = solver_.grid();
    for (Field2* f : {&ug_, &vg_, &us_, &vs_}) *f = Field2(g.nx, g.ny);
    refresh();
  }

  double time() const override { return solver_.time(); }
  void advance(double t_end) override {
    // Land exactly on every scheduled output time (monitor rows, frames, checkpoints), so that each is written
    // at its instant and a restarted run schedules the same steps.
    const double t = solver_.time();
    double t_stop = t_end;
    for (double interval : {config_.output.monitor_interval, config_.output.interval, config_.output.checkpoint_interval}) {
      if (interval > 0.0) t_stop = std::min(t_stop, (std::floor(t / interval + 1e-9) + 1.0) * interval);
    }
    last_dt_ = solver_.step(t_stop);
    refresh();
  }
  /// The step is adaptive and lands on the output times: no scheduling slack is needed.
  double macro_dt() const override { return 0.0; }
  // Columns defined in docs/output-format.md ("monitor.csv columns"). Mass and kinetic energy come per metre of
  // depth (the two-dimensional equations) and, for the contract columns, for a slab coupling.depth deep, the
  // basis of the CFD-DEM monolayer, so that the two models' columns of one name compare directly.
  std::vector<std::string> monitor_columns() const override {
    return {"kinetic_energy_J", "pressure_drop_Pa", "max_overlap_m", "gas_mass_residual", "solids_mass_kg",
            "solids_mass_per_depth_kg_m", "kinetic_energy_per_depth_J_m", "time_step_s", "min_voidage",
            "max_solids_speed_m_s", "granular_temperature_bed_max_m2_s2", "granular_temperature_solids_mean_m2_s2",
            "linear_solver_fallbacks", "inlet_velocity_m_s"};
  }
  std::vector<std::optional<double>> monitor_values() override {
    // Kinetic energy of the solids' mean motion per metre of depth, from cell-centred velocities.
    const Grid2& g = solver_.grid();
    const tfm::TfmState& s = solver_.state();
    double ke = 0.0;
    for (std::size_t c = 0; c < g.cells(); ++c) {
      ke += 0.5 * config_.tfm.rho_s * (1.0 - s.eps.v[c]) * (us_.v[c] * us_.v[c] + vs_.v[c] * vs_.v[c]) * g.dx * g.dy;
    }
    const double depth = config_.coupling.depth;
    const double mass = solver_.solids_mass();
    return {ke * depth, solver_.pressure_drop(), std::nullopt, solver_.gas_volume_residual(), mass * depth, mass, ke,
            last_dt_, solver_.min_voidage(), solver_.max_solids_speed(), solver_.bed_granular_temperature_max(),
            solver_.solids_mean_granular_temperature(), static_cast<double>(solver_.linear_fallbacks()),
            // The superficial inflow of the last step (the TFM takes it at the step's end, the current time).
            inlet_mean_velocity(config_.tfm.boundary, g, solver_.time())};
  }
  FieldView fields() override {
    FieldView f;
    f.set_grid(solver_.grid());
    f.eps = solver_.state().eps.v.data();
    f.p = solver_.state().p.v.data();
    f.ug = {ug_.v.data(), vg_.v.data(), nullptr};
    f.us = {us_.v.data(), vs_.v.data(), nullptr};
    f.theta = solver_.state().theta.v.data();
    return f;
  }

  void save(Hdf5File& f) const override {
    f.create_group("tfm");
    for (const tfm::NamedArray& a : solver_.save_state()) {
      f.write("tfm/" + a.name, a.values);
      f.set_attribute("tfm/" + a.name, "nx", static_cast<std::int64_t>(a.nx));
      f.set_attribute("tfm/" + a.name, "ny", static_cast<std::int64_t>(a.ny));
    }
    f.set_attribute("tfm", "last_dt", last_dt_);
  }
  void load(const Hdf5File& f) override {
    std::vector<tfm::NamedArray> wanted = solver_.save_state();  // the names and shapes this grid needs
    std::vector<tfm::NamedArray> arrays;
    for (tfm::NamedArray& a : wanted) {
      // An array the file lacks is left out: restore_state names it if it is required.
      if (f.has("tfm/" + a.name)) arrays.push_back(std::move(a));
    }
    for (tfm::NamedArray& a : arrays) {
      a.values = f.read_double("tfm/" + a.name);
      a.nx = static_cast<int>(f.attribute_int64("tfm/" + a.name, "nx"));
      a.ny = static_cast<int>(f.attribute_int64("tfm/" + a.name, "ny"));
    }
    solver_.restore_state(arrays);
    last_dt_ = f.attribute_double("tfm", "last_dt");
    refresh();
  }

  CostInfo cost() const override { return {0, solver_.grid().cells(), static_cast<std::uint64_t>(solver_.state().steps)}; }
  std::string describe() const override {
    const char* rheology = config_.tfm.rheology == tfm::SolidsRheology::KineticTheory   ? "kinetic theory"
                           : config_.tfm.rheology == tfm::SolidsRheology::Inviscid        ? "inviscid solids"
                                                                                           : "constant solids viscosity";
    return fmt::format("TFM ({}), {} x {} cells, adaptive dt <= {:g} s", rheology, solver_.grid().nx,
                       solver_.grid().ny, config_.tfm.dt_max);
  }

 private:
  void refresh() {
    solver_.gas_velocity_cells(ug_, vg_);
    solver_.solids_velocity_cells(us_, vs_);
  }

  CaseConfig config_;
  tfm::TfmSolver solver_;
  Field2 ug_, vg_, us_, vs_;
  double last_dt_ = 0.0;
};

}  // namespace

std::unique_ptr<ModelRun> make_tfm_model(const CaseConfig& config) { return std::make_unique<TfmModel>(config); }

}  // namespace fluidbed
