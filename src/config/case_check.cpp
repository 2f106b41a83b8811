#include "config/case_check.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "core/error.hpp"
#include "dem/contact_law.hpp"
#include "dem/contact_model.hpp"
#include "closures/drag.hpp"
#include "fluid/gas_boundary.hpp"
#include "config/case_loader.hpp"
#include "io/csv.hpp"
#include "config/settle_record.hpp"

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
      return fmt::format("{:.6g} m/s", u0);
    case ScheduleKind::Ramp:
      return fmt::format("{:.6g} m/s, ramped linearly from {:.6g} m/s over {:.6g} <= t < {:.6g} s", u0, s.ramp_from, s.ramp_start,
                         s.ramp_start + s.ramp_time);
    case ScheduleKind::Table:
      return fmt::format("a table of {} points from {:.6g} m/s at {:.6g} s to {:.6g} m/s at {:.6g} s, linear between", s.times.size(),
                         s.velocities.front(), s.times.front(), s.velocities.back(), s.times.back());
    case ScheduleKind::Sine:
      return fmt::format("{:.6g} + {:.6g} sin(2 pi {:.6g} t + {:.6g}) m/s", u0, s.amplitude, s.frequency, s.phase);
    case ScheduleKind::Square:
      return fmt::format("{:.6g} m/s, plus {:.6g} m/s over {:g}% of each {:.6g} s period (phase {:.6g} rad)", u0, s.amplitude,
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

// Species a against species b (b < 0: a wall) as a contact sees them: reduced mass, radius and modulus, the smaller
// diameter (overlaps are measured against it) and both materials; each species by its smallest particle (the
// lightest, whose contacts are the shortest) or by its nominal diameter.
struct ContactPair {
  double m_eff, r_eff, e_star, d_small;
  const ElasticMaterial* ma;
  const ElasticMaterial* mb;
};
ContactPair contact_pair(const DemConfig& dem, int a, int b, bool smallest) {
  const auto of = [&](int s) {
    const Species& sp = dem.species[static_cast<std::size_t>(s)];
    return smallest ? sp.of_diameter(sp.d_min()) : sp;
  };
  const bool wall = b < 0;
  const Species sa = of(a);
  const Species sb = wall ? sa : of(b);
  const ElasticMaterial* ma = &dem.material_of(static_cast<std::size_t>(a));
  const ElasticMaterial* mb = wall ? &dem.contact.wall_material : &dem.material_of(static_cast<std::size_t>(b));
  return {wall ? sa.mass() : reduced_mass(sa.mass(), sb.mass()),
          wall ? sa.radius() : sa.radius() * sb.radius() / (sa.radius() + sb.radius()),
          effective_youngs_modulus(*ma, *mb), wall ? sa.diameter : std::min(sa.diameter, sb.diameter), ma, mb};
}

}  // namespace

EquivalentContact equivalent_contact(const DemConfig& dem, int a, int b) {
  const ContactPair p = contact_pair(dem, a, b, true);
  const double m_eff = p.m_eff;
  const bool wall = b < 0;
  const double e = wall ? dem.wall[static_cast<std::size_t>(a)].restitution : dem.pair_params(a, b).restitution;
  const ContactModelConfig& m = dem.contact;
  if (m.normal == NormalModel::Linear) {
    const double k = dem.stiffness;
    const double k_t = m.tangential == TangentialModel::Linear ? k * dem.tangential_stiffness_ratio : 0.0;
    const double eta = damping_from_restitution(m_eff, k, e);
    EquivalentContact c{m_eff, k, k_t, eta, pair_contact_duration(m_eff, k, e)};
    if (m.tangential == TangentialModel::Mindlin) {
      // Mindlin's k_t at the linear spring's largest overlap of the impact
      const double g = effective_shear_modulus(*p.ma, *p.mb);
      c.k_t = 8.0 * g * std::sqrt(p.r_eff * m.impact_speed * std::sqrt(m_eff / k));
    }
    return c;
  }
  const HertzImpact h = hertz_impact(m_eff, p.e_star, p.r_eff, m.impact_speed);
  const double a_max = std::sqrt(p.r_eff * h.max_overlap);
  const double k_n = 2.0 * p.e_star * a_max;
  const double k_t = m.tangential == TangentialModel::Mindlin ? 8.0 * effective_shear_modulus(*p.ma, *p.mb) * a_max
                                                              : k_n * dem.tangential_stiffness_ratio;
  return {m_eff, k_n, k_t, tsuji_alpha_for_hertz(e) * std::sqrt(m_eff * k_n), h.duration};
}

namespace {
// equivalent_contact's t_c alone: the Hertz duration needs no dashpot (whose Tsuji alpha is an integration).
double contact_duration_of(const DemConfig& dem, int a, int b) {
  if (dem.contact.normal == NormalModel::Linear) return equivalent_contact(dem, a, b).t_c;
  const ContactPair p = contact_pair(dem, a, b, true);
  return hertz_impact(p.m_eff, p.e_star, p.r_eff, dem.contact.impact_speed).duration;
}
}  // namespace

StiffestContact stiffest_contact(const DemConfig& dem) {
  StiffestContact out{1e300, 0, -1};
  for (std::size_t a = 0; a < dem.n_species(); ++a) {
    for (std::size_t b = a; b < dem.n_species(); ++b) {
      const double t = contact_duration_of(dem, static_cast<int>(a), static_cast<int>(b));
      if (t < out.t_c) out = {t, static_cast<int>(a), static_cast<int>(b)};
    }
    const double t = contact_duration_of(dem, static_cast<int>(a), -1);
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
  if (three_d && d > domain.depth && d <= std::min(domain.width, domain.height)) {
    // The width and height hold it: the depth is what is too thin, not the diameter's unit.
    r.fail("domain.depth", fmt::format("{:.6g} m is shallower than a particle of {} = {:.6g} m: a 3D bed must be at "
                                       "least one diameter deep (a pseudo-2D slab is a few); deepen domain.depth",
                                       domain.depth, diameter_key, d));
  }
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

namespace {

// `check`'s report: aligned "what: value" lines, and warnings that say what a choice costs.
struct Report {
  std::string text;
  std::vector<std::string> warnings;
  void line(const std::string& what, const std::string& value) { text += fmt::format("  {:<44} {}\n", what, value); }
};

// Totals of the particles a DEM case places.
struct BedTotals {
  double mass = 0.0;      ///< kg
  double measure = 0.0;   ///< solid area (2D discs), m^2, or volume (3D), m^3
  double height = 0.0;    ///< estimated settled height, m
  double d_largest = 0.0; ///< m
};

// Every kind of contact once: (a, b) with a <= b, then (a, wall) as b = -1.
template <class F>
void for_each_contact_kind(const DemConfig& dem, F&& f) {
  for (std::size_t a = 0; a < dem.n_species(); ++a) {
    for (std::size_t b = a; b < dem.n_species(); ++b) f(static_cast<int>(a), static_cast<int>(b));
    f(static_cast<int>(a), -1);
  }
}
std::string kind_name(int a, int b) { return b < 0 ? fmt::format("{}-wall", a) : fmt::format("{}-{}", a, b); }

// The case's contacts with every elastic modulus (particles and walls) times s, or the linear spring's k times s.
DemConfig stiffened(const DemConfig& dem, double s) {
  DemConfig d = dem;
  if (dem.contact.normal == NormalModel::Linear) {
    d.stiffness *= s;
    return d;
  }
  for (ElasticMaterial& m : d.material) m.youngs_modulus *= s;
  d.contact.wall_material.youngs_modulus *= s;
  return d;
}

// The softest particle modulus of the case (the one an advice to scale the moduli is quoted for).
double softest_modulus(const DemConfig& dem) {
  double e = 1e300;
  for (std::size_t s = 0; s < dem.n_species(); ++s) e = std::min(e, dem.material_of(s).youngs_modulus);
  return e;
}

// A rough run-time figure in words.
std::string duration_text(double s) {
  if (s < 120.0) return fmt::format("{:.2g} s", s);
  if (s < 2.0 * 3600.0) return fmt::format("{:.2g} min", s / 60.0);
  if (s < 2.0 * 86400.0) return fmt::format("{:.2g} h", s / 3600.0);
  return fmt::format("{:.2g} days", s / 86400.0);
}

void describe_header(Report& r, const CaseConfig& c) {
  r.text += fmt::format("case '{}' ({}): {}\n", c.name, c.model == Model::Tfm ? "two-fluid model" : "discrete particles",
                        c.description);
  for (const std::string& n : c.notes) r.text += fmt::format("  note: {}\n", n);
  const DomainConfig& d = c.domain;
  if (d.dimension == 3) {
    const std::string sides = d.periodic[0] && d.periodic[2] ? "periodic in x and z"
                              : d.periodic[2]                ? "periodic in z"
                              : d.periodic[0]                ? "periodic in x, front and back walls"
                                                             : "front and back walls";
    r.line("domain", fmt::format("{:.6g} x {:.6g} x {:.6g} m (width x height x depth, {}), gravity ({:.6g}, {:.6g}, "
                                 "{:.6g}) m/s^2", d.width, d.height, d.depth, sides, d.gravity.x, d.gravity.y, d.gravity.z));
  } else {
    r.line("domain", fmt::format("{:.6g} x {:.6g} m{}, gravity ({:.6g}, {:.6g}) m/s^2", d.width, d.height,
                                 d.periodic[0] ? " (periodic in x)" : "", d.gravity.x, d.gravity.y));
  }
  r.line("end time", fmt::format("{:.6g} s", c.run.end_time));
}

// U_mf of one size and density by the law the case's bed line uses, so both lines agree.
double case_law_minimum_fluidisation(const CaseConfig& c, double d, double rho) {
  const double g = std::abs(c.domain.gravity.y);
  const DragModel model{c.coupling.drag_law, c.coupling.drag_switch};
  if (model.law == DragLaw::ErgunWenYu && model.blend == DragSwitch::Sharp) {
    return ergun_minimum_fluidisation_velocity(kDemEpsMf, d, rho, c.gas.rho_g, c.gas.mu_g, g);
  }
  return minimum_fluidisation_velocity(model, kDemEpsMf, d, rho, c.gas.rho_g, c.gas.mu_g, g);
}

BedTotals describe_dem_species(Report& r, const CaseConfig& c) {
  const DemConfig& dem = c.dem;
  const bool three_d = c.domain.dimension == 3;
  const double g = std::abs(c.domain.gravity.y);
  const std::vector<double>& frac = c.particles.packing.species_fraction;
  const auto n = static_cast<double>(c.particles.packing.count);
  BedTotals bed;
  const std::vector<SpeciesSizes> sizes = species_sizes(c);
  for (std::size_t a = 0; a < dem.n_species(); ++a) {
    const Species& sp = dem.species[a];
    const double f = a < frac.size() ? frac[a] : 0.0;
    const SizeMoments m = size_moments(sp.distribution());
    bed.mass += n * f * sp.density * std::numbers::pi * m.m3 / 6.0;
    bed.measure += n * f * (three_d ? std::numbers::pi * m.m3 / 6.0 : std::numbers::pi * m.m2 / 4.0);
    bed.d_largest = std::max(bed.d_largest, sp.d_max());
    std::string v = fmt::format("d = {:.6g} m, rho = {:.6g} kg/m^3, mass {:.4g} kg, {:.3g}% by number", sp.diameter,
                                sp.density, sp.mass(), 100.0 * f);
    if (g > 0.0 && sp.density > c.gas.rho_g) {
      v += fmt::format("; u_t = {:.3f} m/s (Eq. 14), {} alone {:.3f} m/s",
                       terminal_velocity(sp.diameter, sp.density, c.gas.rho_g, c.gas.mu_g, g),
                       bed_minimum_fluidisation_label(c), case_law_minimum_fluidisation(c, sp.diameter, sp.density));
    }
    r.line(fmt::format("species {}", a), v);
    const SpeciesSizes& z = sizes[a];
    r.line(fmt::format("species {} sizes", a),
           fmt::format("{}: {} particles{}, mean d = {:.4g} m, d32 = {:.4g} m, min {:.4g} m, max {:.4g} m", z.what,
                       z.count, z.from_file ? " in the file" : "", z.mean, z.d32, z.d_min, z.d_max));
  }
  return bed;
}

// Duration of every kind of contact in time steps, by the law the case uses (Eq. 8 for the linear spring, Hertz's
// impact at contact.impact_speed), and the DEM step against the stiffest.
void describe_dem_contacts(Report& r, const DemConfig& dem) {
  const ContactModelConfig& law = dem.contact;
  r.line("contact law", fmt::format("normal {}, damping {}, tangential {}, rolling {}", to_string(law.normal),
                                    to_string(law.damping), to_string(law.tangential), to_string(law.rolling)));
  if (law.normal == NormalModel::Hertz) {
    for_each_contact_kind(dem, [&](int a, int b) {
      // Johnson (1985): duration and largest overlap of an impact; the smallest particles (equivalent_contact).
      const EquivalentContact ec = equivalent_contact(dem, a, b);
      const ContactPair p = contact_pair(dem, a, b, true);
      const double overlap = hertz_impact(p.m_eff, p.e_star, p.r_eff, law.impact_speed).max_overlap;
      const double d_small = p.d_small;
      r.line(fmt::format("Hertz contact {}", kind_name(a, b)),
             fmt::format("at {:g} m/s: t_c = {:.4g} s = {:.1f} time steps, largest overlap {:.3g}% of d, tangent "
                         "stiffness {:.4g} N/m", law.impact_speed, ec.t_c, ec.t_c / dem.dt, 100.0 * overlap / d_small,
                         ec.k_n));
    });
  } else {
    double m_light = 1e300;  // the lightest particle any species places
    for (const Species& sp : dem.species) m_light = std::min(m_light, sp.of_diameter(sp.d_min()).mass());
    const double t_cr = critical_time(m_light, dem.stiffness);
    r.line("t_cr = 2 pi sqrt(m/k) (Table 3 item 5)",
           fmt::format("{:.4g} s for the lightest species; dt / t_cr = {:.3g}", t_cr, dem.dt / t_cr));
    for_each_contact_kind(dem, [&](int a, int b) {
      const Species& sa = dem.species[static_cast<std::size_t>(a)];
      const double m_eff = b < 0 ? sa.mass() : reduced_mass(sa.mass(), dem.species[static_cast<std::size_t>(b)].mass());
      const double e = b < 0 ? dem.wall[static_cast<std::size_t>(a)].restitution : dem.pair_params(a, b).restitution;
      const double t_c = pair_contact_duration(m_eff, dem.stiffness, e);
      r.line(fmt::format("contact duration {} (e = {:g})", kind_name(a, b), e),
             fmt::format("{:.4g} s = {:.1f} time steps; damping eta {:.4g} kg/s (Eq. 8)", t_c, t_c / dem.dt,
                         damping_from_restitution(m_eff, dem.stiffness, e)));
    });
  }
  const StiffestContact sc = stiffest_contact(dem);
  r.line("DEM time step", fmt::format("{:g} s = t_c / {:.1f} of the stiffest contact ({}); largest stable {:.4g} s",
                                      dem.dt, sc.t_c / dem.dt, pair_name(sc.a, sc.b), dem_stable_time_step(dem)));
}

// The impact speed the overlap lines judge: the fastest inflow of any schedule (as the gas step's derivation), or
// the free fall from the fill height without gas.
double impact_velocity(const CaseConfig& c) {
  if (c.gas_enabled) return inlet_peak_velocity(c.gas.boundary);
  return std::sqrt(2.0 * std::abs(c.domain.gravity.y) * c.particles.packing.y_max);
}

// Overlaps under the bed's weight and in a head-on impact, by the case's normal law, and the stiffness (linear:
// k; Hertz: the moduli) for a 1% overlap. Returns the factor on the stiffness a 1% impact overlap needs (0: none).
double describe_dem_overlaps(Report& r, const CaseConfig& c, const BedTotals& bed) {
  const DemConfig& dem = c.dem;
  const bool hertz = dem.contact.normal == NormalModel::Hertz;
  const bool three_d = c.domain.dimension == 3;
  const double g = std::abs(c.domain.gravity.y);
  constexpr double target = 0.01;
  auto advice = [&](double s) {
    const double dt = default_dem_time_step(stiffened(dem, s));
    return hertz ? fmt::format("youngs_modulus = {:.3g} Pa (the case's moduli x {:.3g}; default dt there {:g} s)",
                               s * softest_modulus(dem), s, dt)
                 : fmt::format("k = {:.3g} N/m (default dt there {:g} s)", s * dem.stiffness, dt);
  };
  const std::string stiffness = hertz ? "youngs_modulus" : "stiffness";
  if (g > 0.0) {
    // A bottom particle carries the column above its width (2D, a monolayer: F = M g d / W) or its cross-section d^2
    // (3D: F = M g d^2 / (W D)); linear delta = F / k, Hertz F = (4/3) E* sqrt(R*) delta^(3/2) with its neighbour
    // above (Johnson 1985, Eq. 4.22), R* = d / 4.
    const double d = bed_mixture(dem, c.particles.packing.species_fraction).d32;
    const double force = three_d ? bed.mass * g * d * d / (c.domain.width * c.domain.depth) : bed.mass * g * d / c.domain.width;
    double e_star = 1e300;
    for_each_contact_kind(dem, [&](int a, int b) { if (b >= 0) e_star = std::min(e_star, contact_pair(dem, a, b, false).e_star); });
    const double r_eff = 0.25 * d;
    const double delta = hertz ? std::pow(3.0 * force / (4.0 * e_star * std::sqrt(r_eff)), 2.0 / 3.0) : force / dem.stiffness;
    // Hertz: delta ~ E*^(-2/3), so the moduli for delta = target d scale by (delta / (target d))^(3/2).
    const double s = hertz ? std::pow(delta / (target * d), 1.5) : delta / (target * d);
    r.line("mean overlap under the bed's weight", fmt::format("{:.3g}% of d at the bottom (force chains carry several "
                                                              "times the mean)", 100.0 * delta / d));
    r.line(fmt::format("{} for a 1% mean static overlap", stiffness), advice(s));
  }
  const double v = impact_velocity(c);
  if (!(v > 0.0)) return 0.0;
  double worst = 0.0;
  for_each_contact_kind(dem, [&](int a, int b) {
    const ContactPair p = contact_pair(dem, a, b, false);
    // Linear: the undamped spring's amplitude v sqrt(m*/k); Hertz: (15 m* v^2 / (16 E* sqrt(R*)))^(2/5).
    const double delta = hertz ? hertz_impact(p.m_eff, p.e_star, p.r_eff, v).max_overlap : v * std::sqrt(p.m_eff / dem.stiffness);
    worst = std::max(worst, delta / p.d_small);
  });
  const std::string at = c.gas_enabled ? fmt::format("at the fastest inflow {:.6g} m/s", v)
                                       : fmt::format("at {:.2f} m/s (free fall from the fill height)", v);
  r.line("overlap of a head-on impact", fmt::format("{:.3g}% of d {}", 100.0 * worst, at));
  // Linear: delta ~ k^(-1/2); Hertz: delta ~ E*^(-2/5).
  const double s = std::pow(worst / target, hertz ? 2.5 : 2.0);
  r.line(fmt::format("{} for a 1% impact overlap", stiffness), advice(s));
  return s;
}

// Frictional spheres settle looser than the frictionless random close packing (0.64): about 0.56 to 0.60 at the
// friction coefficients of glass and sand, down to random loose packing near 0.555 (Silbert 2010, Soft Matter 6).
constexpr double kFrictionalPackingLow = 0.56, kFrictionalPackingHigh = 0.60, kFrictionalPacking = 0.58;

bool frictionless(const DemConfig& dem) {
  bool none = true;
  for_each_contact_kind(dem, [&](int a, int b) {
    none = none && (b < 0 ? dem.wall[static_cast<std::size_t>(a)].friction : dem.pair_params(a, b).friction) <= 0.0;
  });
  return none;
}

// The DEM solver's data a particle of a packed bed, as it holds it (docs/performance.md section 39: 1,252 B for
// the 3D settle, whose heap measured 1,470 B a sphere with 16.6 entries and the program's own allocations): the
// store, 8 bytes a double array and 24 of ids and keys, the fluid's five (2D) or seven (3D) arrays only with gas;
// the list-build positions; per-particle offsets and orders, 24; E list entries of 18 bytes (partner, contact mark,
// half-list links, the scan's room); C / 2 contact records (force, two torques, the spring and its next value, the
// rolling springs' too for a law with them); the C springs by partner id a rebuild carries (id, spring, its
// place). Lists and records keep an eighth to spare (dem/growth.hpp). E and C are those counted on packed beds at
// the default skin (bench/contact_counts.py): 6 and 3.7 in 2D, 15 and 7 in 3D.
double dem_bytes_per_particle(const CaseConfig& c) {
  const bool three_d = c.domain.dimension == 3;
  const double dim = three_d ? 3.0 : 2.0, spin = three_d ? 3.0 : 1.0;
  const double entries = three_d ? 15.0 : 6.0, contacts = three_d ? 7.0 : 3.7;
  const bool rolling = c.dem.contact.needs_rolling_history();
  const double doubles = 3.0 * dim + 2.0 * spin + 4.0 + (c.gas_enabled ? 2.0 * dim + 1.0 : 0.0);
  const double store = 8.0 * doubles + 24.0 + 8.0 * dim + 24.0;
  const double record = 8.0 * (dim + 2.0 * spin + 2.0 * dim + (rolling ? 2.0 * spin : 0.0));
  const double held = 8.0 + 8.0 * dim + (rolling ? 8.0 * spin : 0.0) + 4.0;
  return store + 1.125 * (18.0 * entries + 0.5 * contacts * record) + contacts * held;
}

void describe_dem_bed(Report& r, const CaseConfig& c, BedTotals& bed) {
  const DemConfig& dem = c.dem;
  const auto n = c.particles.packing.count;
  r.line("particles", c.particles.source == ParticleSource::File ? fmt::format("{} read from {}", n, c.particles.file)
                                                                 : fmt::format("{} placed at random", n));
  if (c.domain.dimension == 3) {
    const double floor = c.domain.width * c.domain.depth;
    if (frictionless(dem)) {
      bed.height = bed.measure / kSpherePackingFraction / floor;
      r.line("estimated settled bed height", fmt::format("{:.3f} m from every species' volume (frictionless: random "
                                                        "close packing, volume fraction {})", bed.height,
                                                        kSpherePackingFraction));
    } else {
      bed.height = bed.measure / kFrictionalPacking / floor;
      r.line("estimated settled bed height",
             fmt::format("{:.3f} m from every species' volume (frictional spheres: volume fraction {} within {}-{}, "
                         "{:.3f}-{:.3f} m; {:.3f} m at the frictionless {})", bed.height, kFrictionalPacking,
                         kFrictionalPackingLow, kFrictionalPackingHigh, bed.measure / kFrictionalPackingHigh / floor,
                         bed.measure / kFrictionalPackingLow / floor, bed.measure / kSpherePackingFraction / floor,
                         kSpherePackingFraction));
    }
  } else {
    bed.height = bed.measure / kDiscPackingFraction / c.domain.width;
    r.line("estimated settled bed height", fmt::format("{:.3f} m from every species' area (random disc packing, area "
                                                      "fraction {})", bed.height, kDiscPackingFraction));
  }
  if (dem.n_species() > 1) {
    const BedMixture mix = bed_mixture(dem, c.particles.packing.species_fraction);
    r.line("mixture", fmt::format("Sauter mean diameter d32 = {:.4g} m, volume-mean density {:.4g} kg/m^3", mix.d32, mix.rho));
  }
  if (const auto u = bed_minimum_fluidisation_velocity(c)) {
    r.line(fmt::format("{} at eps_mf = {}", bed_minimum_fluidisation_label(c), kDemEpsMf),
           fmt::format("{:.3f} m/s{}", *u, dem.n_species() > 1 ? " (the mixture's d32 and density)" : ""));
  }
  r.line("memory estimate", fmt::format("{:.1f} MB for the particles (plus about 25 MB for the program)",
                                        static_cast<double>(n) * dem_bytes_per_particle(c) / 1e6));
}

void describe_dem_boundaries(Report& r, const CaseConfig& c) {
  const bool three_d = c.domain.dimension == 3;
  const WallConfig& walls = c.dem.walls;
  r.line("top of the domain (particles)", walls.top ? "wall"
                                          : walls.top_outflow ? "outflow: leaving particles are removed and counted"
                                                              : "open: a particle crossing it fails the run");
  if (three_d && !c.domain.periodic[2]) {
    r.line("front and back (particles)", walls.outflow(4) || walls.outflow(5)
                                             ? "walls, except the outflow sides of domain.particle_outflow"
                                             : "walls (z = 0 and z = domain.depth)");
  }
  if (c.domain.any_periodic()) {
    const bool x = c.domain.periodic[0], z = c.domain.periodic[2];
    r.line("periodic axes", fmt::format("{}: particles leaving one side re-enter at the other, contacts through the "
                                        "nearest image", x && z ? "x and z" : x ? "x" : "z"));
  }
  std::string out;
  const char* side_names[6] = {"left", "right", "bottom", "top", "back", "front"};
  for (int w = 0; w < (three_d ? 6 : 4); ++w) {
    if (w != 3 && walls.outflow(w)) out += (out.empty() ? "" : ", ") + std::string(side_names[w]);
  }
  if (!out.empty()) r.line("outflow sides (particles)", out + ": leaving particles are removed and counted");
  if (c.dem.insertion.enabled()) {
    const InsertionConfig& in = c.dem.insertion;
    const double m = c.dem.species[static_cast<std::size_t>(in.species)].mass();
    r.line("particle feed", fmt::format("{:.6g} particles/s ({:.6g} kg/s) of species {} from t = {:.6g} s{}, seed {}",
                                        in.rate, in.rate * m, in.species, in.t_start,
                                        std::isfinite(in.t_end) ? fmt::format(" to {:.6g} s", in.t_end) : std::string(),
                                        in.seed));
  }
}

// The slab a 2D monolayer stands for: a packed layer of discs (area fraction 0.82) of spheres of diameter d in a
// slab D deep holds a solids volume fraction 0.82 (pi d^3 / 6) / (pi d^2 D / 4) = 0.82 (2/3) d / D.
void describe_slab(Report& r, const CaseConfig& c, const BedTotals& bed) {
  const double depth = c.coupling.depth;
  const double eps_packed = 1.0 - kDiscPackingFraction * (2.0 / 3.0) * bed.d_largest / depth;
  r.line("slab depth (coupling.depth)",
         fmt::format("{:.6g} m: particle volume over cells {:.6g} x {:.6g} x {:.6g} m; a packed layer of the largest "
                     "particles ({:.6g} m) has a voidage of about {:.3f}", depth, c.grid.dx, c.grid.dy, depth,
                     bed.d_largest, eps_packed));
  if (eps_packed < c.coupling.eps_min) {
    r.warnings.push_back(fmt::format("coupling.depth = {:.6g} m is too thin for the largest particles ({:.6g} m): a "
                                     "packed layer of them has a voidage of {:.3f}, below coupling.eps_min = {:g}{}; "
                                     "the slab must be at least as deep as the largest particle", depth, bed.d_largest,
                                     eps_packed, c.coupling.eps_min, eps_packed < 0.0 ? " (below zero: the run fails)" : ""));
  }
}

void describe_inlet(Report& r, const CaseConfig& c) {
  const bool three_d = c.domain.dimension == 3;
  const GasBoundaryConfig& bc = c.gas.boundary;
  r.line("inlet (superficial)",
         bc.schedule.kind != ScheduleKind::Constant
             ? schedule_text(bc.schedule, bc.inlet_velocity) + " through the bottom"
         : bc.ramp_time > 0.0 ? fmt::format("{:.6g} m/s through the bottom, ramped from {:.6g} m/s over 0 <= t < {:.6g} s",
                                          bc.inlet_velocity, bc.ramp_from, bc.ramp_time)
                            : fmt::format("{:.6g} m/s through the bottom", bc.inlet_velocity));
  if (bc.inlet_noise > 0.0) {
    r.line("distributor non-uniformity", fmt::format("+-{:g}% per bottom cell, fixed in time (seed {}), total inflow "
                                                     "unchanged", 100.0 * bc.inlet_noise, bc.noise_seed));
  }
  double open_area = 0.0;
  for (const InletJet& j : bc.jets) {
    open_area += j.shape == InletShape::Disc        ? std::numbers::pi * 0.25 * j.width * j.width
                 : j.shape == InletShape::Rectangle ? j.width * j.depth
                                                    : j.width * (three_d ? c.domain.depth : 1.0);
  }
  const std::size_t n_jets = bc.jets.size();
  if (n_jets > 8) {
    r.line("jets and plate holes", fmt::format("{} regions, open area {:.6g} {} ({:.4g}% of the bottom); the first "
                                               "four:", n_jets, open_area, three_d ? "m^2" : "m per metre of depth",
                                               100.0 * open_area / (c.domain.width * (three_d ? c.domain.depth : 1.0))));
  }
  for (std::size_t k = 0; k < n_jets && (n_jets <= 8 || k < 4); ++k) {
    const InletJet& j = bc.jets[k];
    std::string where = fmt::format("[{:.6g}, {:.6g}] m", j.x_centre - 0.5 * j.width, j.x_centre + 0.5 * j.width);
    if (three_d) {
      where = j.shape == InletShape::Disc
                  ? fmt::format("a disc of diameter {:.6g} m centred at (x, z) = ({:.6g}, {:.6g}) m", j.width,
                                j.x_centre, j.z_centre)
              : j.shape == InletShape::Rectangle
                  ? fmt::format("a rectangle x in {}, z in [{:.6g}, {:.6g}] m", where, j.z_centre - 0.5 * j.depth,
                                j.z_centre + 0.5 * j.depth)
                  : fmt::format("a slot x in {} across the whole depth", where);
    }
    // A plate's default end (1e9 s) reads as "from t_start on".
    const std::string when = j.t_end >= 1e9 ? fmt::format("from t = {:.6g} s on", j.t_start)
                                            : fmt::format("for {:.6g} <= t < {:.6g} s", j.t_start, j.t_end);
    r.line("jet", fmt::format("{} over {} {}", schedule_text(j.schedule, j.velocity), where, when));
  }
}

void describe_gas(Report& r, const CaseConfig& c, const BedTotals& bed) {
  const CaseGrid& g = c.grid;
  if (c.domain.dimension == 3) {
    r.line("gas grid", fmt::format("{} x {} x {} cells of {:.6g} x {:.6g} x {:.6g} m", g.nx, g.ny, g.nz, g.dx, g.dy, g.dz));
  } else {
    r.line("gas grid", fmt::format("{} x {} cells of {:.6g} x {:.6g} m", g.nx, g.ny, g.dx, g.dy));
  }
  if (c.model == Model::Dem) {
    r.line("gas time step", fmt::format("{:g} s ({} DEM steps)", c.dem.dt * c.coupling.dem_substeps, c.coupling.dem_substeps));
    if (c.domain.dimension == 2) describe_slab(r, c, bed);
  }
  describe_inlet(r, c);
  r.line("U_mf of the throughflow ratio (bubble.u_mf)", fmt::format("{:.3f} m/s", c.bubble.u_mf));
}

void describe_tfm(Report& r, const CaseConfig& c) {
  const tfm::TfmConfig& t = c.tfm;
  const double g = std::abs(c.domain.gravity.y);
  r.line("solids", fmt::format("d = {:.6g} m, rho_s = {:.6g} kg/m^3, eps_initial = {:.6g}, eps* = {:.6g}", t.d_p,
                               t.rho_s, t.eps_initial, t.eps_star));
  if (const auto u = bed_minimum_fluidisation_velocity(c)) {
    r.line(bed_minimum_fluidisation_label(c) + " at eps_initial", fmt::format("{:.3f} m/s", *u));
  }
  if (g > 0.0) r.line("terminal velocity (Eq. 14)", fmt::format("{:.3f} m/s", terminal_velocity(t.d_p, t.rho_s, t.rho_g, t.mu_g, g)));
  r.line("bed weight per area", fmt::format("{:.0f} Pa", (1.0 - t.eps_initial) * (t.rho_s - t.rho_g) * g * t.packed_height));
  r.line("memory estimate", fmt::format("{:.2f} MB", static_cast<double>(c.grid.cells()) * 40 * 8 / 1e6));
}

// Geldart (1973) group of a powder by its Sauter diameter and density difference: A/B at
// (rho_p - rho_g) d = 225 g/cm^3 um, B/D at (rho_p - rho_g) d^2 = 1e6 g/cm^3 um^2, cohesive C below about 30 um.
char geldart_group(double d, double drho) {
  const double d_um = d * 1e6, drho_g_cm3 = drho * 1e-3;
  if (d_um < 30.0) return 'C';
  if (drho_g_cm3 * d_um < 225.0) return 'A';
  if (drho_g_cm3 * d_um * d_um < 1e6) return 'B';
  return 'D';
}

// The regime a bed is likely in: its Geldart group, and slugging by Stewart & Davidson (1967), U - U_mf >
// 0.07 sqrt(g D), in a bed deeper than the column is wide, with Darton et al.'s (1977) bubble at the surface,
// D_b = 0.54 (U - U_mf)^0.4 H^0.8 g^-0.2 (a porous distributor).
void describe_regime(Report& r, const CaseConfig& c, double bed_height) {
  const double g = std::abs(c.domain.gravity.y);
  const auto u_mf = bed_minimum_fluidisation_velocity(c);
  if (!(g > 0.0) || !u_mf) return;
  double d = c.tfm.d_p, rho = c.tfm.rho_s;
  if (c.model == Model::Dem) {
    const BedMixture mix = bed_mixture(c.dem, c.particles.packing.species_fraction);
    d = mix.d32;
    rho = mix.rho;
  }
  const char group = geldart_group(d, rho - c.gas.rho_g);
  const char* words = group == 'C'   ? "cohesive: channels and lifts as a plug rather than fluidising"
                      : group == 'A' ? "aeratable: expands before it bubbles"
                      : group == 'B' ? "sand-like: bubbles from U_mf on"
                                     : "coarse or dense: slow bubbles, spouting and slugging in narrow beds";
  r.line("Geldart group (Geldart 1973)", fmt::format("{} (d32 = {:.4g} m, rho_p - rho_g = {:.6g} kg/m^3): {}", group,
                                                     d, rho - c.gas.rho_g, words));
  double u = 0.0;  // the background inflow at its peak over the run (jets aside)
  for (int k = 0; k <= 200; ++k) u = std::max(u, std::abs(background_inlet_velocity(c.gas.boundary, c.run.end_time * k / 200.0)));
  const bool three_d = c.domain.dimension == 3;
  // A slug spans the column: in a pseudo-2D slab every void touches the front and back, so the width counts.
  const double width = three_d ? std::max(c.domain.width, c.domain.depth) : c.domain.width;
  const double h = c.model == Model::Tfm ? c.tfm.packed_height : bed_height;
  const double excess = u - *u_mf;
  const double sd = 0.07 * std::sqrt(g * width);
  std::string verdict;
  if (excess <= 0.0) {
    verdict = "the background inflow is not above U_mf: a fixed bed outside the jets";
  } else {
    const double d_b = 0.54 * std::pow(excess, 0.4) * std::pow(h, 0.8) * std::pow(g, -0.2);
    const bool slugs = excess > sd && h > width;
    verdict = fmt::format("Darton's bubble at the surface {:.3g} m ({:.2g} of the width); {}", d_b, d_b / width,
                          slugs ? "slugging likely: voids span the column (slugs; a plug lifted off the distributor "
                                  "for coarse particles), not free bubbles"
                                : "free bubbling expected");
    if (slugs) {
      r.warnings.push_back(fmt::format("the bed is likely to slug: U - U_mf = {:.3g} m/s exceeds 0.07 sqrt(g D) = {:.3g} "
                                       "m/s (Stewart & Davidson 1967) and the bed ({:.3g} m) is deeper than the column is "
                                       "wide ({:.3g} m); the analysis flags voids that span the column as slugs", excess,
                                       sd, h, width));
    }
  }
  r.line("slugging (Stewart & Davidson 1967)",
         fmt::format("U - U_mf = {:.3g} m/s against 0.07 sqrt(g D) = {:.3g} m/s for D = {:.6g} m, H/D = {:.2g}: {}",
                     excess, sd, width, h / width, verdict));
}

// This build's measured costs on one core (docs/performance.md): a DEM particle-step in a packed bed, 2D 62 ns
// (section 24, 22,000 to 1,000,000 particles) and 3D 435 ns (section 25, 100,000 spheres settling); a CFD-DEM gas
// cell-step in 2D 2.7 us (section 13: 4.0 ms per step of the paper's 1,500 cells), in 3D that times the TFM's 3D to
// 2D ratio (3.3, section 25); a TFM cell-step 1.03 us in 2D and 3.4 us in 3D (section 25).
constexpr double kDemParticleStep2d = 62e-9, kDemParticleStep3d = 435e-9;
constexpr double kGasCellStep2d = 2.7e-6, kGasCellStep3d = 3.3 * kGasCellStep2d;
constexpr double kTfmCellStep2d = 1.03e-6, kTfmCellStep3d = 3.4e-6;

void describe_cost(Report& r, const CaseConfig& c, double soften) {
  const bool three_d = c.domain.dimension == 3;
  const double t = c.run.end_time;
  const auto cells = static_cast<double>(c.grid.cells());
  if (c.model == Model::Tfm) {
    // The TFM's step is adaptive: at most tfm.dt_max, and a Courant number tfm.cfl on the fastest inflow.
    double h = std::min(c.grid.dx, c.grid.dy);
    if (three_d) h = std::min(h, c.grid.dz);
    const double steps = t * std::max(1.0 / c.tfm.dt_max, inlet_peak_velocity(c.gas.boundary) / (c.tfm.cfl * h));
    const double wall = steps * cells * (three_d ? kTfmCellStep3d : kTfmCellStep2d);
    r.line("run-time estimate", fmt::format("{} on one thread: about {:.3g} steps x {:.0f} cells x {:.3g} us per "
                                            "cell-step (this build, docs/performance.md); the adaptive step may take "
                                            "up to twice as many", duration_text(wall), steps, cells,
                                            1e6 * (three_d ? kTfmCellStep3d : kTfmCellStep2d)));
    return;
  }
  const DemConfig& dem = c.dem;
  const double dem_steps = t / dem.dt;
  const double particle_steps = dem_steps * static_cast<double>(c.particles.packing.count);
  const double per_particle = three_d ? kDemParticleStep3d : kDemParticleStep2d;
  const double gas_steps = c.gas_enabled ? dem_steps / c.coupling.dem_substeps : 0.0;
  const double per_cell = three_d ? kGasCellStep3d : kGasCellStep2d;
  const double wall = particle_steps * per_particle + gas_steps * cells * per_cell;
  r.line("run-time estimate",
         fmt::format("{} on one thread ({:.3g} s per simulated second): {:.3g} particle-steps x {:.0f} ns{} (this "
                     "build, docs/performance.md)", duration_text(wall), t > 0.0 ? wall / t : 0.0, particle_steps,
                     1e9 * per_particle, c.gas_enabled ? fmt::format(" + {:.3g} gas cell-steps x {:.2g} us",
                                                                      gas_steps * cells, 1e6 * per_cell)
                                                       : std::string()));
  const double dt_derived = default_dem_time_step(dem);
  if (dem.dt < 0.5 * dt_derived) {
    r.warnings.push_back(fmt::format("dem.time_step = {:g} s is {:.3g} times below the derived step {:g} s (t_c / {:g} "
                                     "of the stiffest contact): the run costs that many times more", dem.dt,
                                     dt_derived / dem.dt, dt_derived, kStepsPerContact));
  }
  // Contacts far stiffer than a 1% impact overlap needs: the step, and the cost, follow t_c ~ k^(-1/2) (linear)
  // or E^(-2/5) (Hertz).
  if (soften > 0.0 && soften < 0.1) {
    const double dt_soft = default_dem_time_step(stiffened(dem, soften));
    if (dt_soft > 3.0 * dem.dt) {
      r.warnings.push_back(fmt::format(
          "the contacts are {:.3g} times stiffer than a 1% impact overlap needs, which sets the DEM step to {:g} s; "
          "with {} = {:.3g} {} the step would be {:g} s and the particle part of the run about {:.3g} times shorter "
          "(softer contacts last longer: keep them short against the bed's time scales)", 1.0 / soften, dem.dt,
          dem.contact.normal == NormalModel::Hertz ? "youngs_modulus" : "contact.stiffness",
          dem.contact.normal == NormalModel::Hertz ? soften * softest_modulus(dem) : soften * dem.stiffness,
          dem.contact.normal == NormalModel::Hertz ? "Pa" : "N/m", dt_soft, dt_soft / dem.dt));
    }
  }
  if (c.gas_enabled && c.coupling.dem_substeps >= 100) {
    r.warnings.push_back(fmt::format("{} DEM steps per gas step: the particles' step is {} times below the gas's; "
                                     "the DEM cost dominates", c.coupling.dem_substeps, c.coupling.dem_substeps));
  }
}

void describe_averages(Report& r, const AveragesConfig& a) {
  if (!a.enabled) return;
  r.line("time averages ([averages])",
         a.interval > 0.0 ? fmt::format("{:.6g} to {:.6g} s, a sample every {:.6g} s ({:.0f} samples)", a.t_start, a.t_end,
                                        a.interval, std::floor((a.t_end - a.t_start) / a.interval + 1e-9) + 1)
                          : fmt::format("{:.6g} to {:.6g} s, a sample after every model step", a.t_start, a.t_end));
}

}  // namespace

std::string describe_case(const CaseConfig& c) {
  Report r;
  describe_header(r, c);
  BedTotals bed;
  double soften = 0.0;
  if (c.model == Model::Dem) {
    bed = describe_dem_species(r, c);
    describe_dem_contacts(r, c.dem);
    soften = describe_dem_overlaps(r, c, bed);
    describe_dem_bed(r, c, bed);
    describe_dem_boundaries(r, c);
  }
  if (c.model == Model::Tfm || c.gas_enabled) describe_gas(r, c, bed);
  if (c.model == Model::Tfm) describe_tfm(r, c);
  if (c.model == Model::Tfm || c.gas_enabled) describe_regime(r, c, bed.height);
  describe_cost(r, c, soften);
  describe_averages(r, c.averages);
  for (const std::string& w : r.warnings) r.text += fmt::format("  warning: {}\n", w);
  return r.text;
}

}  // namespace fluidbed
