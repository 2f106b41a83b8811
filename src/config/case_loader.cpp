#include "config/case_loader.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "config/case_check.hpp"
#include "config/case_sections.hpp"
#include "core/error.hpp"
#include "fluid/gas_boundary.hpp"

namespace fluidbed {

namespace {

using namespace case_sections;

// [case] and [domain]: what every model reads.
void read_case_and_domain(CaseReader& r, CaseConfig& c) {
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

  c.domain.dimension = static_cast<int>(r.integer("case.dimension", 2, "2: a monolayer in the x-y plane (per metre "
                                                  "of depth, coupling.depth deep); 3: a box with front and back walls "
                                                  "(domain.depth deep)", R::between(2, 3)));
  const bool three_d = c.domain.dimension == 3;

  // [domain]: the box and gravity of every model, read here only and copied into each model's config.
  c.domain.width = r.number("domain.width", 0.6, "m", "bed width (x)", R::positive());
  c.domain.height = r.number("domain.height", 1.0, "m", "domain height (y)", R::positive());
  if (three_d) {
    c.domain.depth = r.required_number("domain.depth", "m", "bed depth (z, between the front and back walls); 3D "
                                       "only (case.dimension = 3), required there", R::positive());
  } else if (r.has("domain.depth")) {
    r.fail("domain.depth", "a 2D case (case.dimension = 2) has no depth: its bed is a monolayer per metre of depth "
                           "(coupling.depth sets the slab its volume fractions stand for); set case.dimension = 3 for "
                           "a bed between front and back walls");
  }
  check_domain_plausible(r, c.domain);
  r.alias("dem.gravity", "domain.gravity");  // its name before the two-fluid model could set it
  const auto grav = r.numbers("domain.gravity", three_d ? std::vector<double>{0.0, -9.81, 0.0} : std::vector<double>{0.0, -9.81},
                              "m/s^2", "gravitational acceleration (x, y) of every model, (x, y, z) in 3D; a 2D case "
                              "takes three only with z = 0 (dem.gravity is read as this key)", 2, 3);
  if (three_d && grav.size() != 3) {
    r.fail("domain.gravity", fmt::format("a 3D case needs three components (x, y, z), got {}", grav.size()));
  }
  if (!three_d && grav.size() == 3 && grav[2] != 0.0) {
    r.fail("domain.gravity", fmt::format("z = {} m/s^2 in a 2D case, whose bed lies in the x-y plane: give (x, y), "
                                         "or set case.dimension = 3", grav[2]));
  }
  c.domain.gravity = {grav[0], grav[1], grav.size() == 3 ? grav[2] : 0.0};
  const std::vector<std::string> periodic =
      r.strings("domain.periodic", {}, "periodic axes: particles and gas leaving through one side re-enter through "
                "the opposite one, with no walls there (x; z too in 3D; every model)",
                three_d ? std::vector<std::string>{"x", "z"} : std::vector<std::string>{"x"});
  for (const std::string& axis : periodic) c.domain.periodic[axis == "x" ? 0 : 2] = true;
  c.dem.domain = c.domain;
  const std::string ptop = r.string("domain.particle_top", "open", "what particles meet at the top: open (a particle "
                                    "that crosses it fails the run), wall (they bounce; the gas outlet stays open), "
                                    "outflow (they leave, removed and counted in monitor.csv); the other sides are "
                                    "walls unless periodic (domain.periodic) or outflow (domain.particle_outflow)",
                                    {"open", "wall", "outflow"});
  c.dem.walls.top = ptop == "wall";
  c.dem.walls.top_outflow = ptop == "outflow";
  {
    const std::vector<std::string> sides = three_d
        ? std::vector<std::string>{"left", "right", "bottom", "top", "back", "front"}
        : std::vector<std::string>{"left", "right", "bottom", "top"};
    const std::vector<std::string> out =
        r.strings("domain.particle_outflow", {}, "sides particles leave through (no wall there; each particle that "
                  "crosses is removed and counted in monitor.csv, particles_lost and mass_lost_kg); \"top\" is "
                  "domain.particle_top = \"outflow\"", sides);
    for (const std::string& side : out) {
      const auto w = static_cast<std::size_t>(std::find(sides.begin(), sides.end(), side) - sides.begin());
      if (c.domain.periodic[w / 2]) {
        r.fail("domain.particle_outflow", fmt::format("the {} side lies on a periodic axis (domain.periodic): it has "
                                                      "no boundary to leave through", side));
      }
      if (w == 3 && ptop == "wall") {
        r.fail("domain.particle_outflow", "the top is an outflow here but domain.particle_top = \"wall\"");
      }
      if (w == 3) {
        c.dem.walls.top_outflow = true;
      } else {
        c.dem.walls.side_outflow[w] = true;
      }
    }
    WallConfig& wl = c.dem.walls;
    wl.left = !wl.outflow(0) && !c.domain.periodic[0];
    wl.right = !wl.outflow(1) && !c.domain.periodic[0];
    wl.bottom = !wl.outflow(2);
    wl.back = !wl.outflow(4) && !c.domain.periodic[2];
    wl.front = !wl.outflow(5) && !c.domain.periodic[2];
  }
}

// The sections of the case, in the key table's order; the particle sections belong to the discrete model.
void read_case(CaseReader& r, CaseConfig& c) {
  read_case_and_domain(r, c);
  if (c.model == Model::Tfm) return;
  read_species(r, c);
  read_contact(r, c);
  read_dem(r, c);
  read_insertion(r, c);
  read_particles(r, c);
  read_settle(r, c);
}

// [grid], [gas], [inlet], [coupling] and [bubble], in that order (the key table's): read (and checked) even when the
// gas is off, so toggling gas.enabled is safe.
void read_gas(CaseReader& r, CaseConfig& c) {
  GasKeys k;
  read_grid(r, c, k);
  read_gas_phase(r, c, k);
  read_inlet(r, c, k);
  read_coupling(r, c);
  read_bubble(r, c, k);
}

// Keys of earlier versions that are no longer read, with what replaced them (dem.gravity is still read, as an
// alias of domain.gravity): a case file of an earlier version gets the new name, not "unknown key".
void refuse_renamed_keys(const CaseReader& r) {
  const std::pair<const char*, const char*> renamed[] = {
      {"domain.top_wall", "is now domain.particle_top: \"wall\" for top_wall = true, \"open\" for false (or "
                          "\"outflow\": leaving particles removed and counted)"},
      {"tfm.inlet_noise", "is now inlet.noise, shared by both models (the same +- fraction per bottom cell, fixed in "
                          "time)"},
  };
  for (const auto& [old_key, now] : renamed) {
    if (r.has(old_key)) r.fail(old_key, fmt::format("{} {}", old_key, now));
  }
}

LoadedCase finish(CaseReader& r, const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) r.set_override(o);
  LoadedCase out;
  read_case(r, out.config);
  read_output(r, out.config);  // before the gas: a derived gas step divides the output intervals
  read_parallel(r, out.config);
  read_gas(r, out.config);  // read (and checked) even when the gas is off, so toggling gas.enabled is safe
  read_probes(r, out.config);
  read_averages(r, out.config);
  refuse_renamed_keys(r);
  r.reject_unknown_keys();
  // What the gas solver and the bubble tracker check when they are built, so that `check` refuses what `run`
  // would (the TFM's own check, tfm::validate, runs in read_tfm).
  try {
    validate(out.config.gas);
    const BubbleTracker probe(out.config.bubble);
  } catch (const Error& e) {
    throw_input_error(fmt::format("{}: {}", r.file_name(), e.what()));
  }
  out.config.source_path = r.file_name();
  out.resolved_toml = r.resolved_toml();
  out.keys = r.keys();
  return out;
}

}  // namespace

std::string case_keys_markdown() {
  // Read a minimal case of each model with a jet, a pair table and one species so every key is registered.
  const std::string base = "case.name = \"keys\"\nspecies = [{diameter = 0.004}]\ncontact.pair = [{species_a = 0}]\n"
                           "inlet.jet = [{centre = 0.31}]\n";
  std::vector<KeyInfo> all = load_case_text(base, "keys.toml").keys;
  // Keys that only other cases read go after the last key of their table (or section), so sections stay whole.
  auto merge = [&all](const std::vector<KeyInfo>& more) {
    for (const KeyInfo& k : more) {
      if (std::any_of(all.begin(), all.end(), [&](const KeyInfo& a) { return a.path == k.path; })) continue;
      auto prefix = [](const std::string& path, bool table) {
        return table ? path.substr(0, path.rfind('.') + 1) : path.substr(0, path.find_first_of(".[") + 1);
      };
      std::size_t at = all.size();
      bool found = false;
      for (const bool table : {true, false}) {
        for (std::size_t i = 0; i < all.size() && !found; ++i) {
          if (prefix(all[i].path, table) != prefix(k.path, table)) continue;
          at = i + 1;
          while (at < all.size() && prefix(all[at].path, table) == prefix(k.path, table)) ++at;
          found = true;
        }
        if (found) break;
      }
      all.insert(all.begin() + static_cast<std::ptrdiff_t>(at), k);
    }
  };
  merge(load_case_text("case.name = \"keys\"\ncase.model = \"tfm\"\ninlet.jet = [{centre = 0.31}]\n", "keys.toml").keys);
  // One species of each size distribution: their keys.
  merge(load_case_text("case.name = \"keys\"\nspecies = [{size_distribution = \"uniform\", d_min = 0.003, d_max = 0.004}, "
                       "{size_distribution = \"normal\", mean = 0.004, std = 0.0002}, {size_distribution = \"log-normal\", "
                       "median = 0.004, sigma = 0.05}, {size_distribution = \"list\", diameters = [0.004], "
                       "fractions = [1.0]}]\n", "keys.toml").keys);
  // A 3D case with a jet of each shape: the keys of the depth.
  merge(load_case_text("case.name = \"keys\"\ncase.dimension = 3\ndomain.depth = 0.1\nspecies = [{diameter = 0.004}]\n"
                       "inlet.jet = [{centre = 0.31}, {centre = 0.31, shape = \"rectangle\"}, "
                       "{centre = 0.31, shape = \"disc\"}]\n", "keys.toml").keys);
  // The schedules' and plates' keys: a ramped background with ramp_start, a jet of each time-dependent kind, a plate
  // in 2D and 3D (keys read only for their kind).
  merge(load_case_text("case.name = \"keys\"\nspecies = [{diameter = 0.004}]\n"
                       "inlet = {schedule = \"ramp\", ramp_time = 0.1, jet = [{centre = 0.31, schedule = \"ramp\", "
                       "ramp_time = 0.1}, {centre = 0.31, schedule = \"table\", table_times = [0], table_velocities = "
                       "[1]}, {centre = 0.31, "
                       "schedule = \"square\", frequency = 1}], plate = [{hole_width = 0.004, pitch = 0.01}]}\n",
                       "keys.toml").keys);
  merge(load_case_text("case.name = \"keys\"\nspecies = [{diameter = 0.004}]\n"
                       "inlet = {schedule = \"sine\", frequency = 1}\n", "keys.toml").keys);
  merge(load_case_text("case.name = \"keys\"\nspecies = [{diameter = 0.004}]\n"
                       "inlet = {schedule = \"square\", frequency = 1}\n", "keys.toml").keys);
  merge(load_case_text("case.name = \"keys\"\nspecies = [{diameter = 0.004}]\n"
                       "inlet = {schedule = \"table\", table_times = [0], table_velocities = [1]}\n", "keys.toml").keys);
  merge(load_case_text("case.name = \"keys\"\ncase.dimension = 3\ndomain.depth = 0.1\nspecies = [{diameter = 0.004}]\n"
                       "inlet.plate = [{hole_diameter = 0.004, pitch = 0.01}]\n", "keys.toml").keys);
  std::string md;
  std::string section;
  for (const KeyInfo& k : all) {
    if (k.type == "array of tables") continue;
    const std::string sec = k.path.substr(0, k.path.find_first_of(".["));
    if (sec != section) {
      section = sec;
      md += fmt::format("\n### [{}]\n\n| key | type | unit | default | allowed | meaning |\n|---|---|---|---|---|---|\n", sec);
    }
    md += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", k.path, k.type, k.unit.empty() ? "-" : k.unit,
                      k.default_text.empty() ? "**required**" : "`" + k.default_text + "`",
                      k.range.empty() ? "-" : k.range, k.doc);
  }
  return md;
}

LoadedCase load_case(const std::string& path, const std::vector<std::string>& overrides) {
  CaseReader r(path);
  return finish(r, overrides);
}

LoadedCase load_case_text(const std::string& text, const std::string& name, const std::vector<std::string>& overrides) {
  CaseReader r(text, name);
  return finish(r, overrides);
}

}  // namespace fluidbed
