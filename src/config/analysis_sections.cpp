// [bubble], [probes] and [averages]: the observers into CaseConfig::bubble (BubbleConfig,
// analysis/bubble_tracker.hpp), CaseConfig::probes and CaseConfig::averages (analysis/probes.hpp, time_average.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "config/case_check.hpp"
#include "config/case_sections.hpp"
#include "core/error.hpp"

namespace fluidbed {

namespace case_sections {

void read_bubble(CaseReader& r, CaseConfig& c, const GasKeys& k) {
  using R = CaseReader;
  const bool needs_gas = c.model == Model::Tfm || c.gas_enabled;
  const double dx = k.dx;
  const std::size_t nj = k.jet_tables;
  GasConfig& g = c.gas;
  // [bubble]
  BubbleConfig& b = c.bubble;
  b.cells = {c.grid.nx, c.grid.ny, c.domain.dimension == 3 ? c.grid.nz : 0};
  b.eps_threshold = r.number("bubble.threshold", 0.8, "", "voidage above which a cell is bubble (the paper: 0.8)",
                             R::Range{0.0, 1.0, true, true});
  b.jet_x = r.number("bubble.jet_x", nj == 0 ? c.domain.width / 2 : g.boundary.jets[0].x_centre, "m",
                     "vertical line on which the nose is measured");
  b.jet_width = r.number("bubble.jet_width", nj == 0 ? dx : g.boundary.jets[0].width, "m",
                         "width of the jet the bubble grows from", R::positive());
  const bool u_mf_given = r.has("bubble.u_mf");
  const std::optional<double> u_ergun = bed_minimum_fluidisation_velocity(c);
  b.u_mf = r.number("bubble.u_mf", u_ergun.value_or(1.8), "m/s", "U_mf of the throughflow ratio (the paper: 1.8 "
                    "m/s); default: the Ergun U_mf of the bed (DEM: Sauter mean diameter of the species at eps_mf = "
                    "0.43; TFM: at tfm.eps_initial)", R::positive());
  r.describe_default("bubble.u_mf", "Ergun U_mf");
  if (!u_mf_given && (c.model == Model::Tfm || c.gas_enabled)) {
    c.notes.push_back(u_ergun ? fmt::format("bubble.u_mf not given: {:.4g} m/s, the {} of the bed", b.u_mf,
                                            bed_minimum_fluidisation_label(c))
                              : fmt::format("bubble.u_mf not given and the bed has no Ergun U_mf (no downward gravity): "
                                            "{} m/s", b.u_mf));
  }
  b.min_area = r.number("bubble.min_area", b.min_area, "m^2", "smallest void counted as a bubble", R::positive());
  b.surface_eps = r.number("bubble.surface_voidage", b.surface_eps, "", "voidage that marks the bed surface",
                           R::Range{0.0, 1.0, true, true});
  b.gravity = std::abs(c.domain.gravity.y);
  if (c.domain.dimension == 3) {
    // The tracked bubble grows on the first jet: its footprint on the bottom face, and the nose line through its
    // centre.
    b.min_volume = r.number("bubble.min_volume", b.min_volume, "m^3", "smallest void counted as a bubble (3D)",
                            R::positive());
    if (nj > 0) {
      const InletJet& j = g.boundary.jets[0];
      b.jet_shape = j.shape;
      if (j.shape != InletShape::Slot) b.jet_z = j.z_centre;
      b.jet_depth = j.depth;
    }
  } else if (r.has("bubble.min_volume")) {
    r.fail("bubble.min_volume", "a 2D case measures bubbles by area (bubble.min_area); set case.dimension = 3");
  }
  (void)needs_gas;
}

// [probes] and [[probe]]: the probes of issue 15 (analysis/probes.hpp, docs/analysis.md "Probes").
void read_probes(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  ProbesConfig& pc = c.probes;
  pc.interval = r.number("probes.interval", 0.001, "s",
                         "interval of probes.csv rows; 0: after every model step (gas step of CFD-DEM, TFM step)",
                         R::non_negative());
  const bool three_d = c.grid.dimension == 3;
  const std::size_t n = r.table_count("probe", "probes: points, horizontal lines/planes, pressure drops (probes.csv)");
  pc.probes.clear();
  for (std::size_t k = 0; k < n; ++k) {
    const std::string p = fmt::format("probe[{}].", k);
    ProbeSpec s;
    const std::string kind = r.string(p + "kind", "point", "point (fields at position), plane (the mean over the "
                                      "horizontal line, 3D plane, at height), pressure_drop (mean pressure at "
                                      "height minus at height_top), bed_height (the highest height where the "
                                      "cross-section mean solids fraction falls to solids_fraction) or particle_top "
                                      "(the percentile of the particles' tops: CFD-DEM)",
                                      {"point", "plane", "pressure_drop", "bed_height", "particle_top"});
    s.kind = kind == "plane"           ? ProbeKind::Plane
             : kind == "pressure_drop" ? ProbeKind::PressureDrop
             : kind == "bed_height"    ? ProbeKind::BedHeight
             : kind == "particle_top"  ? ProbeKind::ParticleTop
                                       : ProbeKind::Point;
    s.name = r.string(p + "name", fmt::format("probe{}", k), "column prefix in probes.csv");
    if (s.name.empty() || s.name.find_first_of(", \t\n\"") != std::string::npos)
      r.fail(p + "name", "a probe name is a column prefix: no commas, spaces or quotes");
    for (std::size_t q = 0; q < k; ++q)
      if (pc.probes[q].name == s.name) r.fail(p + "name", fmt::format("'{}' is also probe[{}]'s name", s.name, q));
    if (s.kind == ProbeKind::Point) {
      const std::size_t dims = three_d ? 3 : 2;
      const std::vector<double> x = r.numbers(p + "position", {}, "m", "x, y (3D: x, y, z) of a point probe", dims);
      for (std::size_t a = 0; a < x.size(); ++a) s.position[a] = x[a];
      const double extent[3] = {c.domain.width, c.domain.height, c.domain.depth};
      for (std::size_t a = 0; a < dims; ++a)
        if (!(x[a] >= 0.0 && x[a] <= extent[a])) r.fail(p + "position", "the point lies outside the domain");
    } else if (s.kind == ProbeKind::BedHeight) {
      s.solids_fraction = r.number(p + "solids_fraction", 0.3, "", "bed_height: the cross-section mean solids "
                                   "fraction 1 - eps that marks the bed surface (about half a packed bed's)",
                                   R::Range{0.0, 1.0, true, true});
    } else if (s.kind == ProbeKind::ParticleTop) {
      if (c.model == Model::Tfm) {
        r.fail(p + "kind", "particle_top reads the particles, and the two-fluid model has none: use bed_height");
      }
      s.percentile = r.number(p + "percentile", 99.0, "%", "particle_top: the percent of the particles' tops "
                              "(centre + radius) at or below the probe's height",
                              R::between(0.0, 100.0));
    } else {
      s.height = r.required_number(p + "height", "m", "height of a plane probe, lower tap of a pressure drop",
                                   R::between(0.0, c.domain.height));
      if (s.kind == ProbeKind::PressureDrop)
        s.height_top = r.required_number(p + "height_top", "m", "upper tap of a pressure drop",
                                         R::between(0.0, c.domain.height));
    }
    pc.probes.push_back(s);
  }
}

// [averages]: the window of the time-averaged fields (analysis/time_average.hpp, docs/analysis.md "Time averages").
void read_averages(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  AveragesConfig& a = c.averages;
  a.t_start = r.number("averages.t_start", 0.0, "s", "first sample of the time averages (averages.vti, .csv)",
                       R::non_negative());
  a.t_end = r.number("averages.t_end", 0.0, "s",
                     "last sample of the time averages; 0: no averages", R::non_negative());
  a.interval = r.number("averages.interval", 0.01, "s",
                        "interval of the samples; 0: after every model step (gas step of CFD-DEM, TFM step)",
                        R::non_negative());
  if (a.t_end != 0.0 && !(a.t_end > a.t_start))
    r.fail("averages.t_end", fmt::format("{} s is not after averages.t_start = {} s", a.t_end, a.t_start));
  a.enabled = a.t_end > a.t_start;
}

}  // namespace case_sections
}  // namespace fluidbed
