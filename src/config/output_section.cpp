// [output]: what a run writes and when, into CaseConfig::output (OutputConfig, config/case_config.hpp).
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

void read_output(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  c.output.interval = r.number("output.interval", 0.01, "s",
                               "interval of field frames, tracers and bubble samples (particle frames: "
                               "output.particle_interval)", R::positive());
  // Particle frames are a subset of the field frames (same frame numbers and instants), so a restart resumes them
  // from the frame counter alone.
  c.output.particle_interval = r.number("output.particle_interval", c.output.interval, "s",
                                        "interval of particle frames (particles/*.vtu and *.csv, DEM): a whole "
                                        "multiple of output.interval", R::positive());
  r.describe_default("output.particle_interval", "output.interval");
  const double every = c.output.particle_interval / c.output.interval;
  if (std::abs(every - std::round(every)) > 1e-9 * every || std::round(every) < 1.0) {
    const double lo = std::max(1.0, std::floor(every)), hi = std::max(lo + 1.0, std::ceil(every));
    r.fail("output.particle_interval",
           fmt::format("{} s is not a whole multiple of output.interval = {} s (particle frames are written with "
                       "field frames); choose {:.6g} s or {:.6g} s, or lower output.interval",
                       c.output.particle_interval, c.output.interval, lo * c.output.interval, hi * c.output.interval));
  }
  c.output.monitor_interval = r.number("output.monitor_interval", 0.001, "s", "interval of monitor.csv rows", R::positive());
  c.output.checkpoint_interval = r.number("output.checkpoint_interval", 0.25, "s",
                                          "interval of HDF5 checkpoints (one is always written at the end); 0 = end only",
                                          R::non_negative());
  c.output.checkpoint_keep = static_cast<int>(r.integer(
      "output.checkpoint_keep", 3, "periodic checkpoints kept, the newest ones (an older one is deleted only after a "
      "newer one is complete)", R::between(1, 1000000)));
  c.output.fields = r.boolean("output.fields", true, "write fields.pvd and fields/*.vti");
  c.output.particles = r.boolean("output.particles", true, "write particles.pvd and particles/*.vtu (DEM)");
  c.output.particles_csv = r.boolean("output.particles_csv", false, "also write particles/*.csv at full precision (DEM)");
  c.output.tracers = r.boolean("output.tracers", true, "write the layer tracers (tracers/*.csv)");
}

}  // namespace case_sections
}  // namespace fluidbed
