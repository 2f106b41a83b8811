// The discrete model's sections, [species], [contact], [dem], [insertion], [particles] and [settle], into
// CaseConfig::dem (DemConfig, dem/dem_config.hpp), CaseConfig::particles and CaseConfig::settle, and the time steps
// the DEM keys imply.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "config/case_check.hpp"
#include "config/case_loader.hpp"
#include "config/case_sections.hpp"
#include "config/settle_record.hpp"
#include "core/error.hpp"
#include "dem/contact_law.hpp"
#include "io/csv.hpp"

namespace fluidbed {

double dem_stable_time_step(const DemConfig& dem) {
  double dt = 1e300;
  // A linear contact integrated by Eq. 10 (symplectic Euler) is stable for omega dt < 2 (sqrt(1 + zeta^2) - zeta).
  // Two modes per contact: normal (k_n on the reduced mass) and tangential, where the contact point also moves
  // by rotation: 1/m_t = 1/m1 + 1/m2 + r1^2/I1 + r2^2/I2 (7/m for equal spheres). A Hertz contact is judged by
  // its stiffest moment, the tangent stiffness at the largest overlap (equivalent_contact).
  auto limit = [&](double inv_m, double inv_m_t, const EquivalentContact& ec) {
    for (const auto& [k, inv] : {std::pair{ec.k_n, inv_m}, std::pair{ec.k_t, inv_m_t}}) {
      const double w0 = std::sqrt(k * inv);
      const double zeta = 0.5 * ec.eta_n * inv / w0;
      dt = std::min(dt, 2.0 / w0 * (std::sqrt(1.0 + zeta * zeta) - zeta));
    }
  };
  // Each species by its smallest particle: the lightest, whose contacts are the shortest.
  for (std::size_t a = 0; a < dem.n_species(); ++a) {
    const Species sa = dem.species[a].of_diameter(dem.species[a].d_min());
    const double rot_a = sa.radius() * sa.radius() / sa.inertia();
    for (std::size_t b = 0; b < dem.n_species(); ++b) {
      const Species sb = dem.species[b].of_diameter(dem.species[b].d_min());
      const double rot_b = sb.radius() * sb.radius() / sb.inertia();
      limit(1.0 / sa.mass() + 1.0 / sb.mass(), 1.0 / sa.mass() + 1.0 / sb.mass() + rot_a + rot_b,
            equivalent_contact(dem, static_cast<int>(a), static_cast<int>(b)));
    }
    limit(1.0 / sa.mass(), 1.0 / sa.mass() + rot_a, equivalent_contact(dem, static_cast<int>(a), -1));
  }
  return dt;
}

double dem_packed_bed_time_step(const DemConfig& dem) {
  const double z = dem.domain.dimension == 3 ? 12.0 : 6.0;
  double dt = 1e300;
  for (std::size_t a = 0; a < dem.n_species(); ++a) {
    const Species s = dem.species[a].of_diameter(dem.species[a].d_min());  // its lightest particle
    const EquivalentContact ec = equivalent_contact(dem, static_cast<int>(a), static_cast<int>(a));
    // The spin block of the stiffness is k_t r^2 / I times the contact graph's signless Laplacian (top eigenvalue
    // about 2 Z); the single dashpot (Eq. 3) has the same structure, hence zeta from the same factor.
    const double g = 2.0 * z * s.radius() * s.radius() / s.inertia();
    const double w0 = std::sqrt(ec.k_t * g);
    const double zeta = 0.5 * ec.eta_n * g / w0;
    dt = std::min(dt, 2.0 / w0 * (std::sqrt(1.0 + zeta * zeta) - zeta));
  }
  return dt;
}

namespace case_sections {

namespace {

// The composed contact law (docs/model.md, contact laws): one name per part, the elastic constants of Hertz and
// Mindlin per species and for the walls; returns the default rolling coefficients of pairs and walls (the pair
// tables may override the first). The defaults are the paper's law.
std::pair<double, double> read_contact_law(CaseReader& r, DemConfig& dem) {
  using R = CaseReader;
  ContactModelConfig& m = dem.contact;
  const auto index_of = [](const std::vector<std::string>& names, const std::string& v) {
    return static_cast<int>(std::find(names.begin(), names.end(), v) - names.begin());
  };
  m.normal = static_cast<NormalModel>(index_of(normal_model_names(), r.string("contact.normal", "linear",
      "normal spring: linear (the paper's Eq. 2, contact.stiffness) or hertz (Hertz 1882, from the species' "
      "Young's modulus and Poisson ratio)", normal_model_names())));
  const bool hertz = m.normal == NormalModel::Hertz;
  m.damping = static_cast<DampingModel>(index_of(damping_model_names(), r.string("contact.damping",
      hertz ? "tsuji" : "paper", "normal and tangential dashpot from the restitution: paper (Eq. 8, constant eta; "
      "linear spring only) or tsuji (Tsuji, Tanaka & Ishida 1992: eta = alpha sqrt(m* dF/d delta); restitution "
      "independent of the impact speed)", damping_model_names())));
  r.describe_default("contact.damping", "paper; tsuji with contact.normal = \"hertz\"");
  if (hertz && m.damping == DampingModel::Paper) {
    r.fail("contact.damping", "\"paper\" is the constant dashpot of the linear spring (Eq. 8); a Hertz spring "
           "takes \"tsuji\", whose restitution is the input at every impact speed");
  }
  m.tangential = static_cast<TangentialModel>(index_of(tangential_model_names(), r.string("contact.tangential",
      hertz ? "mindlin" : "linear", "tangential spring: linear (k_t = contact.tangential_stiffness_ratio x "
      "contact.stiffness) or mindlin (Mindlin 1949: k_t = 8 G* sqrt(R* delta))", tangential_model_names())));
  r.describe_default("contact.tangential", "linear; mindlin with contact.normal = \"hertz\"");
  m.rolling = static_cast<RollingModel>(index_of(rolling_model_names(), r.string("contact.rolling", "none",
      "rolling resistance (Ai et al. 2011): none, constant (model A, torque mu_r R* F_n against the rolling) or "
      "epsd (model C, elastic-plastic spring-dashpot)", rolling_model_names())));
  const double mu_r = r.number("contact.rolling_friction", 0.0, "", "rolling resistance coefficient mu_r of "
                               "particle-particle contacts", R::non_negative());
  const double mu_rw = r.number("contact.wall_rolling_friction", mu_r, "", "rolling resistance coefficient of "
                                "particle-wall contacts", R::non_negative());
  m.rolling_damping = r.number("contact.rolling_damping", 0.3, "", "viscous damping ratio eta_r of the epsd "
                               "rolling model (Ai et al. 2011 Eq. 16)", R::non_negative());
  m.impact_speed = r.number("contact.impact_speed", 1.0, "m/s", "impact speed at which a Hertz contact's duration "
                            "is judged (default time step and its check; t_c ~ v^(-1/5))", R::positive());
  // Walls as stiff as the stiffest particles unless given: a default of its own would set the wall contacts'
  // duration, and so the DEM step, without the user's say.
  ElasticMaterial stiffest = dem.material_of(0);
  for (const ElasticMaterial& e : dem.material) {
    if (e.youngs_modulus > stiffest.youngs_modulus) stiffest = e;
  }
  m.wall_material.youngs_modulus = r.number("contact.wall_youngs_modulus", stiffest.youngs_modulus, "Pa",
                                            "Young's modulus of the walls (Hertz, Mindlin)", R::positive());
  r.describe_default("contact.wall_youngs_modulus", "the stiffest species' youngs_modulus");
  m.wall_material.poisson_ratio = r.number("contact.wall_poisson_ratio", stiffest.poisson_ratio, "",
                                           "Poisson ratio of the walls", R::Range{-1.0, 0.5, true, false});
  r.describe_default("contact.wall_poisson_ratio", "the stiffest species' poisson_ratio");
  return {mu_r, mu_rw};
}

// Keys the chosen contact law needs or ignores. Hertz and Mindlin take their stiffness from the particles'
// moduli, which set the DEM step (t_c ~ E^(-2/5)): a default there would choose the cost of the run (glass's 7e10
// Pa: some 40 times the steps of a softened 1e7 Pa), so each species gives its own. Keys the law does not read
// are accepted with a note, so a user sees they change nothing.
void check_contact_keys(CaseReader& r, CaseConfig& c) {
  const ContactModelConfig& m = c.dem.contact;
  const bool hertz = m.normal == NormalModel::Hertz;
  const bool elastic = hertz || m.tangential == TangentialModel::Mindlin;
  const std::string law = hertz ? "contact.normal = \"hertz\"" : "contact.tangential = \"mindlin\"";
  for (std::size_t s = 0; s < c.dem.n_species(); ++s) {
    const std::string key = fmt::format("species[{}].youngs_modulus", s);
    if (elastic && !r.has(key)) {
      const DemConfig soft = [&] {
        DemConfig d = c.dem;
        for (ElasticMaterial& e : d.material) e.youngs_modulus = 1e7;
        d.contact.wall_material.youngs_modulus = 1e7;
        return d;
      }();
      r.fail(key, fmt::format("{} takes the contact stiffness from each species' Young's modulus: give it (glass "
                              "6e10-7e10 Pa, sand 7e10 Pa; CFD-DEM of bubbling beds often softens it to 1e7-1e8 Pa). "
                              "It sets the DEM step: the default step would be {:g} s at 7e10 Pa, {:g} s at 1e7 Pa",
                              law, default_dem_time_step(c.dem), default_dem_time_step(soft)));
    }
  }
  if (!elastic) {
    std::vector<std::string> unused;
    for (std::size_t s = 0; s < c.dem.n_species(); ++s) {
      for (const char* k : {"youngs_modulus", "poisson_ratio"}) {
        if (r.has(fmt::format("species[{}].{}", s, k))) unused.push_back(fmt::format("species[{}].{}", s, k));
      }
    }
    for (const char* k : {"contact.wall_youngs_modulus", "contact.wall_poisson_ratio"}) {
      if (r.has(k)) unused.push_back(k);
    }
    if (!unused.empty()) {
      c.notes.push_back(fmt::format("{}: read by the Hertz and Mindlin laws only; this case's linear springs "
                                    "(contact.stiffness) do not use {}", fmt::join(unused, ", "),
                                    unused.size() > 1 ? "them" : "it"));
    }
  }
  if (hertz && r.has("contact.stiffness")) {
    c.notes.push_back("contact.stiffness: the linear spring's; contact.normal = \"hertz\" takes its stiffness from the "
                      "species' youngs_modulus and does not use it");
  }
  if (m.rolling != RollingModel::None) {
    bool any = false;
    for (const InteractionParams& p : c.dem.pair) any = any || p.rolling_friction > 0.0;
    for (const InteractionParams& p : c.dem.wall) any = any || p.rolling_friction > 0.0;
    if (!any) {
      c.notes.push_back(fmt::format("contact.rolling = \"{}\" with a rolling friction of 0 for every pair and wall: "
                                    "the rolling model resists nothing (contact.rolling_friction sets mu_r)",
                                    to_string(m.rolling)));
    }
  }
}

// The size of one species' particles: a fixed diameter (the paper), or a distribution of the randomly placed ones
// (issue 14, item 3). With a distribution, Species::diameter is its number mean.
void read_species_size(CaseReader& r, const std::string& p, Species& sp) {
  using R = CaseReader;
  const std::string law = r.string(p + "size_distribution", "fixed", "sizes of the randomly placed particles, by "
                                   "number: fixed (all `diameter`), uniform (d_min..d_max), normal (mean, std), "
                                   "log-normal (median, sigma), both cut at d_min and d_max, or list (diameters, "
                                   "fractions)", {"fixed", "uniform", "normal", "log-normal", "list"});
  SizeDistribution& z = sp.size;
  z = SizeDistribution{};
  if (law == "fixed") {
    sp.diameter = r.number(p + "diameter", 0.004, "m", "particle diameter (size_distribution = \"fixed\")", R::positive());
    return;
  }
  if (r.has(p + "diameter")) {
    r.fail(p + "diameter", fmt::format("a species with size_distribution = \"{}\" takes its sizes from the "
                                       "distribution; its diameter is the distribution's mean", law));
  }
  auto cut_offs = [&](double lo, double hi) {
    z.d_min = r.number(p + "d_min", lo, "m", "smallest diameter placed (cut-off); default: 3 standard deviations "
                       "below the mean (normal) or the median / exp(3 sigma) (log-normal)", R::positive());
    z.d_max = r.number(p + "d_max", hi, "m", "largest diameter placed (cut-off); default: 3 standard deviations "
                       "above the mean (normal) or the median exp(3 sigma) (log-normal)", R::positive());
    if (!(z.d_max > z.d_min)) {
      r.fail(p + "d_max", fmt::format("{} m is not above d_min = {} m", z.d_max, z.d_min));
    }
  };
  if (law == "uniform") {
    z.law = SizeLaw::Uniform;
    z.d_min = r.required_number(p + "d_min", "m", "smallest diameter placed (cut-off)", R::positive());
    z.d_max = r.required_number(p + "d_max", "m", "largest diameter placed (cut-off)", R::positive());
    if (!(z.d_max > z.d_min)) r.fail(p + "d_max", fmt::format("{} m is not above d_min = {} m", z.d_max, z.d_min));
  } else if (law == "normal") {
    z.law = SizeLaw::Normal;
    z.mean = r.required_number(p + "mean", "m", "mean diameter of the normal distribution (before its cut-offs)",
                               R::positive());
    z.std = r.required_number(p + "std", "m", "standard deviation of the normal distribution's diameter",
                              R::positive());
    cut_offs(z.mean - 3.0 * z.std, z.mean + 3.0 * z.std);
    if (z.d_min <= 0.0) r.fail(p + "std", "mean - 3 std is not positive: give d_min");
  } else if (law == "log-normal") {
    z.law = SizeLaw::LogNormal;
    z.median = r.required_number(p + "median", "m", "median diameter exp(mu) of the log-normal distribution (before "
                                 "its cut-offs)", R::positive());
    z.sigma = r.required_number(p + "sigma", "", "standard deviation of ln d of the log-normal distribution",
                                R::positive());
    cut_offs(z.median * std::exp(-3.0 * z.sigma), z.median * std::exp(3.0 * z.sigma));
  } else {
    z.law = SizeLaw::List;
    z.diameters = r.numbers(p + "diameters", {}, "m", "the sizes of a list distribution");
    z.fractions = r.numbers(p + "fractions", {}, "", "fraction of each size of `diameters` (by number or by mass, see "
                            "fraction_basis); they add up to 1");
    const std::string basis = r.string(p + "fraction_basis", "number", "what `fractions` are: number fractions or "
                                       "mass fractions (equal density: turned into number fractions ~ f / d^3)",
                                       {"number", "mass"});
    if (z.diameters.empty()) r.fail(p + "diameters", "size_distribution = \"list\" needs at least one diameter");
    if (z.fractions.size() != z.diameters.size()) {
      r.fail(p + "fractions", fmt::format("{} fractions for {} diameters", z.fractions.size(), z.diameters.size()));
    }
    double sum = 0.0;
    for (std::size_t k = 0; k < z.diameters.size(); ++k) {
      if (!(z.diameters[k] > 0.0)) r.fail(p + "diameters", fmt::format("{} m is not a positive diameter", z.diameters[k]));
      if (!(z.fractions[k] >= 0.0)) r.fail(p + "fractions", fmt::format("{} is negative", z.fractions[k]));
      sum += z.fractions[k];
    }
    if (std::abs(sum - 1.0) > 1e-9) r.fail(p + "fractions", fmt::format("the fractions add up to {}, not 1", sum));
    if (basis == "mass") {
      double n = 0.0;
      for (std::size_t k = 0; k < z.diameters.size(); ++k) {
        z.fractions[k] /= z.diameters[k] * z.diameters[k] * z.diameters[k];
        n += z.fractions[k];
      }
      for (double& f : z.fractions) f /= n;
    }
    z.d_min = *std::min_element(z.diameters.begin(), z.diameters.end());
    z.d_max = *std::max_element(z.diameters.begin(), z.diameters.end());
  }
  // A range that holds next to nothing of its law (cut-offs far in a tail) is a slip, not a bed.
  if (const auto refusal = size_range_refusal(z, p)) r.fail(p + refusal->key, refusal->message);
  sp.diameter = size_moments(z).m1;
}

}  // namespace

// The plausibility of a species' smallest and largest particle, named by the key that sets each.
void check_species_plausible(const CaseReader& r, const std::string& p, const Species& sp, const DomainConfig& domain,
                             const std::optional<CaseGrid>& cell) {
  if (!sp.sized()) {
    check_particle_plausible(r, p + "diameter", sp.diameter, p + "density", sp.density, domain, cell);
    return;
  }
  const bool list = sp.size.law == SizeLaw::List;
  check_particle_plausible(r, p + (list ? "diameters" : "d_min"), sp.d_min(), p + "density", sp.density, domain, cell);
  check_particle_plausible(r, p + (list ? "diameters" : "d_max"), sp.d_max(), p + "density", sp.density, domain, cell);
}

void read_species(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  // [[species]]
  const std::size_t ns = std::max<std::size_t>(1, r.table_count("species", "particle species; default: one species"));
  c.dem.species.assign(ns, Species{});
  c.dem.material.assign(ns, ElasticMaterial{});
  std::vector<double> fraction(ns, 1.0 / static_cast<double>(ns));
  for (std::size_t s = 0; s < ns; ++s) {
    const std::string p = fmt::format("species[{}].", s);
    read_species_size(r, p, c.dem.species[s]);
    c.dem.species[s].density = r.number(p + "density", 2700.0, "kg/m^3", "particle density", R::positive());
    fraction[s] = r.number(p + "fraction", 1.0 / static_cast<double>(ns), "",
                           "number fraction of the randomly placed particles", R::between(0.0, 1.0));
    // Elastic constants: read by the Hertz and Mindlin contact laws only (contact.normal, contact.tangential).
    c.dem.material[s].youngs_modulus = r.number(p + "youngs_modulus", 7e10, "Pa", "Young's modulus of the particles "
                                                "(Hertz, Mindlin: required there)", R::positive());
    c.dem.material[s].poisson_ratio = r.number(p + "poisson_ratio", 0.25, "", "Poisson ratio of the particles",
                                               R::Range{-1.0, 0.5, true, false});
  }
  double fsum = 0.0;
  for (double f : fraction) fsum += f;
  if (std::abs(fsum - 1.0) > 1e-9) r.fail("species[0].fraction", fmt::format("the fractions add up to {}, not 1", fsum));
  c.particles.packing.species_fraction = fraction;
  // Before any rule that an implausible unit would trip in a less telling way (a time step, a packing).
  for (std::size_t s = 0; s < ns; ++s) {
    const std::string p = fmt::format("species[{}].", s);
    check_species_plausible(r, p, c.dem.species[s], c.domain, std::nullopt);
  }
}

void read_contact(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  const std::size_t ns = c.dem.n_species();
  // [contact]
  const R::Range restitution{0.0, 1.0, true, false};
  c.dem.stiffness = r.number("contact.stiffness", 800.0, "N/m", "spring stiffness k of Eqs. 2-3", R::positive());
  c.dem.tangential_stiffness_ratio = r.number("contact.tangential_stiffness_ratio", 1.0, "",
                                              "k_t / k_n (the paper uses one k)", R::positive());
  const double e_pp = r.number("contact.restitution", 0.9, "", "particle-particle restitution e (Eq. 8)", restitution);
  const double mu_pp = r.number("contact.friction", 0.3, "", "particle-particle friction mu_f (Eq. 6)", R::non_negative());
  const double e_pw = r.number("contact.wall_restitution", e_pp, "", "particle-wall restitution", restitution);
  const double mu_pw = r.number("contact.wall_friction", mu_pp, "", "particle-wall friction", R::non_negative());
  const auto [mu_r, mu_rw] = read_contact_law(r, c.dem);
  c.dem.pair.assign(ns * ns, InteractionParams{e_pp, mu_pp, mu_r});
  c.dem.wall.assign(ns, InteractionParams{e_pw, mu_pw, mu_rw});
  const std::size_t npairs = r.table_count("contact.pair", "restitution and friction of one species pair");
  for (std::size_t k = 0; k < npairs; ++k) {
    const std::string p = fmt::format("contact.pair[{}].", k);
    const auto a = r.integer(p + "species_a", 0, "first species index", R::between(0, static_cast<double>(ns - 1)));
    const auto b = r.integer(p + "species_b", 0, "second species index", R::between(0, static_cast<double>(ns - 1)));
    const InteractionParams ip{r.number(p + "restitution", e_pp, "", "restitution of the pair", restitution),
                               r.number(p + "friction", mu_pp, "", "friction of the pair", R::non_negative()),
                               r.number(p + "rolling_friction", mu_r, "", "rolling resistance coefficient of the "
                                        "pair", R::non_negative())};
    c.dem.pair[static_cast<std::size_t>(a) * ns + static_cast<std::size_t>(b)] = ip;
    c.dem.pair[static_cast<std::size_t>(b) * ns + static_cast<std::size_t>(a)] = ip;
  }
  check_contact_keys(r, c);
}

void read_dem(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  // [dem]
  const bool dt_given = r.has("dem.time_step");
  c.dem.dt = r.number("dem.time_step", default_dem_time_step(c.dem), "s",
                      "DEM time step (the paper: 2e-4 s); default: t_c / 20 of the stiffest contact, rounded down to "
                      "1, 1.25, 2, 2.5, 4, 5 or 8 x 10^n s", R::positive());
  r.describe_default("dem.time_step", "t_c / 20");
  if (!dt_given) {
    const StiffestContact sc = stiffest_contact(c.dem);
    c.notes.push_back(fmt::format("dem.time_step not given: {:g} s = t_c / {:.1f}, from t_c / {} = {:.4g} s rounded "
                                  "down (t_c = {:.4g} s, the contact duration of species {} with {})",
                                  c.dem.dt, sc.t_c / c.dem.dt, kStepsPerContact, sc.t_c / kStepsPerContact, sc.t_c,
                                  sc.a, sc.b < 0 ? std::string("a wall") : fmt::format("species {}", sc.b)));
  }
  // 0.5 d: in a dense bed the second shell of neighbours is at 1.73 d, so a wide skin adds few list entries and
  // saves rebuilds (measured in docs/performance.md: 19% less CPU for the settling bed than 0.1 d).
  c.dem.skin = r.number("dem.skin", 0.5 * c.dem.species[0].diameter, "m",
                        "Verlet skin of the neighbour list; the list is rebuilt when a particle has moved half of it",
                        R::non_negative());
  {
    // The neighbour search through periodic images (DemSolver) needs a period above two reaches.
    double d_max = 0.0;
    for (const Species& sp : c.dem.species) d_max = std::max(d_max, sp.diameter);
    const double reach = d_max + c.dem.skin;
    for (int a : {0, 2}) {
      const double L = a == 0 ? c.domain.width : c.domain.depth;
      if (c.domain.periodic[static_cast<std::size_t>(a)] && !(L > 2.0 * reach)) {
        r.fail("domain.periodic", fmt::format("a periodic axis needs a period above 2 (largest diameter + dem.skin) "
                                              "= {} m; domain.{} is {} m", 2.0 * reach, a == 0 ? "width" : "depth", L));
      }
    }
  }
  const double dt_max = dem_stable_time_step(c.dem);
  if (c.dem.dt > dt_max) {
    r.fail("dem.time_step", fmt::format("{} s is above the stability limit of the stiffest contact; the largest "
                                        "stable time step is {:.4g} s", c.dem.dt, dt_max));
  }
  if (c.dem.contact.normal == NormalModel::Hertz) {
    // The Hertz contact shortens with the impact speed (t_c ~ v^(-1/5)): judged at contact.impact_speed.
    const StiffestContact sc = stiffest_contact(c.dem);
    if (c.dem.dt > sc.t_c / kStepsPerContact) {
      c.notes.push_back(fmt::format("dem.time_step = {:g} s is above t_c / {:g} = {:.3g} s of the Hertz contact of "
                                    "{} at contact.impact_speed = {:g} m/s (t_c = {:.3g} s): too few steps per "
                                    "contact for its restitution and peak force",
                                    c.dem.dt, kStepsPerContact, sc.t_c / kStepsPerContact,
                                    sc.b < 0 ? fmt::format("species {} with a wall", sc.a)
                                             : fmt::format("species {} with species {}", sc.a, sc.b),
                                    c.dem.contact.impact_speed, sc.t_c));
    }
  }
  if (const double dt_bed = dem_packed_bed_time_step(c.dem); c.dem.dt > dt_bed && c.dem.dt <= dt_max) {
    c.notes.push_back(fmt::format("dem.time_step = {:g} s is above {:.3g} s, the limit of the spin mode of a packed "
                                  "bed with sticking contacts: sticking springs there oscillate until they slide "
                                  "(the paper case steps at 1e-4 s for this reason)", c.dem.dt, dt_bed));
  }
}

void read_insertion(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  const bool three_d = c.domain.dimension == 3;
  const std::size_t ns = c.dem.n_species();
  // [insertion]: a feed of new particles during the run.
  {
    InsertionConfig& in = c.dem.insertion;
    const std::size_t nd = three_d ? 3 : 2;
    in.rate = r.number("insertion.rate", 0.0, "1/s", "particles added per second during the run (0: none; or "
                       "insertion.mass_rate)", R::non_negative());
    const double mass_rate = r.number("insertion.mass_rate", 0.0, "kg/s", "mass added per second (instead of "
                                      "insertion.rate: rate = mass_rate / particle mass)", R::non_negative());
    if (in.rate > 0.0 && mass_rate > 0.0) {
      r.fail("insertion.mass_rate", "give insertion.rate or insertion.mass_rate, not both");
    }
    in.species = static_cast<int>(r.integer("insertion.species", 0, "species of the new particles",
                                            R::between(0, static_cast<double>(ns - 1))));
    if (mass_rate > 0.0) in.rate = mass_rate / c.dem.species[static_cast<std::size_t>(in.species)].mass();
    const std::vector<double> zero(nd, 0.0);
    const auto lo = r.numbers("insertion.region_min", zero, "m", "low corner of the box the new centres are drawn "
                              "in (x, y; z in 3D)", nd);
    const auto hi = r.numbers("insertion.region_max", zero, "m", "high corner of that box", nd);
    const auto vel = r.numbers("insertion.velocity", zero, "m/s", "velocity of each new particle", nd);
    in.t_start = r.number("insertion.start_time", 0.0, "s", "the feed starts", R::non_negative());
    const double t_end = r.number("insertion.end_time", 0.0, "s", "the feed stops (0: at the end of the run)",
                                  R::non_negative());
    in.t_end = t_end > 0.0 ? t_end : std::numeric_limits<double>::infinity();
    in.seed = static_cast<std::uint64_t>(r.integer("insertion.seed", static_cast<std::int64_t>(c.seed) + 1,
                                                   "seed of the random positions of the new particles",
                                                   R::non_negative()));
    in.attempts_per_particle = static_cast<int>(r.integer("insertion.attempts", 50, "random positions tried per "
                                                          "particle and step before it waits for the next step",
                                                          R::between(1, 1e6)));
    const Vec3 ext{c.domain.width, c.domain.height, c.domain.depth};
    for (std::size_t a = 0; a < nd; ++a) {
      in.region_lo[static_cast<int>(a)] = lo[a];
      in.region_hi[static_cast<int>(a)] = hi[a];
      in.velocity[static_cast<int>(a)] = vel[a];
      if (in.rate > 0.0 && !(lo[a] >= 0.0 && lo[a] <= hi[a] && hi[a] <= ext[static_cast<int>(a)])) {
        r.fail("insertion.region_max", fmt::format("the region [{}, {}] on axis {} must lie inside the domain [0, {}] "
                                                   "with region_min <= region_max", lo[a], hi[a], "xyz"[a],
                                                   ext[static_cast<int>(a)]));
      }
    }
  }
}

void read_particles(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  const bool three_d = c.domain.dimension == 3;
  // [particles]
  const std::string source = r.string("particles.source", "random",
                                      "random: place at random (then settle, see [settle]); file: read a CSV "
                                      "id,x,y,vx,vy,omega,species (3D: id,x,y,z,vx,vy,vz,omega_x,omega_y,omega_z,"
                                      "species), optionally a last column diameter (m) per particle",
                                      {"random", "file"});
  c.particles.source = source == "file" ? ParticleSource::File : ParticleSource::Random;
  c.particles.file = r.string("particles.file", "", "CSV file of particles (particles.source = \"file\"), "
                              "relative to the case file");
  if (c.particles.source == ParticleSource::File && c.particles.file.empty()) {
    r.fail("particles.file", "particles.source = \"file\" needs particles.file");
  }
  c.particles.packing.count = r.integer("particles.count", 22000, "number of particles placed at random", R::positive());
  c.particles.packing.x_min = 0.0;
  c.particles.packing.x_max = c.domain.width;
  c.particles.packing.y_min = 0.0;
  c.particles.packing.y_max = r.number("particles.fill_height", c.domain.height, "m",
                                       "top of the region where particles are placed at random", R::positive());
  if (c.particles.packing.y_max > c.domain.height) {
    r.fail("particles.fill_height", fmt::format("{} m is above the domain height {} m", c.particles.packing.y_max, c.domain.height));
  }
  c.particles.packing.z_min = 0.0;
  c.particles.packing.z_max = three_d ? c.domain.depth : 0.0;
  c.particles.packing.min_gap = r.number("particles.gap", 0.05 * c.dem.species[0].diameter, "m",
                                         "smallest gap between randomly placed particles", R::non_negative());
  c.particles.packing.seed = c.seed;
  if (c.particles.source == ParticleSource::Random) {
    const std::int64_t capacity = three_d ? random_placement_capacity<3>(c.dem, c.particles.packing)
                                          : random_placement_capacity<2>(c.dem, c.particles.packing);
    if (c.particles.packing.count > capacity) {
      r.fail("particles.count", fmt::format("{} particles do not fit in the {} x {}{} m placement region: at most {} "
                                            "with a gap of {} m; raise particles.fill_height or domain.height",
                                            c.particles.packing.count, c.domain.width, c.particles.packing.y_max,
                                            three_d ? fmt::format(" x {}", c.domain.depth) : std::string(), capacity,
                                            c.particles.packing.min_gap));
    }
  } else {
    // Read the file now, so that `check` reports a bad row before any run.
    const auto path = case_relative_path(r.file_name(), c.particles.file);
    const std::vector<ParticleCsvRow> rows = read_particles_csv(path, three_d ? 3 : 2);
    check_particle_rows(rows, path.string(), c.domain, c.dem.n_species());
    std::vector<std::int32_t> file_species;
    for (const ParticleCsvRow& row : rows) file_species.push_back(row.species);
    c.particles.packing.count = static_cast<std::int64_t>(file_species.size());
    // The bed is the file's: its species make up the mixture `check` and the U_mf default describe.
    std::vector<double> share(c.dem.n_species(), 0.0);
    for (const std::int32_t sp : file_species) share[static_cast<std::size_t>(sp)] += 1.0;
    for (double& f : share) f /= std::max<double>(1.0, static_cast<double>(file_species.size()));
    if (!file_species.empty()) c.particles.packing.species_fraction = share;
  }
  c.particles.layers = static_cast<int>(r.integer("particles.layers", 6, "colour layers of the initial bed (Fig. 4)",
                                                  R::between(1, 1000)));
}

void read_settle(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  // [settle]
  c.settle.enabled = r.boolean("settle.enabled", true, "settle the random placement in vacuum before t = 0") &&
                     c.particles.source != ParticleSource::File;
  c.settle.kinetic_energy_per_particle = r.number("settle.kinetic_energy_per_particle", 1e-10, "J",
                                                  "the bed is settled when the mean kinetic energy per particle falls below this",
                                                  R::positive());
  c.settle.max_time = r.number("settle.max_time", 3.0, "s", "longest settling time", R::positive());
  c.settle.cache = r.string("settle.cache", "", "CSV of the settled bed, relative to the case file: reused when "
                            "its record (<file>.record: particles, placement, contact law, time step, settling) matches "
                            "this bed, else settled anew and replaced");
  if (!c.settle.cache.empty() && c.settle.enabled && c.particles.source == ParticleSource::Random) {
    // A run reuses the cache only when its record matches this bed (dem_model.cpp); `check` says which way it goes.
    const auto cache = case_relative_path(r.file_name(), c.settle.cache);
    std::error_code ec;
    if (std::filesystem::is_regular_file(cache, ec)) {
      if (const std::string diff = settle_cache_mismatch(c, cache); !diff.empty()) {
        c.notes.push_back(fmt::format("settle.cache {} will not be reused ({}): the run settles the bed anew and "
                                      "replaces it", cache.string(), diff));
      }
    }
  }
  c.gas_enabled = r.boolean("gas.enabled", true, "couple the particles to the gas (false: DEM alone, in vacuum)");
  c.max_overlap_fraction = r.number("dem.max_overlap_fraction", 0.1, "",
                                    "the run fails when an overlap exceeds this fraction of the diameter", R::positive());
}

}  // namespace case_sections
}  // namespace fluidbed
