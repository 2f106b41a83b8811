#include "io/case_check.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "core/error.hpp"
#include "dem/contact_law.hpp"
#include "dem/contact_model.hpp"
#include "fluid/drag.hpp"
#include "io/case_loader.hpp"
#include "io/csv.hpp"
#include "io/dem_model.hpp"

namespace fluidbed {

namespace {

// Eq. 8 on the contact's reduced mass: damping from restitution, then the damped half period.
double pair_contact_duration(double m_eff, double k, double e) {
  return contact_duration(m_eff, k, damping_from_restitution(m_eff, k, e));
}

std::string pair_name(int a, int b) {
  return b < 0 ? fmt::format("species {} with a wall", a) : fmt::format("species {} with species {}", a, b);
}

// A random 2D packing of discs fills about 82% of the area, a random close packing of spheres 64% of the volume
// (Berryman 1983).
constexpr double kDiscPackingFraction = 0.82;
constexpr double kSpherePackingFraction = 0.64;

// "0.6 x 1 m" in 2D, "0.6 x 1 x 0.1 m" in 3D (without the unit).
// A schedule in words, the region's velocity u0.
std::string schedule_text(const InletSchedule& s, double u0) {
  switch (s.kind) {
    case ScheduleKind::Constant:
      return fmt::format("{} m/s", u0);
    case ScheduleKind::Ramp:
      return fmt::format("{} m/s, ramped linearly from {} m/s over {} <= t < {} s", u0, s.ramp_from, s.ramp_start,
                         s.ramp_start + s.ramp_time);
    case ScheduleKind::Table:
      return fmt::format("a table of {} points from {} m/s at {} s to {} m/s at {} s, linear between", s.times.size(),
                         s.velocities.front(), s.times.front(), s.velocities.back(), s.times.back());
    case ScheduleKind::Sine:
      return fmt::format("{} + {} sin(2 pi {} t + {}) m/s", u0, s.amplitude, s.frequency, s.phase);
    case ScheduleKind::Square:
      return fmt::format("{} m/s, plus {} m/s over {:g}% of each {} s period (phase {} rad)", u0, s.amplitude,
                         100.0 * s.duty, 1.0 / s.frequency, s.phase);
  }
  return "";
}

std::string box_text(const DomainConfig& d) {
  return d.dimension == 3 ? fmt::format("{} x {} x {}", d.width, d.height, d.depth) : fmt::format("{} x {}", d.width, d.height);
}
std::string cell_text(const CaseGrid& g) {
  return g.dimension == 3 ? fmt::format("{} x {} x {}", g.dx, g.dy, g.dz) : fmt::format("{} x {}", g.dx, g.dy);
}

}  // namespace

EquivalentContact equivalent_contact(const DemConfig& dem, int a, int b) {
  // Each species by its smallest particle: the lightest, whose contacts are the shortest.
  const Species& spa = dem.species[static_cast<std::size_t>(a)];
  const Species sa = spa.of_diameter(spa.d_min());
  const bool wall = b < 0;
  const Species sb = wall ? sa : dem.species[static_cast<std::size_t>(b)].of_diameter(
                                     dem.species[static_cast<std::size_t>(b)].d_min());
  const double m_eff = wall ? sa.mass() : reduced_mass(sa.mass(), sb.mass());
  const double e = wall ? dem.wall[static_cast<std::size_t>(a)].restitution : dem.pair_params(a, b).restitution;
  const ContactModelConfig& m = dem.contact;
  if (m.normal == NormalModel::Linear) {
    const double k = dem.stiffness;
    const double k_t = m.tangential == TangentialModel::Linear ? k * dem.tangential_stiffness_ratio : 0.0;
    const double eta = damping_from_restitution(m_eff, k, e);
    EquivalentContact c{m_eff, k, k_t, eta, pair_contact_duration(m_eff, k, e)};
    if (m.tangential == TangentialModel::Mindlin) {
      // Mindlin's k_t at the linear spring's largest overlap of the impact
      const double r_eff = wall ? sa.radius() : sa.radius() * sb.radius() / (sa.radius() + sb.radius());
      const ElasticMaterial& mb = wall ? m.wall_material : dem.material_of(static_cast<std::size_t>(b));
      const double g = effective_shear_modulus(dem.material_of(static_cast<std::size_t>(a)), mb);
      c.k_t = 8.0 * g * std::sqrt(r_eff * m.impact_speed * std::sqrt(m_eff / k));
    }
    return c;
  }
  const double r_eff = wall ? sa.radius() : sa.radius() * sb.radius() / (sa.radius() + sb.radius());
  const ElasticMaterial& ma = dem.material_of(static_cast<std::size_t>(a));
  const ElasticMaterial& mb = wall ? m.wall_material : dem.material_of(static_cast<std::size_t>(b));
  const double e_star = effective_youngs_modulus(ma, mb);
  const HertzImpact h = hertz_impact(m_eff, e_star, r_eff, m.impact_speed);
  const double a_max = std::sqrt(r_eff * h.max_overlap);
  const double k_n = 2.0 * e_star * a_max;
  const double k_t = m.tangential == TangentialModel::Mindlin ? 8.0 * effective_shear_modulus(ma, mb) * a_max
                                                              : k_n * dem.tangential_stiffness_ratio;
  return {m_eff, k_n, k_t, tsuji_alpha_for_hertz(e) * std::sqrt(m_eff * k_n), h.duration};
}

StiffestContact stiffest_contact(const DemConfig& dem) {
  StiffestContact out{1e300, 0, -1};
  for (std::size_t a = 0; a < dem.n_species(); ++a) {
    for (std::size_t b = a; b < dem.n_species(); ++b) {
      const double t = equivalent_contact(dem, static_cast<int>(a), static_cast<int>(b)).t_c;
      if (t < out.t_c) out = {t, static_cast<int>(a), static_cast<int>(b)};
    }
    const double t = equivalent_contact(dem, static_cast<int>(a), -1).t_c;
    if (t < out.t_c) out = {t, static_cast<int>(a), -1};
  }
  return out;
}

double default_dem_time_step(const DemConfig& dem) {
  const double target = std::min(stiffest_contact(dem).t_c / kStepsPerContact, dem_stable_time_step(dem));
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  double dt = decade;
  for (double m : {1.25, 2.0, 2.5, 4.0, 5.0, 8.0}) {
    if (m * decade <= target) dt = m * decade;
  }
  return dt;
}

BedMixture bed_mixture(const DemConfig& dem, const std::vector<double>& fraction) {
  double s2 = 0.0, s3 = 0.0, m3 = 0.0;
  for (std::size_t s = 0; s < dem.n_species(); ++s) {
    const double f = s < fraction.size() ? fraction[s] : 0.0;
    if (dem.species[s].sized()) {
      // The species' own number moments <d^2>, <d^3>.
      const SizeMoments m = size_moments(dem.species[s].size);
      s2 += f * m.m2;
      s3 += f * m.m3;
      m3 += f * m.m3 * dem.species[s].density;
      continue;
    }
    const double d = dem.species[s].diameter;
    s2 += f * d * d;
    s3 += f * d * d * d;
    m3 += f * d * d * d * dem.species[s].density;
  }
  if (!(s2 > 0.0)) return {dem.species[0].diameter, dem.species[0].density};
  return {s3 / s2, m3 / s3};
}

std::string bed_minimum_fluidisation_label(const CaseConfig& c) {
  if (c.coupling.drag_law == DragLaw::ErgunWenYu && c.coupling.drag_switch == DragSwitch::Sharp) return "Ergun U_mf";
  return "U_mf of the case's drag law";
}

std::optional<double> bed_minimum_fluidisation_velocity(const CaseConfig& c) {
  const double g = -c.domain.gravity.y;
  double eps = kDemEpsMf, d = 0.0, rho = 0.0;
  if (c.model == Model::Tfm) {
    eps = c.tfm.eps_initial;
    d = c.tfm.d_p;
    rho = c.tfm.rho_s;
  } else {
    const BedMixture mix = bed_mixture(c.dem, c.particles.packing.species_fraction);
    d = mix.d32;
    rho = mix.rho;
  }
  if (!(g > 0.0 && eps > 0.0 && eps < 1.0 && d > 0.0 && rho > c.gas.rho_g && c.gas.rho_g > 0.0 && c.gas.mu_g > 0.0)) {
    return std::nullopt;
  }
  // The paper's law is Ergun below eps = 0.8: its closed form. Any other law (or the smooth blend): the U at which
  // that law's fixed-bed pressure gradient carries the bed (drag.hpp), so check and the U_th/U_mf ratio use the
  // drag the run will use.
  const DragModel model{c.coupling.drag_law, c.coupling.drag_switch};
  if (model.law == DragLaw::ErgunWenYu && model.blend == DragSwitch::Sharp) {
    return ergun_minimum_fluidisation_velocity(eps, d, rho, c.gas.rho_g, c.gas.mu_g, g);
  }
  return minimum_fluidisation_velocity(model, eps, d, rho, c.gas.rho_g, c.gas.mu_g, g);
}

void check_domain_plausible(const CaseReader& r, const DomainConfig& domain) {
  // Industrial beds are some 10 m across; the largest benchmark case here is 27 m wide.
  for (const auto& [key, v] : {std::pair{"domain.width", domain.width}, std::pair{"domain.height", domain.height},
                               std::pair{"domain.depth", domain.dimension == 3 ? domain.depth : 0.0}}) {
    if (v > 100.0) {
      r.fail(key, fmt::format("{} m is larger than any fluidised bed (industrial ones are some 10 m){}", v,
                              v * 1e-3 <= 100.0 ? fmt::format(": a size in millimetres? {} mm is {:g} m", v, v * 1e-3)
                                                : std::string()));
    }
  }
}

void check_particle_plausible(const CaseReader& r, const std::string& diameter_key, double d,
                              const std::string& density_key, double rho, const DomainConfig& domain,
                              const std::optional<CaseGrid>& cell) {
  if (d < 1e-7) {
    r.fail(diameter_key, fmt::format("{} m is smaller than any particle a bed is fluidised with (the finest powders are "
                                     "some 1e-6 m): the diameter is in metres", d));
  }
  const bool three_d = domain.dimension == 3;
  const double smallest = three_d ? std::min({domain.width, domain.height, domain.depth})
                                  : std::min(domain.width, domain.height);
  if (d > smallest) {
    r.fail(diameter_key, fmt::format("a particle of {} m is larger than the domain ({} m){}", d, box_text(domain),
                                     d * 1e-3 <= smallest
                                         ? fmt::format(": a diameter in millimetres? {} mm is {:g} m", d, d * 1e-3)
                                         : std::string()));
  }
  if (cell && d > (three_d ? std::min({cell->dx, cell->dy, cell->dz}) : std::min(cell->dx, cell->dy))) {
    r.fail(diameter_key, fmt::format("a particle of {} m is larger than a gas cell ({} m): the gas sees the "
                                     "solids averaged over a cell, so a cell must be wider than a particle; a coarser "
                                     "grid (grid.cell_width{}) or a smaller diameter", d, cell_text(*cell),
                                     three_d ? ", grid.cell_depth" : ""));
  }
  // The lightest particles fluidised are foams of some 10-100 kg/m^3; gases are below 10 kg/m^3 at the pressures
  // of a fluidised bed; no solid is denser than osmium.
  if (rho < 10.0) {
    r.fail(density_key, fmt::format("{} kg/m^3 is the density of a gas, not of a solid (air: 1.2 kg/m^3, glass: "
                                    "2500 kg/m^3): in g/cm^3? {} g/cm^3 is {:g} kg/m^3", rho, rho, rho * 1e3));
  }
  if (rho > 25000.0) {
    r.fail(density_key, fmt::format("{} kg/m^3 is denser than any solid (osmium, the densest: 22,590 kg/m^3): in "
                                    "g/m^3? {} g/m^3 is {:g} kg/m^3", rho, rho, rho * 1e-3));
  }
}

void check_gas_plausible(const CaseReader& r, const GasConfig& g, std::vector<std::string>& notes) {
  // Gases a bed is fluidised with: hydrogen at 0.08 kg/m^3 to pressurised gases of some 100 kg/m^3; liquids to
  // about 2000 kg/m^3. Viscosities: gases 9e-6 (hydrogen) to 5e-5 Pa s, liquids 3e-4 to 10 Pa s (honey).
  if (g.rho_g < 0.01) {
    r.fail("gas.density", fmt::format("{} kg/m^3 is thinner than any gas a bed is fluidised with (air: 1.205 "
                                      "kg/m^3): in g/cm^3? {} g/cm^3 is {:g} kg/m^3", g.rho_g, g.rho_g, g.rho_g * 1e3));
  }
  if (g.rho_g > 2000.0) {
    r.fail("gas.density", fmt::format("{} kg/m^3 is denser than a gas or a common liquid (air: 1.205, water: 1000 "
                                      "kg/m^3): in g/m^3? {} g/m^3 is {:g} kg/m^3", g.rho_g, g.rho_g, g.rho_g * 1e-3));
  }
  if (g.rho_g > 100.0) {
    notes.push_back(fmt::format("gas.density = {} kg/m^3 is the density of a liquid, not of a gas (air: 1.205 "
                                "kg/m^3); the drag laws hold for both, but check the unit", g.rho_g));
  }
  if (g.mu_g < 1e-6) {
    r.fail("gas.viscosity", fmt::format("{} Pa s is below the viscosity of any gas (hydrogen: 8.9e-6, air: 1.8e-5 "
                                        "Pa s)", g.mu_g));
  }
  if (g.mu_g > 10.0) {
    r.fail("gas.viscosity", fmt::format("{} Pa s is above the viscosity of any gas or common liquid (air: 1.8e-5, "
                                        "water: 1e-3 Pa s): in micropascal seconds? {} uPa s is {:g} Pa s",
                                        g.mu_g, g.mu_g, g.mu_g * 1e-6));
  }
  if (g.mu_g > 1e-4) {
    notes.push_back(fmt::format("gas.viscosity = {} Pa s is the viscosity of a liquid, not of a gas (air: 1.8e-5 "
                                "Pa s): in mPa s (cP)? {} mPa s is {:g} Pa s", g.mu_g, g.mu_g, g.mu_g * 1e-3));
  }
}

std::vector<SpeciesSizes> species_sizes(const CaseConfig& c) {
  const DemConfig& dem = c.dem;
  std::vector<SpeciesSizes> out(dem.n_species());
  if (c.particles.source == ParticleSource::File) {
    // The bed is the file's: its particles as they are.
    const auto rows = read_particles_csv(case_relative_path(c.source_path, c.particles.file), c.domain.dimension);
    std::vector<double> s1(out.size(), 0.0), s2(out.size(), 0.0), s3(out.size(), 0.0);
    for (SpeciesSizes& z : out) {
      z.from_file = true;
      z.d_min = 1e300;
      z.d_max = 0.0;
    }
    for (const ParticleCsvRow& row : rows) {
      const auto a = static_cast<std::size_t>(row.species);
      if (a >= out.size()) continue;
      const double d = row.diameter > 0.0 ? row.diameter : dem.species[a].diameter;
      SpeciesSizes& z = out[a];
      ++z.count;
      s1[a] += d;
      s2[a] += d * d;
      s3[a] += d * d * d;
      z.d_min = std::min(z.d_min, d);
      z.d_max = std::max(z.d_max, d);
    }
    for (std::size_t a = 0; a < out.size(); ++a) {
      SpeciesSizes& z = out[a];
      z.what = z.d_min < z.d_max ? "sizes of the file" : "one size";
      if (z.count == 0) {
        z.d_min = z.d_max = z.mean = z.d32 = dem.species[a].diameter;
        continue;
      }
      z.mean = s1[a] / static_cast<double>(z.count);
      z.d32 = s3[a] / s2[a];
    }
    return out;
  }
  // Random placement: the counts it places (species by cumulative fraction, as place_random assigns them) and the
  // requested distribution's moments.
  const std::vector<double>& frac = c.particles.packing.species_fraction;
  const std::int64_t n = c.particles.packing.count;
  double acc = 0.0;
  std::int64_t placed = 0;
  for (std::size_t a = 0; a < out.size(); ++a) {
    acc += a < frac.size() ? frac[a] : (a == 0 ? 1.0 : 0.0);
    const std::int64_t end = a + 1 == out.size() ? n : std::min<std::int64_t>(n, std::llround(acc * static_cast<double>(n)));
    SpeciesSizes& z = out[a];
    z.count = static_cast<std::size_t>(std::max<std::int64_t>(0, end - placed));
    placed = std::max(placed, end);
    const Species& sp = dem.species[a];
    const SizeMoments m = size_moments(sp.distribution());
    z.what = sp.sized() ? std::string(size_law_name(sp.size.law)) + " (requested)" : "fixed";
    z.mean = m.m1;
    z.d32 = sp.sized() ? m.d32() : sp.diameter;
    z.d_min = sp.d_min();
    z.d_max = sp.d_max();
  }
  return out;
}

std::string describe_case(const CaseConfig& c) {
  std::string s;
  auto line = [&s](const std::string& what, const std::string& value) { s += fmt::format("  {:<44} {}\n", what, value); };
  s += fmt::format("case '{}' ({}): {}\n", c.name, c.model == Model::Tfm ? "two-fluid model" : "discrete particles",
                   c.description);
  for (const std::string& n : c.notes) s += fmt::format("  note: {}\n", n);
  const bool three_d = c.domain.dimension == 3;
  if (three_d) {
    line("domain", fmt::format("{} x {} x {} m (width x height x depth, {}), gravity ({}, {}, {}) "
                               "m/s^2", c.domain.width, c.domain.height, c.domain.depth,
                               c.domain.periodic[2] ? "periodic in z" : "front and back walls", c.domain.gravity.x,
                               c.domain.gravity.y, c.domain.gravity.z));
  } else {
    line("domain", fmt::format("{} x {} m, gravity ({}, {}) m/s^2", c.domain.width, c.domain.height, c.domain.gravity.x,
                               c.domain.gravity.y));
  }
  line("end time", fmt::format("{} s", c.run.end_time));
  const double g = std::abs(c.domain.gravity.y);
  const double rho_g = c.gas.rho_g, mu_g = c.gas.mu_g;
  const bool sinks = g > 0.0;
  if (c.model == Model::Dem) {
    const DemConfig& dem = c.dem;
    const double k = dem.stiffness;
    const std::vector<double>& frac = c.particles.packing.species_fraction;
    const std::int64_t n = c.particles.packing.count;
    double bed_mass = 0.0, bed_area = 0.0;
    const std::vector<SpeciesSizes> sizes = species_sizes(c);
    for (std::size_t a = 0; a < dem.n_species(); ++a) {
      const Species& sp = dem.species[a];
      const double f = a < frac.size() ? frac[a] : 0.0;
      if (sp.sized()) {
        const SizeMoments m = size_moments(sp.size);
        bed_mass += static_cast<double>(n) * f * sp.density * std::numbers::pi * m.m3 / 6.0;
        bed_area += static_cast<double>(n) * f * (three_d ? std::numbers::pi * m.m3 / 6.0 : std::numbers::pi * m.m2 / 4.0);
      } else {
        bed_mass += static_cast<double>(n) * f * sp.mass();
        bed_area += static_cast<double>(n) * f *
                    (three_d ? std::numbers::pi * sp.diameter * sp.diameter * sp.diameter / 6.0
                             : std::numbers::pi * sp.diameter * sp.diameter / 4.0);
      }
      std::string v = fmt::format("d = {} m, rho = {} kg/m^3, mass {:.4g} kg, {:.3g}% by number", sp.diameter,
                                  sp.density, sp.mass(), 100.0 * f);
      if (sinks && sp.density > rho_g) {
        v += fmt::format("; u_t = {:.3f} m/s (Eq. 14), U_mf alone {:.3f} m/s", terminal_velocity(sp.diameter, sp.density, rho_g, mu_g, g),
                         ergun_minimum_fluidisation_velocity(kDemEpsMf, sp.diameter, sp.density, rho_g, mu_g, g));
      }
      line(fmt::format("species {}", a), v);
      const SpeciesSizes& z = sizes[a];
      line(fmt::format("species {} sizes", a),
           fmt::format("{}: {} particles{}, mean d = {:.4g} m, d32 = {:.4g} m, min {:.4g} m, max {:.4g} m",
                       z.what, z.count, z.from_file ? " in the file" : "", z.mean, z.d32, z.d_min, z.d_max));
    }
    double m_light = 1e300;  // the lightest particle any species places
    for (const Species& sp : dem.species) m_light = std::min(m_light, sp.of_diameter(sp.d_min()).mass());
    const ContactModelConfig& law = dem.contact;
    line("contact law", fmt::format("normal {}, damping {}, tangential {}, rolling {}", to_string(law.normal),
                                    to_string(law.damping), to_string(law.tangential), to_string(law.rolling)));
    if (law.normal == NormalModel::Hertz) {
      // Hertz contacts: duration and largest overlap of an impact at contact.impact_speed (Johnson 1985).
      for (std::size_t a = 0; a < dem.n_species(); ++a) {
        for (const int b : {static_cast<int>(a), -1}) {
          const EquivalentContact ec = equivalent_contact(dem, static_cast<int>(a), b);
          const double e_star = effective_youngs_modulus(
              dem.material_of(a), b < 0 ? law.wall_material : dem.material_of(static_cast<std::size_t>(b)));
          const double r_eff = dem.species[a].radius() * (b < 0 ? 1.0 : 0.5);
          const double d_max = ec.k_n * ec.k_n / (4.0 * e_star * e_star * r_eff);  // a_max = k_n / (2 E*)
          line(fmt::format("Hertz contact {}-{}", a, b < 0 ? std::string("wall") : fmt::format("{}", b)),
               fmt::format("at {:g} m/s: t_c = {:.4g} s = {:.1f} time steps, largest overlap {:.3g}% of d, tangent "
                           "stiffness {:.4g} N/m", law.impact_speed, ec.t_c, ec.t_c / dem.dt,
                           100.0 * d_max / dem.species[a].diameter, ec.k_n));
        }
      }
    }
    const double t_cr = critical_time(m_light, k);
    line("t_cr = 2 pi sqrt(m/k) (Table 3 item 5)",
         fmt::format("{:.4g} s for the lightest species; dt / t_cr = {:.3f}", t_cr, dem.dt / t_cr));
    // Every kind of contact: its duration in time steps says whether dt resolves it (the Hertz lines above).
    if (law.normal == NormalModel::Linear) {
      for (std::size_t a = 0; a < dem.n_species(); ++a) {
        for (std::size_t b = a; b < dem.n_species(); ++b) {
          const double m_eff = reduced_mass(dem.species[a].mass(), dem.species[b].mass());
          const double e = dem.pair_params(static_cast<int>(a), static_cast<int>(b)).restitution;
          const double t_c = pair_contact_duration(m_eff, k, e);
          line(fmt::format("contact duration {}-{} (e = {})", a, b, e),
               fmt::format("{:.4g} s = {:.1f} time steps; damping eta {:.4g} kg/s (Eq. 8)", t_c, t_c / dem.dt,
                           damping_from_restitution(m_eff, k, e)));
        }
        const double e = dem.wall[a].restitution;
        const double t_c = pair_contact_duration(dem.species[a].mass(), k, e);
        line(fmt::format("contact duration {}-wall (e = {})", a, e), fmt::format("{:.4g} s = {:.1f} time steps", t_c, t_c / dem.dt));
      }
    }
    const StiffestContact sc = stiffest_contact(dem);
    line("DEM time step", fmt::format("{:g} s = t_c / {:.1f} of the stiffest contact ({}); largest stable {:.4g} s",
                                      dem.dt, sc.t_c / dem.dt, pair_name(sc.a, sc.b), dem_stable_time_step(dem)));
    // Overlaps the spring allows, and the stiffness for a target overlap: the static load at the bottom of the
    // bed (the column above a particle's width: delta / d = M g / (W k), the same for every species) and a
    // head-on impact (delta = v sqrt(m_eff / k), the undamped spring's amplitude).
    constexpr double target = 0.01;
    // In 3D the column above a particle's cross-section d^2 of the floor W D: delta / d = M g d / (W D k).
    const double static_fraction = three_d ? bed_mass * g * dem.species[0].diameter / (c.domain.width * c.domain.depth * k)
                                           : bed_mass * g / (c.domain.width * k);
    const auto dt_at = [&](double k_new) {
      DemConfig d2 = dem;
      d2.stiffness = k_new;
      return default_dem_time_step(d2);
    };
    if (sinks) {
      const double k_static = static_fraction * k / target;
      line("mean overlap under the bed's weight", fmt::format("{:.3g}% of d at the bottom (force chains carry several "
                                                              "times the mean)", 100.0 * static_fraction));
      line("stiffness for a 1% mean static overlap", fmt::format("k = {:.3g} N/m (default dt there {:g} s)", k_static, dt_at(k_static)));
    }
    const bool gas = c.gas_enabled;
    const double v_impact = gas ? std::abs(c.gas.boundary.inlet_velocity) : std::sqrt(2.0 * g * c.particles.packing.y_max);
    if (v_impact > 0.0) {
      double worst = 0.0, k_impact = 0.0;
      for (std::size_t a = 0; a < dem.n_species(); ++a) {
        for (std::size_t b = a; b < dem.n_species(); ++b) {
          const double m_eff = reduced_mass(dem.species[a].mass(), dem.species[b].mass());
          const double dmin = std::min(dem.species[a].diameter, dem.species[b].diameter);
          worst = std::max(worst, v_impact * std::sqrt(m_eff / k) / dmin);
          k_impact = std::max(k_impact, m_eff * std::pow(v_impact / (target * dmin), 2));
        }
        const double m = dem.species[a].mass(), d = dem.species[a].diameter;  // on a wall: the whole mass
        worst = std::max(worst, v_impact * std::sqrt(m / k) / d);
        k_impact = std::max(k_impact, m * std::pow(v_impact / (target * d), 2));
      }
      const std::string at = gas ? fmt::format("at the inlet velocity {} m/s", v_impact)
                                 : fmt::format("at {:.2f} m/s (free fall from the fill height)", v_impact);
      line("overlap of a head-on impact", fmt::format("{:.3g}% of d {}", 100.0 * worst, at));
      line("stiffness for a 1% impact overlap", fmt::format("k = {:.3g} N/m (default dt there {:g} s)", k_impact, dt_at(k_impact)));
    }
    line("particles", c.particles.source == ParticleSource::File ? fmt::format("{} read from {}", n, c.particles.file)
                                                                 : fmt::format("{} placed at random", n));
    if (three_d) {
      line("estimated settled bed height", fmt::format("{:.3f} m from every species' volume (random close packing, "
                                                        "volume fraction {})", bed_area / kSpherePackingFraction /
                                                        (c.domain.width * c.domain.depth), kSpherePackingFraction));
    } else {
      line("estimated settled bed height", fmt::format("{:.3f} m from every species' area (random disc packing, area "
                                                        "fraction {})", bed_area / kDiscPackingFraction / c.domain.width,
                                                        kDiscPackingFraction));
    }
    if (dem.n_species() > 1) {
      const BedMixture mix = bed_mixture(dem, frac);
      line("mixture", fmt::format("Sauter mean diameter d32 = {:.4g} m, volume-mean density {:.4g} kg/m^3", mix.d32, mix.rho));
    }
    if (const auto u = bed_minimum_fluidisation_velocity(c)) {
      line(fmt::format("{} at eps_mf = {}", bed_minimum_fluidisation_label(c), kDemEpsMf),
           fmt::format("{:.3f} m/s{}", *u, dem.n_species() > 1 ? " (the mixture's d32 and density)" : ""));
    }
    // The solver's data per particle (docs/performance.md, section 4) with E = 6 list entries (a packed bed):
    // store 152, last-rebuild positions and wall springs 80, list and its previous copy 2 x (8 + 20 E), per-entry
    // mirror, force and torque 28 E. The program and its libraries add about 25 MB.
    constexpr double entries = 6.0;
    const double bytes_per_particle = 152.0 + 80.0 + 2.0 * (8.0 + 20.0 * entries) + 28.0 * entries;
    line("memory estimate", fmt::format("{:.1f} MB for the particles (plus about 25 MB for the program)",
                                        static_cast<double>(n) * bytes_per_particle / 1e6));
  }
  if (c.model == Model::Dem) {
    line("top of the domain (particles)", c.dem.walls.top ? "wall"
                                          : c.dem.walls.top_outflow ? "outflow: leaving particles are removed and counted"
                                                                    : "open: a particle crossing it fails the run");
    if (three_d && !c.domain.periodic[2]) {
      line("front and back (particles)", c.dem.walls.outflow(4) || c.dem.walls.outflow(5)
                                             ? "walls, except the outflow sides of domain.particle_outflow"
                                             : "walls (z = 0 and z = domain.depth)");
    }
    if (c.domain.any_periodic()) {
      line("periodic axes", fmt::format("{}{}: particles leaving one side re-enter at the other, contacts through "
                                        "the nearest image", c.domain.periodic[0] ? "x" : "",
                                        c.domain.periodic[2] ? (c.domain.periodic[0] ? " and z" : "z") : ""));
    }
    std::string out;
    const char* side_names[6] = {"left", "right", "bottom", "top", "back", "front"};
    for (int w = 0; w < (three_d ? 6 : 4); ++w) {
      if (w != 3 && c.dem.walls.outflow(w)) out += (out.empty() ? "" : ", ") + std::string(side_names[w]);
    }
    if (!out.empty()) line("outflow sides (particles)", out + ": leaving particles are removed and counted");
    if (c.dem.insertion.enabled()) {
      const InsertionConfig& in = c.dem.insertion;
      const double m = c.dem.species[static_cast<std::size_t>(in.species)].mass();
      line("particle feed", fmt::format("{:.6g} particles/s ({:.6g} kg/s) of species {} from t = {} s{}, seed {}",
                                        in.rate, in.rate * m, in.species, in.t_start,
                                        std::isfinite(in.t_end) ? fmt::format(" to {} s", in.t_end) : std::string(),
                                        in.seed));
    }
  }
  if (c.model == Model::Tfm || c.gas_enabled) {
    if (three_d) {
      line("gas grid", fmt::format("{} x {} x {} cells of {:.6g} x {:.6g} x {:.6g} m", c.grid.nx, c.grid.ny, c.grid.nz, c.grid.dx,
                                   c.grid.dy, c.grid.dz));
    } else {
      line("gas grid", fmt::format("{} x {} cells of {} x {} m", c.grid.nx, c.grid.ny, c.grid.dx, c.grid.dy));
    }
    if (c.model == Model::Dem) {
      line("gas time step", fmt::format("{:g} s ({} DEM steps)", c.dem.dt * c.coupling.dem_substeps, c.coupling.dem_substeps));
    }
    const GasBoundaryConfig& bc = c.gas.boundary;
    line("inlet (superficial)",
         bc.schedule.kind != ScheduleKind::Constant
             ? schedule_text(bc.schedule, bc.inlet_velocity) + " through the bottom"
         : bc.ramp_time > 0.0 ? fmt::format("{} m/s through the bottom, ramped from {} m/s over 0 <= t < {} s",
                                          bc.inlet_velocity, bc.ramp_from, bc.ramp_time)
                            : fmt::format("{} m/s through the bottom", bc.inlet_velocity));
    if (bc.inlet_noise > 0.0) {
      line("distributor non-uniformity", fmt::format("+-{:g}% per bottom cell, fixed in time (seed {}), total inflow "
                                                     "unchanged", 100.0 * bc.inlet_noise, bc.noise_seed));
    }
    double open_area = 0.0;
    for (const InletJet& j : c.gas.boundary.jets) {
      open_area += j.shape == InletShape::Disc      ? std::numbers::pi * 0.25 * j.width * j.width
                   : j.shape == InletShape::Rectangle ? j.width * j.depth
                                                      : j.width * (three_d ? c.domain.depth : 1.0);
    }
    const std::size_t n_jets = c.gas.boundary.jets.size();
    if (n_jets > 8) {
      line("jets and plate holes", fmt::format("{} regions, open area {:.6g} {} ({:.4g}% of the bottom); the first "
                                               "four:", n_jets, open_area, three_d ? "m^2" : "m per metre of depth",
                                               100.0 * open_area / (c.domain.width * (three_d ? c.domain.depth : 1.0))));
    }
    for (std::size_t k = 0; k < n_jets && (n_jets <= 8 || k < 4); ++k) {
      const InletJet& j = c.gas.boundary.jets[k];
      std::string where = fmt::format("[{}, {}] m", j.x_centre - 0.5 * j.width, j.x_centre + 0.5 * j.width);
      if (three_d) {
        where = j.shape == InletShape::Disc
                    ? fmt::format("a disc of diameter {} m centred at (x, z) = ({}, {}) m", j.width, j.x_centre, j.z_centre)
                : j.shape == InletShape::Rectangle
                    ? fmt::format("a rectangle x in {}, z in [{}, {}] m", where, j.z_centre - 0.5 * j.depth,
                                  j.z_centre + 0.5 * j.depth)
                    : fmt::format("a slot x in {} across the whole depth", where);
      }
      // A plate's default end (1e9 s) reads as "from t_start on".
      const std::string when = j.t_end >= 1e9 ? fmt::format("from t = {} s on", j.t_start)
                                              : fmt::format("for {} <= t < {} s", j.t_start, j.t_end);
      line("jet", fmt::format("{} over {} {}", schedule_text(j.schedule, j.velocity), where, when));
    }
    line("U_mf of the throughflow ratio (bubble.u_mf)", fmt::format("{:.3f} m/s", c.bubble.u_mf));
  }
  if (c.model == Model::Tfm) {
    const tfm::TfmConfig& t = c.tfm;
    line("solids", fmt::format("d = {} m, rho_s = {} kg/m^3, eps_initial = {}, eps* = {}", t.d_p, t.rho_s, t.eps_initial, t.eps_star));
    if (const auto u = bed_minimum_fluidisation_velocity(c)) line(bed_minimum_fluidisation_label(c) + " at eps_initial", fmt::format("{:.3f} m/s", *u));
    if (sinks) line("terminal velocity (Eq. 14)", fmt::format("{:.3f} m/s", terminal_velocity(t.d_p, t.rho_s, t.rho_g, t.mu_g, g)));
    line("bed weight per area", fmt::format("{:.0f} Pa", (1.0 - t.eps_initial) * (t.rho_s - t.rho_g) * g * t.packed_height));
    line("memory estimate", fmt::format("{:.2f} MB", static_cast<double>(c.grid.cells()) * 40 * 8 / 1e6));
  }
  if (c.averages.enabled) {
    const AveragesConfig& a = c.averages;
    line("time averages ([averages])",
         a.interval > 0.0 ? fmt::format("{} to {} s, a sample every {} s ({:.0f} samples)", a.t_start, a.t_end,
                                        a.interval, std::floor((a.t_end - a.t_start) / a.interval + 1e-9) + 1)
                          : fmt::format("{} to {} s, a sample after every model step", a.t_start, a.t_end));
  }
  return s;
}

}  // namespace fluidbed
