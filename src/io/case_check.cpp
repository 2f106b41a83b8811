#include "io/case_check.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "dem/contact_law.hpp"
#include "fluid/drag.hpp"
#include "io/case_loader.hpp"

namespace fluidbed {

std::string describe_case(const CaseConfig& c) {
  std::string s;
  auto line = [&s](const std::string& what, const std::string& value) { s += fmt::format("  {:<44} {}\n", what, value); };
  s += fmt::format("case '{}' ({}): {}\n", c.name, c.model == Model::Tfm ? "two-fluid model" : "discrete particles",
                   c.description);
  line("domain", fmt::format("{} x {} m", c.dem.width, c.dem.height));
  line("end time", fmt::format("{} s", c.run.end_time));
  if (c.model == Model::Dem) {
    const Species& sp = c.dem.species[0];
    const double m = sp.mass();
    const double k = c.dem.stiffness;
    const double t_cr = critical_time(m, k);
    const double m_eff = reduced_mass(m, m);
    const double e = c.dem.pair_params(0, 0).restitution;
    const double eta = damping_from_restitution(m_eff, k, e);
    const double t_c = contact_duration(m_eff, k, eta);
    line("particle mass (species 0)", fmt::format("{:.4g} kg (d = {} m, rho = {} kg/m^3)", m, sp.diameter, sp.density));
    line("t_cr = 2 pi sqrt(m/k) (Table 3 item 5)", fmt::format("{:.4g} s; dt / t_cr = {:.3f}", t_cr, c.dem.dt / t_cr));
    line("contact duration (pair, e)", fmt::format("{:.4g} s = {:.1f} time steps", t_c, t_c / c.dem.dt));
    line("damping eta (Eq. 8, pair reduced mass)", fmt::format("{:.4g} kg/s", eta));
    line("largest stable time step", fmt::format("{:.4g} s (dt = {:g} s)", dem_stable_time_step(c.dem), c.dem.dt));
    const double g = std::abs(c.dem.gravity.y);
    line("static overlap under its own weight", fmt::format("{:.3g} m = {:.2f}% of d", m * g / k, 100.0 * m * g / k / sp.diameter));
    const std::int64_t n = c.particles.packing.count;
    if (c.particles.source != ParticleSource::File) {
      // A random 2D packing of discs fills about 82% of the area (Berryman 1983).
      const double area = static_cast<double>(n) * std::numbers::pi * sp.diameter * sp.diameter / 4.0;
      line("particles", fmt::format("{} placed at random", n));
      line("estimated settled bed height", fmt::format("{:.3f} m (random disc packing, area fraction 0.82)",
                                                        area / 0.82 / c.dem.width));
    }
    const double rho_g = c.gas.rho_g, mu_g = c.gas.mu_g;
    line("terminal velocity in air (Eq. 14)", fmt::format("{:.3f} m/s", terminal_velocity(sp.diameter, sp.density, rho_g, mu_g, g)));
    line("Ergun U_mf at eps_mf = 0.43", fmt::format("{:.3f} m/s", ergun_minimum_fluidisation_velocity(0.43, sp.diameter, sp.density, rho_g, mu_g, g)));
    // The solver's data per particle (docs/performance.md, section 4) with E = 6 list entries (a packed bed):
    // store 152, last-rebuild positions and wall springs 80, list and its previous copy 2 x (8 + 20 E), per-entry
    // mirror, force and torque 28 E. The program and its libraries add about 25 MB.
    constexpr double entries = 6.0;
    const double bytes_per_particle = 152.0 + 80.0 + 2.0 * (8.0 + 20.0 * entries) + 28.0 * entries;
    line("memory estimate", fmt::format("{:.1f} MB for the particles (plus about 25 MB for the program)",
                                        static_cast<double>(n) * bytes_per_particle / 1e6));
  }
  if (c.model == Model::Tfm || c.gas_enabled) {
    line("gas grid", fmt::format("{} x {} cells of {} x {} m", c.grid.nx, c.grid.ny, c.grid.dx, c.grid.dy));
    if (c.model == Model::Dem) {
      line("gas time step", fmt::format("{:g} s ({} DEM steps)", c.dem.dt * c.coupling.dem_substeps, c.coupling.dem_substeps));
    }
    line("inlet (superficial)", fmt::format("{} m/s through the bottom", c.gas.boundary.inlet_velocity));
    for (const InletJet& j : c.gas.boundary.jets) {
      line("jet", fmt::format("{} m/s over [{}, {}] m for {} <= t < {} s", j.velocity, j.x_centre - 0.5 * j.width,
                              j.x_centre + 0.5 * j.width, j.t_start, j.t_end));
    }
  }
  if (c.model == Model::Tfm) {
    const tfm::TfmConfig& t = c.tfm;
    const double g = std::abs(t.gravity.y);
    line("solids", fmt::format("d = {} m, rho_s = {} kg/m^3, eps_initial = {}, eps* = {}", t.d_p, t.rho_s, t.eps_initial, t.eps_star));
    line("Ergun U_mf at eps_initial", fmt::format("{:.3f} m/s", ergun_minimum_fluidisation_velocity(t.eps_initial, t.d_p, t.rho_s, t.rho_g, t.mu_g, g)));
    line("terminal velocity (Eq. 14)", fmt::format("{:.3f} m/s", terminal_velocity(t.d_p, t.rho_s, t.rho_g, t.mu_g, g)));
    line("bed weight per area", fmt::format("{:.0f} Pa", (1.0 - t.eps_initial) * (t.rho_s - t.rho_g) * g * t.packed_height));
    line("memory estimate", fmt::format("{:.2f} MB", static_cast<double>(c.grid.cells()) * 40 * 8 / 1e6));
  }
  return s;
}

}  // namespace fluidbed
