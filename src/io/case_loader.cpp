#include "io/case_loader.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "core/error.hpp"
#include "dem/contact_law.hpp"
#include "io/dem_model.hpp"
#include <filesystem>

namespace fluidbed {

double dem_stable_time_step(const DemConfig& dem) {
  double dt = 1e300;
  auto limit = [&](double m_eff, double e) {
    const double k = dem.stiffness * std::max(1.0, dem.tangential_stiffness_ratio);
    const double eta = damping_from_restitution(m_eff, k, e);
    const double w0 = std::sqrt(k / m_eff);
    const double zeta = eta / (2.0 * std::sqrt(m_eff * k));
    dt = std::min(dt, 2.0 / w0 * (std::sqrt(1.0 + zeta * zeta) - zeta));
  };
  for (std::size_t a = 0; a < dem.n_species(); ++a) {
    for (std::size_t b = 0; b < dem.n_species(); ++b) {
      limit(reduced_mass(dem.species[a].mass(), dem.species[b].mass()),
            dem.pair_params(static_cast<int>(a), static_cast<int>(b)).restitution);
    }
    limit(dem.species[a].mass(), dem.wall[a].restitution);
  }
  return dt;
}

namespace {

void read_case(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  // [case]
  c.name = r.required_string("case.name", "name of the case; the default output folder is out/<name>");
  if (c.name.empty() || c.name.find_first_of("/\\") != std::string::npos) {
    r.fail("case.name", "must be a non-empty name without slashes (it names the output folder)");
  }
  c.description = r.string("case.description", "", "one line saying what the case is");
  const std::string model = r.string("case.model", "dem", "which model: discrete particles (CFD-DEM, or DEM alone "
                                     "when gas.enabled = false) or the two-fluid model", {"dem", "tfm"});
  c.model = model == "tfm" ? Model::Tfm : Model::Dem;
  c.run.end_time = r.number("case.end_time", 1.0, "s", "simulated time at which the run ends", R::positive());
  c.seed = static_cast<std::uint64_t>(r.integer("case.seed", 1998, "seed of the random placement of particles",
                                                R::non_negative()));
  c.run.max_wall_time = r.number("case.max_wall_time", 0.0, "s",
                                 "stop with a checkpoint (exit 130) after this wall time; 0 = no limit", R::non_negative());

  // [domain]
  c.dem.width = r.number("domain.width", 0.6, "m", "bed width (x)", R::positive());
  c.dem.height = r.number("domain.height", 1.0, "m", "domain height (y)", R::positive());
  c.dem.walls.top = r.boolean("domain.top_wall", false, "particles meet a wall at the top (the gas outlet stays open)");

  if (c.model == Model::Tfm) return;  // the particle keys belong to the discrete model

  // [[species]]
  const std::size_t ns = std::max<std::size_t>(1, r.table_count("species", "particle species; default: one species"));
  c.dem.species.assign(ns, Species{});
  std::vector<double> fraction(ns, 1.0 / static_cast<double>(ns));
  for (std::size_t s = 0; s < ns; ++s) {
    const std::string p = fmt::format("species[{}].", s);
    c.dem.species[s].diameter = r.number(p + "diameter", 0.004, "m", "particle diameter", R::positive());
    c.dem.species[s].density = r.number(p + "density", 2700.0, "kg/m^3", "particle density", R::positive());
    fraction[s] = r.number(p + "fraction", 1.0 / static_cast<double>(ns), "",
                           "number fraction of the randomly placed particles", R::between(0.0, 1.0));
  }
  double fsum = 0.0;
  for (double f : fraction) fsum += f;
  if (std::abs(fsum - 1.0) > 1e-9) r.fail("species[0].fraction", fmt::format("the fractions add up to {}, not 1", fsum));
  c.particles.packing.species_fraction = fraction;

  // [contact]
  const R::Range restitution{0.0, 1.0, true, false};
  c.dem.stiffness = r.number("contact.stiffness", 800.0, "N/m", "spring stiffness k of Eqs. 2-3", R::positive());
  c.dem.tangential_stiffness_ratio = r.number("contact.tangential_stiffness_ratio", 1.0, "",
                                              "k_t / k_n (the paper uses one k)", R::positive());
  const double e_pp = r.number("contact.restitution", 0.9, "", "particle-particle restitution e (Eq. 8)", restitution);
  const double mu_pp = r.number("contact.friction", 0.3, "", "particle-particle friction mu_f (Eq. 6)", R::non_negative());
  const double e_pw = r.number("contact.wall_restitution", e_pp, "", "particle-wall restitution", restitution);
  const double mu_pw = r.number("contact.wall_friction", mu_pp, "", "particle-wall friction", R::non_negative());
  c.dem.pair.assign(ns * ns, InteractionParams{e_pp, mu_pp});
  c.dem.wall.assign(ns, InteractionParams{e_pw, mu_pw});
  const std::size_t npairs = r.table_count("contact.pair", "restitution and friction of one species pair");
  for (std::size_t k = 0; k < npairs; ++k) {
    const std::string p = fmt::format("contact.pair[{}].", k);
    const auto a = r.integer(p + "species_a", 0, "first species index", R::between(0, static_cast<double>(ns - 1)));
    const auto b = r.integer(p + "species_b", 0, "second species index", R::between(0, static_cast<double>(ns - 1)));
    const InteractionParams ip{r.number(p + "restitution", e_pp, "", "restitution of the pair", restitution),
                               r.number(p + "friction", mu_pp, "", "friction of the pair", R::non_negative())};
    c.dem.pair[static_cast<std::size_t>(a) * ns + static_cast<std::size_t>(b)] = ip;
    c.dem.pair[static_cast<std::size_t>(b) * ns + static_cast<std::size_t>(a)] = ip;
  }

  // [dem]
  c.dem.dt = r.number("dem.time_step", 2e-4, "s", "DEM time step (the paper: 2e-4 s)", R::positive());
  c.dem.skin = r.number("dem.skin", 0.1 * c.dem.species[0].diameter, "m",
                        "Verlet skin of the neighbour list; the list is rebuilt when a particle has moved half of it",
                        R::non_negative());
  const auto g = r.numbers("dem.gravity", {0.0, -9.81}, "m/s^2", "gravitational acceleration (x, y)", 2);
  c.dem.gravity = {g[0], g[1]};
  const double dt_max = dem_stable_time_step(c.dem);
  if (c.dem.dt > dt_max) {
    r.fail("dem.time_step", fmt::format("{} s is above the stability limit of the stiffest contact; the largest "
                                        "stable time step is {:.4g} s", c.dem.dt, dt_max));
  }

  // [particles]
  const std::string source = r.string("particles.source", "random",
                                      "random: place at random (then settle, see [settle]); file: read a CSV "
                                      "id,x,y,vx,vy,omega,species",
                                      {"random", "file"});
  c.particles.source = source == "file" ? ParticleSource::File : ParticleSource::Random;
  c.particles.file = r.string("particles.file", "", "CSV file of particles (particles.source = \"file\"), "
                              "relative to the case file");
  if (c.particles.source == ParticleSource::File && c.particles.file.empty()) {
    r.fail("particles.file", "particles.source = \"file\" needs particles.file");
  }
  c.particles.packing.count = r.integer("particles.count", 22000, "number of particles placed at random", R::positive());
  c.particles.packing.x_min = 0.0;
  c.particles.packing.x_max = c.dem.width;
  c.particles.packing.y_min = 0.0;
  c.particles.packing.y_max = r.number("particles.fill_height", c.dem.height, "m",
                                       "top of the region where particles are placed at random", R::positive());
  if (c.particles.packing.y_max > c.dem.height) {
    r.fail("particles.fill_height", fmt::format("{} m is above the domain height {} m", c.particles.packing.y_max, c.dem.height));
  }
  c.particles.packing.min_gap = r.number("particles.gap", 0.05 * c.dem.species[0].diameter, "m",
                                         "smallest gap between randomly placed particles", R::non_negative());
  c.particles.packing.seed = c.seed;
  if (c.particles.source == ParticleSource::Random) {
    const std::int64_t capacity = random_placement_capacity(c.dem, c.particles.packing);
    if (c.particles.packing.count > capacity) {
      r.fail("particles.count", fmt::format("{} particles do not fit in the {} x {} m placement region: at most {} "
                                            "with a gap of {} m; raise particles.fill_height or domain.height",
                                            c.particles.packing.count, c.dem.width, c.particles.packing.y_max, capacity,
                                            c.particles.packing.min_gap));
    }
  } else {
    // Read the file now, so that `check` reports a bad row before any run.
    const auto path = std::filesystem::path(c.particles.file).is_absolute()
                          ? std::filesystem::path(c.particles.file)
                          : std::filesystem::path(r.file_name()).parent_path() / c.particles.file;
    c.particles.packing.count = static_cast<std::int64_t>(particles_from_csv(path.string(), c.dem).size());
  }
  c.particles.layers = static_cast<int>(r.integer("particles.layers", 6, "colour layers of the initial bed (Fig. 4)",
                                                  R::between(1, 1000)));

  // [settle]
  c.settle.enabled = r.boolean("settle.enabled", true, "settle the random placement in vacuum before t = 0") &&
                     c.particles.source != ParticleSource::File;
  c.settle.kinetic_energy_per_particle = r.number("settle.kinetic_energy_per_particle", 1e-10, "J",
                                                  "the bed is settled when the mean kinetic energy per particle falls below this",
                                                  R::positive());
  c.settle.max_time = r.number("settle.max_time", 3.0, "s", "longest settling time", R::positive());
  c.settle.cache = r.string("settle.cache", "", "CSV of the settled bed: reused when present, written after "
                            "settling; relative to the case file");
  c.gas_enabled = r.boolean("gas.enabled", true, "couple the particles to the gas (false: DEM alone, in vacuum)");
}

void read_output(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  c.output.interval = r.number("output.interval", 0.01, "s", "interval of fields, particles, tracers and bubble samples", R::positive());
  c.output.monitor_interval = r.number("output.monitor_interval", 0.001, "s", "interval of monitor.csv rows", R::positive());
  c.output.checkpoint_interval = r.number("output.checkpoint_interval", 0.25, "s",
                                          "interval of HDF5 checkpoints (one is always written at the end); 0 = end only",
                                          R::non_negative());
  c.output.fields = r.boolean("output.fields", true, "write fields.pvd and fields/*.vti");
  c.output.particles = r.boolean("output.particles", true, "write particles.pvd and particles/*.vtu (DEM)");
  c.output.particles_csv = r.boolean("output.particles_csv", false, "also write particles/*.csv at full precision (DEM)");
  c.output.tracers = r.boolean("output.tracers", true, "write the layer tracers (tracers/*.csv)");
}

LoadedCase finish(CaseReader& r, const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) r.set_override(o);
  LoadedCase out;
  read_case(r, out.config);
  read_output(r, out.config);
  r.reject_unknown_keys();
  out.config.source_path = r.file_name();
  out.resolved_toml = r.resolved_toml();
  out.keys = r.keys();
  return out;
}

}  // namespace

LoadedCase load_case(const std::string& path, const std::vector<std::string>& overrides) {
  CaseReader r(path);
  return finish(r, overrides);
}

LoadedCase load_case_text(const std::string& text, const std::string& name, const std::vector<std::string>& overrides) {
  CaseReader r(text, name);
  return finish(r, overrides);
}

}  // namespace fluidbed
