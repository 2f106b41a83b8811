#include "io/dem_model.hpp"

#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "analysis/layer_tracers.hpp"
#include "core/error.hpp"
#include "dem/dem_solver.hpp"
#include "dem/packing.hpp"
#include "dem/settle.hpp"
#include "io/csv.hpp"
#include "io/hdf5_file.hpp"

namespace fluidbed {

ParticleStore particles_from_csv(const std::string& path, const DemConfig& dem) {
  const std::vector<ParticleCsvRow> rows = read_particles_csv(path);
  ParticleStore p;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const ParticleCsvRow& row = rows[r];
    if (row.species < 0 || static_cast<std::size_t>(row.species) >= dem.n_species()) {
      throw_input_error(fmt::format("{}: row {}, column species: species {} is not defined in the case (it has {})",
                                    path, r + 2, row.species, dem.n_species()));
    }
    const Species& s = dem.species[static_cast<std::size_t>(row.species)];
    if (row.x < s.radius() || row.x > dem.width - s.radius() || row.y < s.radius() || row.y > dem.height) {
      throw_input_error(fmt::format("{}: row {}, columns x,y: particle {} at ({}, {}) m is not inside the "
                                    "{} x {} m domain", path, r + 2, row.id, row.x, row.y, dem.width, dem.height));
    }
    p.add(row.id, row.species, s, {row.x, row.y}, {row.vx, row.vy}, row.omega);
  }
  return p;
}

namespace {

std::vector<double> wall_xi_flat(const std::vector<std::array<Vec2, 4>>& w) {
  std::vector<double> out;
  out.reserve(w.size() * 8);
  for (const auto& a : w) {
    for (const Vec2& v : a) {
      out.push_back(v.x);
      out.push_back(v.y);
    }
  }
  return out;
}

class DemModel final : public ModelRun {
 public:
  DemModel(const CaseConfig& c, const std::string& out_dir, bool fresh, spdlog::logger& log)
      : config_(c), log_(log), dem_(c.dem, fresh ? initial_particles(c, out_dir, log) : ParticleStore{}) {}

  double time() const override { return dem_.time(); }
  void advance() override { dem_.step(); }
  double macro_dt() const override { return dem_.config().dt; }

  std::vector<std::string> monitor_columns() const override {
    return {"kinetic_energy_J", "pressure_drop_Pa", "max_overlap_m", "gas_mass_residual", "solids_mass_kg",
            "neighbor_rebuilds"};
  }
  std::vector<std::optional<double>> monitor_values() override {
    double mass = 0.0;
    for (double m : dem_.particles().mass) mass += m;
    return {dem_.kinetic_energy(), std::nullopt, dem_.max_overlap(), std::nullopt, mass,
            static_cast<double>(dem_.rebuild_count())};
  }
  FieldView fields() override { return {}; }
  const ParticleStore* particles() const override { return &dem_.particles(); }

  void save(Hdf5File& f) const override {
    const DemSolver::State s = dem_.state();
    const ParticleStore& p = s.particles;
    f.create_group("dem");
    f.write("dem/id", p.id);
    f.write("dem/species", p.species);
    f.write("dem/layer", p.layer);
    for (const auto& [name, a] : std::initializer_list<std::pair<const char*, const std::vector<double>*>>{
             {"x", &p.x}, {"y", &p.y}, {"vx", &p.vx}, {"vy", &p.vy}, {"omega", &p.omega}, {"fx_ext", &p.fx_ext},
             {"fy_ext", &p.fy_ext}, {"drag_k", &p.drag_k}, {"ugx", &p.ugx}, {"ugy", &p.ugy},
             {"x_build", &s.x_build}, {"y_build", &s.y_build}}) {
      f.write(std::string("dem/") + name, *a);
    }
    std::vector<std::int64_t> offset(s.neighbors.offset.begin(), s.neighbors.offset.end());
    std::vector<std::int64_t> partner(s.neighbors.partner.begin(), s.neighbors.partner.end());
    std::vector<double> hx, hy;
    for (const Vec2& h : s.neighbors.history) {
      hx.push_back(h.x);
      hy.push_back(h.y);
    }
    f.write("dem/nbr_offset", offset);
    f.write("dem/nbr_partner", partner);
    f.write("dem/nbr_xi_x", hx);
    f.write("dem/nbr_xi_y", hy);
    f.write("dem/wall_xi", wall_xi_flat(s.wall_xi));
    f.set_attribute("dem", "time", s.time);
    f.set_attribute("dem", "steps", static_cast<std::int64_t>(s.steps));
    f.set_attribute("dem", "rebuilds", static_cast<std::int64_t>(s.rebuilds));
    f.set_attribute("dem", "need_rebuild", static_cast<std::int64_t>(s.need_rebuild));
  }

  void load(const Hdf5File& f) override {
    DemSolver::State s;
    const auto id = f.read_int64("dem/id");
    const auto species = f.read_int32("dem/species");
    const auto layer = f.read_int32("dem/layer");
    if (species.size() != id.size() || layer.size() != id.size()) {
      throw_input_error(fmt::format("{}: inconsistent particle arrays", f.path().string()));
    }
    ParticleStore& p = s.particles;
    for (std::size_t i = 0; i < id.size(); ++i) {
      if (species[i] < 0 || static_cast<std::size_t>(species[i]) >= config_.dem.n_species()) {
        throw_input_error(fmt::format("{}: particle {} has species {} which the case does not define",
                                      f.path().string(), id[i], species[i]));
      }
      p.add(id[i], species[i], config_.dem.species[static_cast<std::size_t>(species[i])], {}, {}, 0.0, layer[i]);
    }
    auto read = [&](const char* name, std::vector<double>& dst) {
      std::vector<double> v = f.read_double(std::string("dem/") + name);
      if (v.size() != id.size()) {
        throw_input_error(fmt::format("{}: dem/{} has {} values for {} particles", f.path().string(), name, v.size(), id.size()));
      }
      dst = std::move(v);
    };
    read("x", p.x);
    read("y", p.y);
    read("vx", p.vx);
    read("vy", p.vy);
    read("omega", p.omega);
    read("fx_ext", p.fx_ext);
    read("fy_ext", p.fy_ext);
    read("drag_k", p.drag_k);
    read("ugx", p.ugx);
    read("ugy", p.ugy);
    read("x_build", s.x_build);
    read("y_build", s.y_build);
    const auto offset = f.read_int64("dem/nbr_offset");
    const auto partner = f.read_int64("dem/nbr_partner");
    const auto hx = f.read_double("dem/nbr_xi_x");
    const auto hy = f.read_double("dem/nbr_xi_y");
    const auto wall = f.read_double("dem/wall_xi");
    const std::size_t n = id.size();
    if (offset.size() != n + 1 || offset.front() != 0 || static_cast<std::size_t>(offset.back()) != partner.size() ||
        hx.size() != partner.size() || hy.size() != partner.size() || wall.size() != 8 * n) {
      throw_input_error(fmt::format("{}: the neighbour list or contact history is inconsistent", f.path().string()));
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (offset[i + 1] < offset[i]) throw_input_error(fmt::format("{}: bad neighbour offsets", f.path().string()));
    }
    s.neighbors.offset.assign(offset.begin(), offset.end());
    s.neighbors.partner.resize(partner.size());
    s.neighbors.history.resize(partner.size());
    for (std::size_t k = 0; k < partner.size(); ++k) {
      if (partner[k] < 0 || static_cast<std::size_t>(partner[k]) >= n) {
        throw_input_error(fmt::format("{}: neighbour index out of range", f.path().string()));
      }
      s.neighbors.partner[k] = static_cast<std::uint32_t>(partner[k]);
      s.neighbors.history[k] = {hx[k], hy[k]};
    }
    s.wall_xi.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (int w = 0; w < 4; ++w) s.wall_xi[i][static_cast<std::size_t>(w)] = {wall[8 * i + 2 * w], wall[8 * i + 2 * w + 1]};
    }
    s.time = f.attribute_double("dem", "time");
    s.steps = static_cast<std::uint64_t>(f.attribute_int64("dem", "steps"));
    s.rebuilds = static_cast<std::uint64_t>(f.attribute_int64("dem", "rebuilds"));
    s.need_rebuild = f.attribute_int64("dem", "need_rebuild") != 0;
    dem_.restore(std::move(s));
  }

  CostInfo cost() const override { return {dem_.particles().size(), 0, dem_.step_count()}; }
  std::string describe() const override {
    return fmt::format("DEM, {} particles, dt = {:g} s, no gas", dem_.particles().size(), dem_.config().dt);
  }

 private:
  static ParticleStore initial_particles(const CaseConfig& c, const std::string& out_dir, spdlog::logger& log) {
    namespace fs = std::filesystem;
    const fs::path case_dir = fs::path(c.source_path).parent_path();
    auto resolve = [&](const std::string& f) { return fs::path(f).is_absolute() ? fs::path(f) : case_dir / f; };
    ParticleStore p;
    if (c.particles.source == ParticleSource::File) {
      p = particles_from_csv(resolve(c.particles.file).string(), c.dem);
      log.info("read {} particles from {}", p.size(), resolve(c.particles.file).string());
    } else if (!c.settle.cache.empty() && c.settle.enabled && fs::exists(resolve(c.settle.cache))) {
      p = particles_from_csv(resolve(c.settle.cache).string(), c.dem);
      if (static_cast<std::int64_t>(p.size()) != c.particles.packing.count) {
        throw_input_error(fmt::format("{}: the settled bed has {} particles but particles.count is {}; delete the "
                                      "file to settle a new bed", resolve(c.settle.cache).string(), p.size(),
                                      c.particles.packing.count));
      }
      log.info("reusing the settled bed {} ({} particles)", resolve(c.settle.cache).string(), p.size());
    } else {
      p = place_random(c.dem, c.particles.packing);
      log.info("placed {} particles at random (seed {})", p.size(), c.particles.packing.seed);
      if (c.settle.enabled) {
        DemConfig vacuum = c.dem;
        DemSolver settler(vacuum, std::move(p));
        const auto t0 = std::chrono::steady_clock::now();
        const SettleResult r = settle_bed(settler, c.settle.kinetic_energy_per_particle, c.settle.max_time);
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        p = settler.particles();
        log.info("settled in vacuum for {:.3f} s ({} steps, {:.1f} s wall): kinetic energy {:.3g} J per particle{}",
                 r.time, settler.step_count(), wall, r.kinetic_energy_per_particle,
                 r.converged ? "" : " (max_time reached before the threshold)");
        write_particles_csv(fs::path(out_dir) / "settled.csv", p);
        if (!c.settle.cache.empty()) {
          fs::create_directories(resolve(c.settle.cache).parent_path());
          write_particles_csv(resolve(c.settle.cache), p);
          log.info("saved the settled bed to {}", resolve(c.settle.cache).string());
        }
      }
    }
    const double h = bed_height(p, c.dem.width, 30);
    assign_layers(p, c.particles.layers, h);
    log.info("bed height {:.4f} m, {} colour layers", h, c.particles.layers);
    return p;
  }

  CaseConfig config_;
  spdlog::logger& log_;
  DemSolver dem_;
};

}  // namespace

std::unique_ptr<ModelRun> make_dem_model(const CaseConfig& config, const std::string& out_dir, bool fresh,
                                         spdlog::logger& log) {
  return std::make_unique<DemModel>(config, out_dir, fresh, log);
}

}  // namespace fluidbed
