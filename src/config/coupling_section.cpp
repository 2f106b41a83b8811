// [coupling]: the CFD-DEM exchange into CaseConfig::coupling (CouplingConfig, coupling/coupling_config.hpp), with
// the gas step's DEM substeps chosen so that the output intervals hold whole gas steps.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "config/case_check.hpp"
#include "config/case_sections.hpp"
#include "core/error.hpp"
#include "fluid/gas_boundary.hpp"

namespace fluidbed {

namespace case_sections {

namespace {

// The output intervals a model step must divide for every row and frame to fall on k * interval
// (docs/output-format.md): frames, monitor rows and periodic checkpoints.
std::vector<std::pair<const char*, double>> output_intervals(const OutputConfig& o) {
  std::vector<std::pair<const char*, double>> v{{"output.interval", o.interval},
                                                {"output.monitor_interval", o.monitor_interval}};
  if (o.checkpoint_interval > 0.0) v.emplace_back("output.checkpoint_interval", o.checkpoint_interval);
  return v;
}

// The number of DEM steps of `dt` an interval holds, when it is a whole number.
std::optional<std::int64_t> whole_steps(double interval, double dt) {
  const double n = interval / dt;
  if (!(n >= 1.0) || std::abs(n - std::round(n)) > 1e-6 * n) return std::nullopt;
  return std::llround(n);
}

// The most DEM steps per gas step, at most `most`, whose gas step divides every output interval that is a whole
// number of DEM steps (the derived DEM step is rounded so that decimal intervals are).
int substeps_dividing_outputs(const OutputConfig& o, double dt, int most) {
  std::int64_t common = 0;
  for (const auto& [key, interval] : output_intervals(o)) {
    if (const auto n = whole_steps(interval, dt)) common = std::gcd(common, *n);
  }
  if (common == 0) return most;
  for (int n = most; n > 1; --n) {
    if (common % n == 0) return n;
  }
  return 1;
}

// Rows and frames of an interval the model step does not divide fall on the first step after each instant.
void note_outputs_between_steps(CaseConfig& c, double step) {
  for (const auto& [key, interval] : output_intervals(c.output)) {
    if (!whole_steps(interval, step)) {
      c.notes.push_back(fmt::format("{} = {:g} s is not a whole number of model steps ({:g} s): its outputs fall on "
                                    "the first step after each multiple of it, not on the multiple", key, interval, step));
    }
  }
}

}  // namespace

void read_coupling(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  const bool three_d = c.domain.dimension == 3;
  GasConfig& g = c.gas;
  // [coupling]
  CouplingConfig& cc = c.coupling;
  const std::string vm = r.string("coupling.voidage", "bilinear", "how particle volume is shared among cells: "
                                  "bilinear (cloud in cell) or centre (the paper's counting)", {"bilinear", "centre"});
  cc.voidage = vm == "centre" ? VoidageMethod::Centre : VoidageMethod::Bilinear;
  if (three_d) {
    // A 3D cell has a volume; the slab depth of the per-depth monitor columns is the domain's.
    if (r.has("coupling.depth")) {
      r.fail("coupling.depth", "a 3D case takes its cell volumes from the grid and its depth from domain.depth; "
                               "coupling.depth is for 2D monolayers");
    }
    cc.depth = c.domain.depth;
  } else {
    // A monolayer's slab is as deep as its largest sphere, whatever the order the species are listed in.
    double d_largest = 0.0;
    if (c.model == Model::Dem) {
      for (const Species& sp : c.dem.species) d_largest = std::max(d_largest, sp.d_max());
    }
    cc.depth = r.number("coupling.depth", c.model == Model::Dem ? d_largest : 0.004, "m",
                        "bed depth that turns particle volume into a volume fraction (one diameter: a monolayer); "
                        "2D only (3D: domain.depth)", R::positive());
    r.describe_default("coupling.depth", "the largest particle diameter of any species");
    if (c.model == Model::Dem && cc.depth < d_largest * (1.0 - 1e-12)) {
      c.notes.push_back(fmt::format("coupling.depth = {:g} m is thinner than the largest particle ({:g} m): the slab the "
                                    "2D bed stands for does not hold its largest spheres, and a packed layer of them "
                                    "may reach a voidage below zero, which stops the run", cc.depth, d_largest));
    }
  }
  cc.eps_min = r.number("coupling.eps_min", 0.3, "", "smallest voidage the gas and the drag see", R::Range{0.0, 1.0, true, true});
  const bool substeps_derived = c.model == Model::Dem && !r.has("dem.time_step") && !r.has("coupling.dem_substeps");
  int substeps_default = 1;
  double gas_dt_max = 0.0;
  if (substeps_derived) {
    // A derived DEM step (t_c / 20) is far below what the gas needs; step the gas at the largest multiple of it
    // within a Courant number of 0.5 on the fastest interstitial inflow (superficial / eps_min) and within half the
    // Stokes relaxation time rho_p d^2 / (18 mu_g) of the smallest particle, so the drag stays resolved.
    const double u_max = inlet_peak_velocity(g.boundary);
    double h_min = std::min(c.grid.dx, c.grid.dy);
    if (three_d) h_min = std::min(h_min, c.grid.dz);
    const double courant = u_max > 0.0 ? 0.5 * h_min * cc.eps_min / u_max : 1e300;
    double stokes = 1e300;
    for (const Species& sp : c.dem.species) {
      stokes = std::min(stokes, sp.density * sp.diameter * sp.diameter / (18.0 * g.mu_g));
    }
    gas_dt_max = std::min(courant, 0.5 * stokes);
    const int most = static_cast<int>(std::clamp(std::floor(gas_dt_max / c.dem.dt * (1.0 + 1e-12)), 1.0, 1000.0));
    substeps_default = substeps_dividing_outputs(c.output, c.dem.dt, most);
  }
  cc.dem_substeps = static_cast<int>(r.integer("coupling.dem_substeps", substeps_default,
                                               "DEM steps per gas step; default 1 when dem.time_step is given, else "
                                               "the most whose gas step keeps a Courant number of 0.5 on the fastest "
                                               "interstitial inflow and half the Stokes time of the smallest particle",
                                               R::between(1, 1000)));
  if (substeps_derived) {
    r.describe_default("coupling.dem_substeps", "1, or derived with dem.time_step");
    c.notes.push_back(fmt::format("coupling.dem_substeps not given: {} DEM steps per gas step (gas step {:g} s, at "
                                  "most {:.3g} s for a Courant number of 0.5 on the inflow and half the Stokes time "
                                  "of the smallest particle, and a whole fraction of the output intervals)",
                                  cc.dem_substeps, cc.dem_substeps * c.dem.dt, gas_dt_max));
  }
  if (c.model == Model::Dem) note_outputs_between_steps(c, c.gas_enabled ? c.dem.dt * cc.dem_substeps : c.dem.dt);
  const std::string law = r.string("coupling.drag_law", "ergun-wen-yu", "gas-particle drag law (docs/model.md): the "
                                   "paper's Eqs. 13-14, Gidaspow (1994), Di Felice (1994), Beetstra et al. (2007) or "
                                   "Koch & Hill (2001); CFD-DEM and TFM",
                                   {"ergun-wen-yu", "gidaspow", "di-felice", "beetstra", "koch-hill"});
  cc.drag_law = law == "gidaspow"    ? DragLaw::Gidaspow
                : law == "di-felice" ? DragLaw::DiFelice
                : law == "beetstra"  ? DragLaw::Beetstra
                : law == "koch-hill" ? DragLaw::KochHill
                                     : DragLaw::ErgunWenYu;
  // Gidaspow's law is used with the Huilin-Gidaspow blend (MFIX's GIDASPOW_BLEND); the paper's with its step.
  const std::string sw = r.string("coupling.drag_switch", cc.drag_law == DragLaw::Gidaspow ? "smooth" : "sharp",
                                  "Ergun to Wen-Yu at eps = 0.8 (drag_law ergun-wen-yu or gidaspow): a step or the "
                                  "arctan blend of Huilin & Gidaspow (2003)", {"sharp", "smooth"});
  r.describe_default("coupling.drag_switch", "\"sharp\"; \"smooth\" for gidaspow");
  cc.drag_switch = sw == "smooth" ? DragSwitch::Smooth : DragSwitch::Sharp;
  // "sharp" (the resolved default) is harmless for a law without branches; asking for a blend there is an error.
  const bool switched = cc.drag_law == DragLaw::ErgunWenYu || cc.drag_law == DragLaw::Gidaspow;
  if (!switched && cc.drag_switch == DragSwitch::Smooth) {
    r.fail("coupling.drag_switch", fmt::format("the drag law \"{}\" has no Ergun/Wen-Yu branches to blend; "
                                               "\"smooth\" is for \"ergun-wen-yu\" and \"gidaspow\"", law));
  }
  cc.pressure_gradient_force = r.boolean("coupling.pressure_force", true, "apply -V_p grad P to each particle");

  if (c.model == Model::Tfm) read_tfm(r, c);  // before [bubble]: the U_mf default needs the solids
}

}  // namespace case_sections
}  // namespace fluidbed
