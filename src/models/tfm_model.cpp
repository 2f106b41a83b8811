#include "models/tfm_model.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <utility>

#include "core/error.hpp"
#include "fluid/gas_boundary.hpp"
#include "io/hdf5_file.hpp"
#include "tfm/tfm_solver.hpp"

namespace fluidbed {

namespace {

template <int Dim>
class TfmModel final : public ModelRun {
 public:
  TfmModel(const CaseConfig& c, const Comm& comm) : config_(c), comm_(comm), solver_(c.tfm, comm) {
    refresh(FieldNeed::All);
  }

  double time() const override { return solver_.time(); }
  double last_step() const override { return last_dt_; }
  void advance(double t_end) override {
    // Land exactly on every scheduled output time (monitor rows, frames, checkpoints), so that each is written
    // at its instant and a restarted run schedules the same steps.
    const double t = solver_.time();
    double t_stop = t_end;
    for (double interval : {config_.output.monitor_interval, config_.output.interval, config_.output.checkpoint_interval}) {
      if (interval > 0.0) t_stop = std::min(t_stop, (std::floor(t / interval + 1e-9) + 1.0) * interval);
    }
    const double c0 = comm_.seconds_communicating();
    const auto w0 = std::chrono::steady_clock::now();
    last_dt_ = solver_.advance(t_stop);
    step_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    step_comm_s_ += comm_.seconds_communicating() - c0;
    ++steps_;
  }
  void share_fields(FieldNeed need) override {
    const auto w0 = std::chrono::steady_clock::now();
    refresh(need);
    gather_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  }
  /// On several ranks: the blocks, and where a rank's time went (the solver's step, its communication with the
  /// waits for the other ranks, the observers' gather on rank 0), the most and the least of any rank.
  std::string parallel_summary() const override {
    if (comm_.size() == 1) return {};
    const IndexBox<Dim>& own = solver_.grid().owned;
    double v[8] = {static_cast<double>(own.count()), -static_cast<double>(own.count()), step_s_, -step_s_,
                   step_comm_s_, -step_comm_s_, gather_s_, -gather_s_};
    comm_.max(std::span<double>(v));
    const Grid<Dim>& g = solver_.grid();
    std::string blocks;
    for (int a = 0; a < Dim; ++a) blocks += (a ? " x " : "") + std::to_string(g.n(a) / std::max(1, own.extent(a)));
    const double steps = std::max(1.0, static_cast<double>(steps_));
    return fmt::format("decomposition: the TFM grid cut {} over {} ranks (x never cut), cells per rank "
                       "{:.0f}-{:.0f}; over {} steps, per rank: the step {:.2f}-{:.2f} s, of it inside communication "
                       "(waits for the other ranks included) {:.3f}-{:.3f} s ({:.2f}-{:.2f} ms a step), the observers' "
                       "gather on rank 0 {:.3f}-{:.3f} s",
                       blocks, comm_.size(), -v[1], v[0], steps_, -v[3], v[2], -v[5], v[4], -v[5] / steps * 1e3,
                       v[4] / steps * 1e3, -v[7], v[6]);
  }
  /// The step is adaptive and lands on the output times: no scheduling slack is needed.
  double macro_dt() const override { return 0.0; }
  // Columns defined in docs/output-format.md ("monitor.csv columns"). In 2D, mass and kinetic energy come per
  // metre of depth (the two-dimensional equations) and, for the contract columns, for a slab coupling.depth deep,
  // the basis of the CFD-DEM monolayer, so that the two models' columns of one name compare directly; in 3D both
  // are of the whole box (the _per_depth columns then divide by domain.depth).
  std::vector<std::string> monitor_columns() const override {
    return {"kinetic_energy_J", "pressure_drop_Pa", "max_overlap_m", "gas_mass_residual", "solids_mass_kg",
            "solids_mass_per_depth_kg_m", "kinetic_energy_per_depth_J_m", "time_step_s", "min_voidage",
            "max_solids_speed_m_s", "granular_temperature_bed_max_m2_s2", "granular_temperature_solids_mean_m2_s2",
            "linear_solver_fallbacks", "inlet_velocity_m_s"};
  }
  std::vector<std::optional<double>> monitor_values() override {
    const Grid<Dim>& g = solver_.grid();
    const double ke = solver_.solids_kinetic_energy();
    const double mass = solver_.solids_mass();
    // 2D: per metre of depth, and for the slab of coupling.depth; 3D: the box, and per metre of its depth.
    const double depth = Dim == 2 ? config_.coupling.depth : 1.0;
    const double per_depth = Dim == 2 ? 1.0 : 1.0 / config_.domain.depth;
    return {ke * depth, solver_.pressure_drop(), std::nullopt, solver_.gas_volume_residual(), mass * depth,
            mass * per_depth, ke * per_depth, last_dt_, solver_.min_voidage(), solver_.max_solids_speed(),
            solver_.bed_granular_temperature_max(), solver_.solids_mean_granular_temperature(),
            static_cast<double>(solver_.linear_fallbacks()),
            // The superficial inflow of the last step, taken at its midpoint as the solver took it (before the
            // first step, the schedules at t = 0).
            inlet_mean_velocity(config_.tfm.boundary, g, solver_.time() - 0.5 * last_dt_)};
  }
  FieldView fields() override {
    const Grid<Dim>& g = solver_.grid();
    FieldView f;
    f.dimension = Dim;
    for (int a = 0; a < Dim; ++a) {
      f.n[static_cast<std::size_t>(a)] = g.n(a);
      f.h[static_cast<std::size_t>(a)] = g.h[a];
      f.origin[static_cast<std::size_t>(a)] = g.origin[a];
    }
    f.eps = eps_.data();
    f.p = p_.data();
    for (int a = 0; a < Dim; ++a) {
      f.ug[static_cast<std::size_t>(a)] = ug_[a].data();
      f.us[static_cast<std::size_t>(a)] = us_[a].data();
    }
    f.theta = theta_.data();
    return f;
  }

  void save(Hdf5File* file) const override {
    // Gathered by every rank (a collective), written by the one that holds the file.
    const std::vector<tfm::NamedArray> state = solver_.save_state();
    if (file == nullptr) return;
    Hdf5File& f = *file;
    f.create_group("tfm");
    for (const tfm::NamedArray& a : state) {
      f.write("tfm/" + a.name, a.values);
      f.set_attribute("tfm/" + a.name, "nx", static_cast<std::int64_t>(a.nx));
      f.set_attribute("tfm/" + a.name, "ny", static_cast<std::int64_t>(a.ny));
      if (Dim == 3) f.set_attribute("tfm/" + a.name, "nz", static_cast<std::int64_t>(a.nz));
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
      a.nz = Dim == 3 ? static_cast<int>(f.attribute_int64("tfm/" + a.name, "nz")) : 1;
    }
    solver_.restore_state(arrays);
    last_dt_ = f.attribute_double("tfm", "last_dt");
    refresh(FieldNeed::All);
  }

  CostInfo cost() const override { return {0, solver_.grid().cells(), static_cast<std::uint64_t>(solver_.state().steps)}; }
  std::string describe() const override {
    const char* rheology = config_.tfm.rheology == tfm::SolidsRheology::KineticTheory   ? "kinetic theory"
                           : config_.tfm.rheology == tfm::SolidsRheology::Inviscid        ? "inviscid solids"
                           : config_.tfm.rheology == tfm::SolidsRheology::Bingham         ? "Bingham plastic solids"
                                                                                           : "constant solids viscosity";
    const Grid<Dim>& g = solver_.grid();
    const std::string cells = Dim == 2 ? fmt::format("{} x {}", g.n(0), g.n(1))
                                       : fmt::format("{} x {} x {}", g.n(0), g.n(1), g.n(Dim - 1));
    return fmt::format("TFM ({}), {} cells, adaptive dt <= {:g} s", rheology, cells, config_.tfm.dt_max);
  }

 private:
  // The observers read contiguous cell arrays (axis 0 fastest), the solver's fields carry ghost layers. On several
  // ranks they are rank 0's (the observers and writers are), gathered there when the runner says they will be read:
  // every rank takes part, while only rank 0 asks for the fields.
  void refresh(FieldNeed need) {
    if (need == FieldNeed::None) return;
    const tfm::TfmState<Dim>& s = solver_.state();
    const bool all = need == FieldNeed::All;
    if (all) solver_.gas_velocity_cells(ug_cells_);
    solver_.solids_velocity_cells(us_cells_);
    if (comm_.size() > 1) {
      gather_on_root(s, all);
      return;
    }
    for (int a = 0; a < Dim; ++a) us_[a] = us_cells_[a].interior();
    if (!all) return;
    eps_ = s.eps.interior();
    p_ = s.p.interior();
    theta_ = s.theta.interior();
    for (int a = 0; a < Dim; ++a) ug_[a] = ug_cells_[a].interior();
  }

  // Rank 0 receives every block into fields over the domain without ghosts (their storage is the observers'
  // layout); the others receive nothing. The solids velocity first, then (all) the voidage, pressure, Theta and gas
  // velocity.
  void gather_on_root(const tfm::TfmState<Dim>& s, bool all) {
    std::vector<const Field<Dim>*> fields;
    std::vector<std::vector<double>*> out;
    for (int a = 0; a < Dim; ++a) {
      fields.push_back(&us_cells_[a]);
      out.push_back(&us_[a]);
    }
    if (all) {
      for (const Field<Dim>* f : {&s.eps, &s.p, &s.theta}) fields.push_back(f);
      for (std::vector<double>* v : {&eps_, &p_, &theta_}) out.push_back(v);
      for (int a = 0; a < Dim; ++a) {
        fields.push_back(&ug_cells_[a]);
        out.push_back(&ug_[a]);
      }
    }
    const bool root = comm_.rank() == 0;
    std::vector<Field<Dim>*> into;
    if (root) {
      if (whole_.size() < fields.size()) whole_.assign(fields.size(), Field<Dim>(solver_.grid().domain, 0));
      for (std::size_t k = 0; k < fields.size(); ++k) into.push_back(&whole_[k]);
    }
    gather_parts<Dim>(comm_, solver_.grid().owned, fields, into, 0);
    if (!root) return;
    for (std::size_t k = 0; k < out.size(); ++k) *out[k] = whole_[k].data();
  }

  CaseConfig config_;
  const Comm& comm_;
  tfm::TfmSolver<Dim> solver_;
  double step_s_ = 0.0, step_comm_s_ = 0.0, gather_s_ = 0.0;  // this process's time in steps, their MPI, the gather
  long steps_ = 0;
  tfm::CellVectorField<Dim> ug_cells_, us_cells_;
  std::vector<Field<Dim>> whole_;  // rank 0, several ranks: the gathered fields (u_s, then eps, p, Theta, u_g)
  std::vector<double> eps_, p_, theta_;
  std::array<std::vector<double>, Dim> ug_, us_;
  double last_dt_ = 0.0;
};

}  // namespace

std::unique_ptr<ModelRun> make_tfm_model(const CaseConfig& config, const Comm& comm) {
  if (config.domain.dimension == 3) return std::make_unique<TfmModel<3>>(config, comm);
  return std::make_unique<TfmModel<2>>(config, comm);
}

}  // namespace fluidbed
