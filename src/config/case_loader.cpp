#include "config/case_loader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <fmt/format.h>

#include "core/error.hpp"
#include "dem/contact_law.hpp"
#include "fluid/gas_boundary.hpp"
#include "config/case_check.hpp"
#include "io/csv.hpp"
#include "config/settle_record.hpp"
#include <filesystem>
#include <fstream>
#include <sstream>

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
                "the opposite one, with no walls there (x; z too in 3D; CFD-DEM and DEM only)",
                three_d ? std::vector<std::string>{"x", "z"} : std::vector<std::string>{"x"});
  for (const std::string& axis : periodic) c.domain.periodic[axis == "x" ? 0 : 2] = true;
  if (c.model == Model::Tfm && !periodic.empty()) {
    r.fail("domain.periodic", "the two-fluid model has walls on every side in this version: periodic axes need "
                              "case.model = \"dem\"");
  }
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

void read_tfm(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  tfm::TfmConfig& t = c.tfm;
  t.domain = c.domain;
  if (std::abs(c.grid.dx - c.grid.dy) > 1e-12 * c.grid.dx) {
    r.fail("grid.cell_height", "the two-fluid model needs square cells (cell_height = cell_width)");
  }
  if (c.domain.dimension == 3 && std::abs(c.grid.dx - c.grid.dz) > 1e-12 * c.grid.dx) {
    r.fail("grid.cell_depth", "the two-fluid model needs cubic cells in 3D (cell_depth = cell_width)");
  }
  t.cell_size = c.grid.dx;
  t.rho_g = c.gas.rho_g;
  t.mu_g = c.gas.mu_g;
  t.boundary = c.gas.boundary;
  t.drag_law = c.coupling.drag_law;
  t.pressure_solver = c.gas.pressure_solver;
  t.drag_switch = c.coupling.drag_switch;
  t.d_p = r.number("tfm.particle_diameter", 0.004, "m", "particle diameter d_p", R::positive());
  t.rho_s = r.number("tfm.particle_density", 2700.0, "kg/m^3", "particle density rho_s", R::positive());
  check_particle_plausible(r, "tfm.particle_diameter", t.d_p, "tfm.particle_density", t.rho_s, c.domain, c.grid);
  if (!(t.rho_s > t.rho_g)) {
    r.fail("tfm.particle_density", fmt::format("solids of {} kg/m^3 are not heavier than the gas ({} kg/m^3): they "
                                               "do not form a bed", t.rho_s, t.rho_g));
  }
  if (c.gas.viscous != ViscousStress::Off) {
    r.fail("gas.viscous_stress", "the two-fluid model's gas has no viscous stress (Eq. 12 of the paper); only \"off\"");
  }
  t.e = r.number("tfm.restitution", 0.9, "", "restitution e of the kinetic theory (Eqs. 23-25)", R::Range{0.0, 1.0, true, false});
  t.phi_deg = r.number("tfm.friction_angle", 40.0, "deg", "angle of internal friction phi (Eq. 21)", R::Range{0.0, 90.0, true, true});
  t.eps_initial = r.number("tfm.eps_initial", 0.431, "", "voidage of the initial bed (Table 1)", R::Range{0.0, 1.0, true, true});
  t.packed_height = r.number("tfm.packed_height", 0.54, "m", "height of the initial bed", R::positive());
  if (t.packed_height > c.domain.height) r.fail("tfm.packed_height", "the bed is taller than the domain");
  t.eps_star = r.number("tfm.eps_star", 0.43, "", "compaction voidage eps* (Eq. 20)", R::Range{0.0, 1.0, true, true});
  const std::string rh = r.string("tfm.rheology", "kinetic_theory", "solids rheology: kinetic theory with the "
                                  "frictional regime (Eqs. 21-26), constant viscosity, or inviscid (both with Eq. 20)",
                                  {"kinetic_theory", "constant_viscosity", "inviscid"});
  t.rheology = rh == "inviscid" ? tfm::SolidsRheology::Inviscid
               : rh == "constant_viscosity" ? tfm::SolidsRheology::ConstantViscosity : tfm::SolidsRheology::KineticTheory;
  if (t.rheology == tfm::SolidsRheology::KineticTheory && t.e >= 1.0) {
    r.fail("tfm.restitution", "e = 1 has no granular temperature in the kinetic theory: its algebraic balance of "
                              "shear production against collisional dissipation (~ 1 - e^2, Eqs. 25-26) has no "
                              "finite solution for elastic particles; use e < 1 (the paper: 0.9)");
  }
  if (t.rheology == tfm::SolidsRheology::KineticTheory && t.e > 0.95) {
    c.notes.push_back(fmt::format("tfm.restitution = {:g} is nearly elastic: the collisional dissipation (~ 1 - e^2) is "
                                  "small and the granular temperature may run away (the paper's case runs at 0.97 "
                                  "and stops at 0.12 s at 0.99); the run stops with a diagnosis if it does", t.e));
  }
  t.mu_s_constant = r.number("tfm.solids_viscosity", 0.5, "Pa s", "solids viscosity of the constant-viscosity rheology "
                             "(the paper gives no value)", R::positive());
  t.mu_s_max = r.number("tfm.max_solids_viscosity", 100.0, "Pa s", "cap on the frictional viscosity", R::positive());
  t.modulus.a = r.number("tfm.modulus_a", 1.0, "Pa", "A of G = A exp(B (eps* - eps)) (Eq. 20)", R::positive());
  t.modulus.b = r.number("tfm.modulus_b", 600.0, "", "B of G = A exp(B (eps* - eps)) (Eq. 20)", R::positive());
  const std::string lim = r.string("tfm.limiter", "superbee", "flux limiter of the convection (the paper: superbee)",
                                   {"superbee", "van_leer", "minmod", "upwind"});
  t.limiter = lim == "upwind" ? tfm::Limiter::Upwind
              : lim == "minmod" ? tfm::Limiter::Minmod : lim == "van_leer" ? tfm::Limiter::VanLeer : tfm::Limiter::Superbee;
  t.cfl = r.number("tfm.cfl", 0.5, "", "Courant number of the adaptive time step", R::Range{0.0, 1.0, true, false});
  t.dt_max = r.number("tfm.dt_max", 1e-3, "s", "largest time step", R::positive());
  t.dt_min = r.number("tfm.dt_min", 1e-8, "s", "the run fails below this time step", R::positive());
  t.max_compaction = r.number("tfm.max_compaction", tfm::default_max_compaction(t.rheology), "",
                              "compaction below eps* that the packing limiter allows, eps >= eps* - max_compaction "
                              "exactly (default 0.015 with kinetic_theory, 0.03 with the Eq. 20 rheologies)",
                              R::Range{0.0, t.eps_star, false, true});
  t.solids_no_slip_walls = r.boolean("tfm.solids_no_slip_walls", false, "solids stick to the side walls");
  t.eps_noise = r.number("tfm.eps_noise", 0.0, "", "amplitude of the seeded (case.seed) initial voidage noise of the "
                         "bed: eps + a (2u - 1), kept in [eps*, 1]", R::Range{0.0, 0.5, false, true});
  t.seed = c.seed;
  try {
    tfm::validate(t);
  } catch (const Error& e) {
    throw_input_error(fmt::format("{}: [tfm]: {}", r.file_name(), e.what()));
  }
}

// A region's velocity schedule, keys under prefix p ("inlet." or "inlet.jet[k]."): inlet.schedule picks the kind;
// u0_key is the region's velocity key (a table replaces it). The background's ramp keys are the start-up ramp's.
InletSchedule read_schedule(CaseReader& r, const std::string& p, const std::string& u0_key, double ramp_start_default,
                            bool background) {
  using R = CaseReader;
  InletSchedule s;
  const std::string kind = r.string(p + "schedule", "constant", "superficial velocity in time: constant, ramp "
                                    "(linear), table (linear between (t, U) pairs), sine (U0 + A sin(2 pi f t + phase)) "
                                    "or square (U0 + A over the duty fraction of each period)",
                                    {"constant", "ramp", "table", "sine", "square"});
  const auto refuse = [&](std::initializer_list<const char*> keys, const std::string& why) {
    for (const char* k : keys)
      if (r.has(p + k)) r.fail(p + k, why);
  };
  if (kind == "constant") {
    if (!background) refuse({"ramp_from", "ramp_start", "ramp_time"}, "ramp keys need schedule = \"ramp\"");
  } else if (kind == "ramp") {
    s.kind = ScheduleKind::Ramp;
    if (!background) {
      s.ramp_from = r.number(p + "ramp_from", 0.0, "m/s", "velocity until ramp_start (schedule = \"ramp\")");
      s.ramp_time = r.required_number(p + "ramp_time", "s", "duration of the linear ramp to the region's velocity "
                                      "(schedule = \"ramp\")", R::positive());
    }
    s.ramp_start = r.number(p + "ramp_start", ramp_start_default, "s", "the ramp begins (schedule = \"ramp\")");
    if (!background) r.describe_default(p + "ramp_start", "the jet's start");
  } else {
    refuse({"ramp_start"}, "ramp_start needs schedule = \"ramp\"");
    if (!background) refuse({"ramp_from", "ramp_time"}, "ramp keys need schedule = \"ramp\"");
  }
  if (kind == "table") {
    s.kind = ScheduleKind::Table;
    if (r.has(u0_key)) r.fail(u0_key, "a table schedule gives the velocities itself (table_velocities or table_file)");
    const std::string file = r.string(p + "table_file", "", "CSV of the table (schedule = \"table\"): one header "
                                      "line, then time_s,velocity_m_s rows; relative to the case file");
    if (!file.empty()) {
      if (r.has(p + "table_times") || r.has(p + "table_velocities")) {
        r.fail(p + "table_file", "give the table inline (table_times, table_velocities) or as a file, not both");
      }
      const auto path = case_relative_path(r.file_name(), file);
      std::ifstream in(path);
      if (!in) r.fail(p + "table_file", fmt::format("cannot read {}", path.string()));
      std::string line;
      std::getline(in, line);
      for (int row = 2; std::getline(in, line); ++row) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream ls(line);
        double t = 0.0, u = 0.0;
        char comma = 0;
        if (!(ls >> t >> comma >> u) || comma != ',') {
          r.fail(p + "table_file", fmt::format("{} line {}: expected time_s,velocity_m_s", path.string(), row));
        }
        s.times.push_back(t);
        s.velocities.push_back(u);
      }
    } else {
      s.times = r.numbers(p + "table_times", {}, "s", "times of the table (schedule = \"table\"), increasing");
      s.velocities = r.numbers(p + "table_velocities", {}, "m/s", "velocities at table_times (schedule = \"table\")");
    }
    if (s.times.empty() || s.times.size() != s.velocities.size()) {
      r.fail(file.empty() ? p + "table_velocities" : p + "table_file",
             fmt::format("a table needs as many velocities as times, at least one (got {} and {})", s.times.size(),
                         s.velocities.size()));
    }
    for (std::size_t k = 1; k < s.times.size(); ++k) {
      if (!(s.times[k] > s.times[k - 1])) {
        r.fail(file.empty() ? p + "table_times" : p + "table_file", "the table's times must increase strictly");
      }
    }
  } else {
    refuse({"table_file", "table_times", "table_velocities"}, "table keys need schedule = \"table\"");
  }
  if (kind == "sine" || kind == "square") {
    s.kind = kind == "sine" ? ScheduleKind::Sine : ScheduleKind::Square;
    s.amplitude = r.number(p + "amplitude", 0.0, "m/s", "pulsation amplitude A (schedule = \"sine\" or \"square\")");
    s.frequency = r.required_number(p + "frequency", "Hz", "pulsation frequency f (schedule = \"sine\" or "
                                    "\"square\")", R::positive());
    s.phase = r.number(p + "phase", 0.0, "rad", "pulsation phase (schedule = \"sine\" or \"square\")");
    if (s.kind == ScheduleKind::Square) {
      s.duty = r.number(p + "duty", 0.5, "", "the on fraction of each period (schedule = \"square\")",
                        R::Range{0.0, 1.0, true, true});
    } else {
      refuse({"duty"}, "duty needs schedule = \"square\"");
    }
  } else {
    refuse({"amplitude", "frequency", "phase", "duty"}, "pulsation keys need schedule = \"sine\" or \"square\"");
  }
  return s;
}

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

// The grid keys as given (the cells' sizes before the grid rounds them to whole cells) and the number of
// inlet.jet tables: what the later sections' defaults derive from.
struct GasKeys {
  double dx = 0.0, dy = 0.0, dz = 0.0;  ///< m
  std::size_t jet_tables = 0;
};

// [grid]: the cells of the gas, the voidage and the two-fluid model.
void read_grid(CaseReader& r, CaseConfig& c, GasKeys& k) {
  using R = CaseReader;
  const bool needs_gas = c.model == Model::Tfm || c.gas_enabled;
  // [grid]: one staggered grid for the gas, the voidage and the two-fluid model.
  const bool three_d = c.domain.dimension == 3;
  // DEM alone without a [grid]: cells near the paper's 0.02 m that divide the domain, so that a box of any size
  // needs no grid it does not use (the cells then serve turning the gas on with --set only).
  const bool grid_given = r.has("grid.cell_width") || r.has("grid.cell_height") || r.has("grid.cell_depth");
  const bool fitted = !needs_gas && !grid_given;
  const auto fit = [](double length, double min_cells) { return length / std::max(min_cells, std::round(length / 0.02)); };
  const double dx = r.number("grid.cell_width", fitted ? fit(c.domain.width, 2.0) : 0.02, "m",
                             "gas cell width (the paper: 0.02 m)", R::positive());
  r.describe_default("grid.cell_width", "0.02; gas off and no [grid]: the nearest that divides the width");
  const double dy = r.number("grid.cell_height", fitted ? fit(c.domain.height, 2.0) : dx, "m", "gas cell height",
                             R::positive());
  double dz = 0.0;
  if (three_d) {
    dz = r.number("grid.cell_depth", fitted ? fit(c.domain.depth, 1.0) : std::min(dx, c.domain.depth), "m",
                  "gas cell depth (z); 3D only; default: grid.cell_width, or the whole depth when that is less",
                  R::positive());
    r.describe_default("grid.cell_depth", "min(cell_width, domain.depth)");
  } else if (r.has("grid.cell_depth")) {
    r.fail("grid.cell_depth", "a 2D case (case.dimension = 2) has one layer of cells; set case.dimension = 3 for "
                              "cells across a depth");
  }
  const double fx = c.domain.width / dx, fy = c.domain.height / dy, fz = three_d ? c.domain.depth / dz : 1.0;
  if (fx * fy * fz > 1e8) {  // 40 fields of 8 bytes per cell (the TFM): 32 GB
    r.fail("grid.cell_width", three_d ? fmt::format("cells of {} x {} x {} m make {:.3g} cells of the {} x {} x {} m "
                                                    "domain; at most 1e8 fit in memory", dx, dy, dz, fx * fy * fz,
                                                    c.domain.width, c.domain.height, c.domain.depth)
                                      : fmt::format("cells of {} x {} m make {:.3g} cells of the {} x {} m domain; at "
                                                    "most 1e8 fit in memory", dx, dy, fx * fy, c.domain.width,
                                                    c.domain.height));
  }
  if (std::abs(fx - std::round(fx)) > 1e-9 * fx) {
    r.fail("grid.cell_width", fmt::format("{} m does not divide the domain width {} m into whole cells", dx, c.domain.width));
  }
  if (std::abs(fy - std::round(fy)) > 1e-9 * fy) {
    r.fail("grid.cell_height", fmt::format("{} m does not divide the domain height {} m into whole cells", dy, c.domain.height));
  }
  if (three_d && std::abs(fz - std::round(fz)) > 1e-9 * fz) {
    r.fail("grid.cell_depth", fmt::format("{} m does not divide the domain depth {} m into whole cells", dz, c.domain.depth));
  }
  c.grid.dimension = c.domain.dimension;
  c.grid.nx = static_cast<int>(std::lround(fx));
  c.grid.ny = static_cast<int>(std::lround(fy));
  c.grid.dx = c.domain.width / c.grid.nx;
  c.grid.dy = c.domain.height / c.grid.ny;
  c.grid.nz = three_d ? static_cast<int>(std::lround(fz)) : 1;
  c.grid.dz = three_d ? c.domain.depth / c.grid.nz : 0.0;
  // The gas solver's rule (GasSolver refuses fewer cells), here so that `check` refuses what `run` would, gas or not.
  // Across the depth one layer is allowed: a slab one cell deep between front and back walls.
  const std::string who = needs_gas ? "the gas needs" : "the grid needs (the gas is off, but --set gas.enabled=true "
                                                         "would use it)";
  if (c.grid.nx < 2) {
    r.fail("grid.cell_width", fmt::format("{} m leaves {} cell across the domain width {} m; {} at least 2",
                                          dx, c.grid.nx, c.domain.width, who));
  }
  if (c.grid.ny < 2) {
    r.fail("grid.cell_height", fmt::format("{} m leaves {} cell over the domain height {} m; {} at least 2",
                                           dy, c.grid.ny, c.domain.height, who));
  }
  k.dx = dx;
  k.dy = dy;
  k.dz = dz;
}

void read_gas_phase(CaseReader& r, CaseConfig& c, const GasKeys& k) {
  using R = CaseReader;
  const double dx = k.dx;
  GasConfig& g = c.gas;
  g.rho_g = r.number("gas.density", 1.205, "kg/m^3", "gas density rho_g", R::positive());
  g.mu_g = r.number("gas.viscosity", 1.8e-5, "Pa s", "gas viscosity mu_g", R::positive());
  check_gas_plausible(r, g, c.notes);
  if (c.model == Model::Dem && c.gas_enabled) {
    for (std::size_t s = 0; s < c.dem.n_species(); ++s) {
      const std::string p = fmt::format("species[{}].", s);
      check_species_plausible(r, p, c.dem.species[s], c.domain, c.grid);
      if (!(c.dem.species[s].density > g.rho_g)) {
        r.fail(p + "density", fmt::format("particles of {} kg/m^3 are not heavier than the gas ({} kg/m^3): they do "
                                          "not form a bed", c.dem.species[s].density, g.rho_g));
      }
    }
  }
  g.gravity = c.domain.gravity;
  const std::string visc = r.string("gas.viscous_stress", "off", "gas viscous stress (off in the paper's Eq. 12): "
                                    "laplacian div(eps mu grad u), or full div(eps mu (grad u + grad u^T))",
                                    {"off", "laplacian", "full"});
  g.viscous = visc == "off" ? ViscousStress::Off : visc == "full" ? ViscousStress::Full : ViscousStress::Laplacian;
  const std::string conv = r.string("gas.convection", "van_leer", "bounded convection scheme of the gas momentum",
                                    {"upwind", "van_leer", "minmod"});
  g.convection = conv == "upwind" ? ConvectionScheme::Upwind
                 : conv == "minmod" ? ConvectionScheme::Minmod : ConvectionScheme::VanLeer;
  const std::string pc = r.string("gas.pressure_coupling", "simplec", "pressure-velocity coupling", {"simple", "simplec"});
  g.coupling = pc == "simple" ? PressureCoupling::Simple : PressureCoupling::Simplec;
  const std::string ps = r.string("gas.pressure_solver", "eigen", "pressure-correction solver: eigen (sparse Cholesky), "
                                  "eigen-cg (incomplete-Cholesky CG) or hypre-pfmg (structured multigrid CG; needs a build "
                                  "with hypre)", {"eigen", "eigen-cg", "hypre-pfmg"});
  g.pressure_solver = ps == "hypre-pfmg" ? PressureBackend::HyprePfmg
                      : ps == "eigen-cg" ? PressureBackend::EigenCg : PressureBackend::Eigen;
  // The periodic gas (GasSolver's rules, here so that `check` refuses what `run` would).
  if (c.model == Model::Dem && c.gas_enabled && c.domain.any_periodic()) {
    if (g.pressure_solver == PressureBackend::HyprePfmg) {
      r.fail("gas.pressure_solver", "hypre-pfmg does not take periodic axes (domain.periodic) in this version: use "
                                    "eigen or eigen-cg");
    }
    if (c.domain.periodic[0] && c.grid.nx < 3) {
      r.fail("grid.cell_width", fmt::format("{} m leaves {} cells across the periodic width {} m; a periodic axis "
                                            "needs at least 3", dx, c.grid.nx, c.domain.width));
    }
    if (c.domain.periodic[2] && c.grid.nz < 3) {
      r.fail("grid.cell_depth", fmt::format("{} cells across the periodic depth {} m; a periodic axis needs at "
                                            "least 3", c.grid.nz, c.domain.depth));
    }
  }
  g.relax_velocity = r.number("gas.relax_velocity", 0.8, "", "momentum under-relaxation", R::Range{0.0, 1.0, true, false});
  g.relax_pressure = r.number("gas.relax_pressure", 1.0, "", "pressure under-relaxation", R::Range{0.0, 1.0, true, false});
  g.max_simple_iterations = static_cast<int>(r.integer("gas.max_iterations", 200, "SIMPLE iterations per gas step at most",
                                                       R::between(1, 100000)));
  g.mass_tolerance = r.number("gas.mass_tolerance", 1e-8, "", "SIMPLE stops when the normalised mass residual is below this",
                              R::positive());
  g.momentum_tolerance = r.number("gas.momentum_tolerance", 1e-8, "", "SIMPLE also needs the normalised momentum "
                                  "residual below this", R::positive());
  g.momentum_solver_tolerance = r.number("gas.momentum_solver_tolerance", 1e-4, "", "each momentum solve reduces "
                                         "its residual by this factor", R::Range{0.0, 1.0, true, true});
  g.pressure_solver_tolerance = r.number("gas.pressure_solver_tolerance", 1e-3, "", "relative residual of the "
                                         "pressure-correction solves after a step's first", R::Range{0.0, 1.0, true, true});
  const std::string side = r.string("gas.side_walls", "no_slip", "tangential gas condition on the side walls", {"slip", "no_slip"});
  g.boundary.side_walls = side == "slip" ? WallKind::Slip : WallKind::NoSlip;
  if (c.domain.dimension == 3) {
    const std::string fb = r.string("gas.front_back_walls", side, "tangential gas condition on the front and back "
                                    "walls of a 3D bed (default: that of gas.side_walls)", {"slip", "no_slip"});
    g.boundary.front_back_walls = fb == "slip" ? WallKind::Slip : WallKind::NoSlip;
  } else if (r.has("gas.front_back_walls")) {
    r.fail("gas.front_back_walls", "a 2D case has no front and back walls; set case.dimension = 3");
  }
  const std::string top = r.string("gas.top", "outlet", "top boundary: pressure outlet or wall", {"outlet", "wall"});
  g.boundary.top = top == "outlet" ? TopBoundary::PressureOutlet : TopBoundary::Wall;
  g.boundary.top_pressure = r.number("gas.top_pressure", 0.0, "Pa", "gauge pressure at the outlet");
}

void read_plates(CaseReader& r, CaseConfig& c);

void read_inlet(CaseReader& r, CaseConfig& c, GasKeys& keys) {
  using R = CaseReader;
  const bool three_d = c.domain.dimension == 3;
  const double dx = keys.dx, dz = keys.dz;
  GasConfig& g = c.gas;
  // [inlet]
  g.boundary.inlet_velocity = r.number("inlet.velocity", 1.8, "m/s",
                                       "superficial gas velocity through the whole bottom (the paper: U_mf = 1.8 m/s)");
  g.boundary.ramp_time = r.number("inlet.ramp_time", 0.0, "s", "the background inflow ramps linearly from "
                                  "inlet.ramp_from to inlet.velocity over this time (0: no ramp)", R::non_negative());
  g.boundary.ramp_from = r.number("inlet.ramp_from", 0.0, "m/s", "background inflow at t = 0 when inlet.ramp_time > 0");
  g.boundary.schedule = read_schedule(r, "inlet.", "inlet.velocity", 0.0, true);
  if (g.boundary.schedule.kind == ScheduleKind::Ramp) {
    // The start-up ramp keys, from ramp_start: a ramp that starts at 0 is the start-up ramp itself.
    g.boundary.schedule.ramp_from = g.boundary.ramp_from;
    g.boundary.schedule.ramp_time = g.boundary.ramp_time;
    if (!(g.boundary.ramp_time > 0.0)) r.fail("inlet.ramp_time", "schedule = \"ramp\" needs inlet.ramp_time > 0");
  } else if (g.boundary.schedule.kind != ScheduleKind::Constant) {
    for (const char* k : {"inlet.ramp_from", "inlet.ramp_time"}) {
      if (r.has(k)) r.fail(k, "the start-up ramp is for a constant background; a table schedule can ramp too");
    }
  }
  g.boundary.inlet_noise = r.number("inlet.noise", 0.0, "", "distributor non-uniformity: the background inflow of "
                                    "bottom cell i is scaled by 1 + noise (2u_i - 1), u_i seeded by case.seed, fixed in "
                                    "time, total inflow unchanged", R::Range{0.0, 1.0, false, true});
  g.boundary.noise_seed = c.seed;
  const std::size_t nj = r.table_count("inlet.jet", "jets through the bottom, replacing the background inflow");
  keys.jet_tables = nj;
  g.boundary.jets.clear();
  for (std::size_t k = 0; k < nj; ++k) {
    const std::string p = fmt::format("inlet.jet[{}].", k);
    InletJet j;
    if (three_d) {
      const std::string shape = r.string(p + "shape", "slot", "region of the bottom face (3D only): slot (across the "
                                         "whole depth), rectangle (width x depth) or disc (diameter)",
                                         {"slot", "rectangle", "disc"});
      j.shape = shape == "disc" ? InletShape::Disc : shape == "rectangle" ? InletShape::Rectangle : InletShape::Slot;
    } else {
      for (const char* k : {"shape", "centre_z", "depth", "diameter"}) {
        if (r.has(p + k)) {
          r.fail(p + k, "a 2D case's jet is a slot of the bottom edge (centre, width); shapes across a depth need "
                        "case.dimension = 3");
        }
      }
    }
    j.x_centre = r.number(p + "centre", c.domain.width / 2, "m", "x of the jet centre");
    if (j.shape == InletShape::Disc) {
      if (r.has(p + "width")) r.fail(p + "width", "a disc jet is given by its diameter, not a width");
      j.width = r.number(p + "diameter", std::max(dx, dz), "m", "diameter of a disc jet (3D)", R::positive());
      r.describe_default(p + "diameter", "max(cell_width, cell_depth)");
    } else {
      if (r.has(p + "diameter")) r.fail(p + "diameter", "only a disc jet has a diameter; a slot or a rectangle has a width");
      j.width = r.number(p + "width", dx, "m", "jet width (x extent of a slot or a rectangle)", R::positive());
    }
    if (j.shape == InletShape::Slot) {
      for (const char* k : {"centre_z", "depth"}) {
        if (r.has(p + k)) r.fail(p + k, "a slot spans the whole depth; use shape = \"rectangle\" for a part of it");
      }
      j.z_centre = 0.5 * c.domain.depth;
      j.depth = c.domain.depth;
    } else {
      j.z_centre = r.number(p + "centre_z", 0.5 * c.domain.depth, "m", "z of the centre of a rectangle or disc jet (3D)");
      r.describe_default(p + "centre_z", "domain.depth / 2");
      if (j.shape == InletShape::Rectangle) {
        j.depth = r.number(p + "depth", dz, "m", "z extent of a rectangle jet (3D)", R::positive());
        r.describe_default(p + "depth", "grid.cell_depth");
      } else {
        if (r.has(p + "depth")) r.fail(p + "depth", "a disc jet is given by its diameter; only a rectangle has a depth");
        j.depth = j.width;
      }
    }
    j.velocity = r.number(p + "velocity", 30.0, "m/s", "superficial gas velocity through the jet");
    j.t_start = r.number(p + "start", 0.0, "s", "the jet opens at this time", R::non_negative());
    j.t_end = r.number(p + "end", 0.4, "s", "the jet closes at this time", R::non_negative());
    j.schedule = read_schedule(r, p, p + "velocity", j.t_start, false);
    // The jet is a region of the bottom face: inside it, and wide enough for the grid to resolve.
    if (j.x_centre - 0.5 * j.width < -1e-12 || j.x_centre + 0.5 * j.width > c.domain.width + 1e-12) {
      r.fail(p + "centre", fmt::format("the jet [{}, {}] m is not inside the bottom [0, {}] m",
                                       j.x_centre - 0.5 * j.width, j.x_centre + 0.5 * j.width, c.domain.width));
    }
    if (j.shape != InletShape::Slot &&
        (j.z_centre - 0.5 * j.depth < -1e-12 || j.z_centre + 0.5 * j.depth > c.domain.depth + 1e-12)) {
      r.fail(p + "centre_z", fmt::format("the jet's z range [{}, {}] m is not inside the bottom's depth [0, {}] m",
                                         j.z_centre - 0.5 * j.depth, j.z_centre + 0.5 * j.depth, c.domain.depth));
    }
    const std::string wkey = j.shape == InletShape::Disc ? p + "diameter" : p + "width";
    if (j.width < dx * (1.0 - 1e-9)) {
      r.fail(wkey, fmt::format("{} m is narrower than a gas cell ({} m): the grid cannot resolve it", j.width, dx));
    }
    if (j.shape != InletShape::Slot && j.depth < c.grid.dz * (1.0 - 1e-9)) {
      r.fail(j.shape == InletShape::Disc ? wkey : p + "depth",
             fmt::format("{} m is shallower than a gas cell's depth ({} m): the grid cannot resolve it", j.depth,
                         c.grid.dz));
    }
    if (j.t_end < j.t_start) r.fail(p + "end", "the jet closes before it opens");
    g.boundary.jets.push_back(j);
  }
  read_plates(r, c);
}

// [[inlet.plate]]: blocks of equal holes, each hole a jet appended after the inlet.jet ones.
void read_plates(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  const bool three_d = c.domain.dimension == 3;
  GasConfig& g = c.gas;
  const std::size_t np = r.table_count("inlet.plate", "perforated distributor plates: blocks of equal holes (2D slots, "
                                       "3D discs), each hole a jet");
  for (std::size_t k = 0; k < np; ++k) {
    const std::string p = fmt::format("inlet.plate[{}].", k);
    PerforatedPlate pl;
    pl.n_x = static_cast<int>(r.integer(p + "holes", 1, "holes per row (along x)", R::between(1, 100000)));
    if (three_d) {
      pl.n_z = static_cast<int>(r.integer(p + "rows", 1, "rows of holes (along z, 3D)", R::between(1, 100000)));
      pl.hole = r.required_number(p + "hole_diameter", "m", "diameter of each disc hole (3D)", R::positive());
      const std::string lay = r.string(p + "layout", "square", "hole pitch (3D): square or triangular (equilateral, "
                                       "odd rows shifted by half a pitch)", {"square", "triangular"});
      pl.layout = lay == "triangular" ? HolePitch::Triangular : HolePitch::Square;
      pl.z_centre = r.number(p + "centre_z", 0.5 * c.domain.depth, "m", "z of the block's centre (3D)");
      r.describe_default(p + "centre_z", "domain.depth / 2");
    } else {
      for (const char* key : {"rows", "hole_diameter", "layout", "centre_z"}) {
        if (r.has(p + key)) r.fail(p + key, "a 2D plate is a row of slots (holes, hole_width, pitch); set case.dimension = 3");
      }
      pl.hole = r.required_number(p + "hole_width", "m", "width of each slot (2D)", R::positive());
    }
    if (three_d && r.has(p + "hole_width")) r.fail(p + "hole_width", "a 3D plate's holes are discs: hole_diameter");
    pl.pitch = r.required_number(p + "pitch", "m", "centre-to-centre distance of neighbouring holes", R::positive());
    if (pl.pitch < pl.hole) r.fail(p + "pitch", fmt::format("holes of {} m overlap at a pitch of {} m", pl.hole, pl.pitch));
    pl.x_centre = r.number(p + "centre", c.domain.width / 2, "m", "x of the block's centre");
    r.describe_default(p + "centre", "domain.width / 2");
    pl.velocity = r.number(p + "velocity", 10.0, "m/s", "superficial velocity through each hole");
    pl.t_start = r.number(p + "start", 0.0, "s", "the holes open at this time", R::non_negative());
    pl.t_end = r.number(p + "end", 1e9, "s", "the holes close at this time", R::non_negative());
    if (pl.t_end < pl.t_start) r.fail(p + "end", "the plate closes before it opens");
    pl.schedule = read_schedule(r, p, p + "velocity", pl.t_start, false);
    for (const InletJet& h : perforated_plate_holes(pl, three_d ? 3 : 2)) {
      // Holes narrower than a cell are allowed: the face overlap keeps each hole's volume flux exact.
      const double r_x = 0.5 * h.width;
      const double r_z = 0.5 * h.depth;
      if (h.x_centre - r_x < -1e-12 || h.x_centre + r_x > c.domain.width + 1e-12 ||
          (three_d && (h.z_centre - r_z < -1e-12 || h.z_centre + r_z > c.domain.depth + 1e-12))) {
        r.fail(p + "pitch", fmt::format("the hole centred at x = {} m{} is not inside the bottom", h.x_centre,
                                        three_d ? fmt::format(", z = {} m", h.z_centre) : std::string()));
      }
      if (!three_d) {
        InletJet slot = h;
        slot.z_centre = 0.5 * c.domain.depth;
        slot.depth = c.domain.depth;
        g.boundary.jets.push_back(slot);
      } else {
        g.boundary.jets.push_back(h);
      }
    }
  }
}

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
                                      "height minus at height_top) or bed_height (the highest height where the "
                                      "cross-section mean solids fraction falls to solids_fraction)",
                                      {"point", "plane", "pressure_drop", "bed_height"});
    s.kind = kind == "plane"           ? ProbeKind::Plane
             : kind == "pressure_drop" ? ProbeKind::PressureDrop
             : kind == "bed_height"    ? ProbeKind::BedHeight
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
