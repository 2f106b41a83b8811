#include "config/settle_record.hpp"

#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace fluidbed {

std::string settled_bed_record(const CaseConfig& c) {
  const DemConfig& d = c.dem;
  const PackingConfig& pk = c.particles.packing;
  std::string s;
  auto line = [&](const std::string& key, double v) { s += fmt::format("{} = {:.17g}\n", key, v); };
  // What the code's contact law was when the bed settled: a bed settled by an earlier law is not this one.
  // 2: the friction torque's lever arm to the contact point (r - delta/2), issue 12.
  line("contact law revision", 2.0);
  line("case.dimension", static_cast<double>(c.domain.dimension));
  line("particles.count", static_cast<double>(pk.count));
  line("case.seed", static_cast<double>(pk.seed));
  line("particles.gap", pk.min_gap);
  line("placement.x_min", pk.x_min);
  line("placement.x_max", pk.x_max);
  line("placement.y_min", pk.y_min);
  line("placement.y_max", pk.y_max);
  for (std::size_t k = 0; k < pk.species_fraction.size(); ++k) line(fmt::format("species[{}].fraction", k), pk.species_fraction[k]);
  for (std::size_t k = 0; k < d.species.size(); ++k) {
    line(fmt::format("species[{}].diameter", k), d.species[k].diameter);
    line(fmt::format("species[{}].density", k), d.species[k].density);
    // A size distribution, where there is one (a bed of fixed sizes keeps the record it had before distributions).
    const SizeDistribution& z = d.species[k].size;
    if (z.law == SizeLaw::Fixed) continue;
    s += fmt::format("species[{}].size_distribution = {}\n", k, size_law_name(z.law));
    line(fmt::format("species[{}].d_min", k), z.d_min);
    line(fmt::format("species[{}].d_max", k), z.d_max);
    if (z.law == SizeLaw::Normal) {
      line(fmt::format("species[{}].mean", k), z.mean);
      line(fmt::format("species[{}].std", k), z.std);
    }
    if (z.law == SizeLaw::LogNormal) {
      line(fmt::format("species[{}].median", k), z.median);
      line(fmt::format("species[{}].sigma", k), z.sigma);
    }
    for (std::size_t j = 0; j < z.diameters.size(); ++j) {
      line(fmt::format("species[{}].diameters[{}]", k, j), z.diameters[j]);
      line(fmt::format("species[{}].number_fractions[{}]", k, j), z.fractions[j]);
    }
  }
  line("contact.stiffness", d.stiffness);
  line("contact.tangential_stiffness_ratio", d.tangential_stiffness_ratio);
  for (std::size_t k = 0; k < d.pair.size(); ++k) {
    line(fmt::format("contact.pair({},{}).restitution", k / d.species.size(), k % d.species.size()), d.pair[k].restitution);
    line(fmt::format("contact.pair({},{}).friction", k / d.species.size(), k % d.species.size()), d.pair[k].friction);
  }
  for (std::size_t k = 0; k < d.wall.size(); ++k) {
    line(fmt::format("contact.wall({}).restitution", k), d.wall[k].restitution);
    line(fmt::format("contact.wall({}).friction", k), d.wall[k].friction);
  }
  // The composed law's parts and parameters, only where it is not the paper's (so that the paper's records, and
  // the beds cached with them, stay valid).
  const ContactModelConfig& m = d.contact;
  if (m.normal != NormalModel::Linear || m.damping != DampingModel::Paper || m.tangential != TangentialModel::Linear ||
      m.rolling != RollingModel::None) {
    s += fmt::format("contact.normal = {}\ncontact.damping = {}\ncontact.tangential = {}\ncontact.rolling = {}\n",
                     to_string(m.normal), to_string(m.damping), to_string(m.tangential), to_string(m.rolling));
    line("contact.rolling_damping", m.rolling_damping);
    line("contact.wall_youngs_modulus", m.wall_material.youngs_modulus);
    line("contact.wall_poisson_ratio", m.wall_material.poisson_ratio);
    for (std::size_t k = 0; k < d.material.size(); ++k) {
      line(fmt::format("species[{}].youngs_modulus", k), d.material[k].youngs_modulus);
      line(fmt::format("species[{}].poisson_ratio", k), d.material[k].poisson_ratio);
    }
    for (std::size_t k = 0; k < d.pair.size(); ++k) {
      line(fmt::format("contact.pair({},{}).rolling_friction", k / d.species.size(), k % d.species.size()),
           d.pair[k].rolling_friction);
    }
    for (std::size_t k = 0; k < d.wall.size(); ++k) line(fmt::format("contact.wall({}).rolling_friction", k), d.wall[k].rolling_friction);
  }
  line("domain.width", d.domain.width);
  line("domain.gravity.x", d.domain.gravity.x);
  line("domain.gravity.y", d.domain.gravity.y);
  if (d.walls.top) line("domain.height (top wall)", d.domain.height);
  // A bed settled across a periodic side is not one settled against walls (only written when periodic, so the
  // records of the closed beds stay as they were).
  if (d.domain.periodic[0]) line("domain.periodic.x", 1.0);
  if (d.domain.periodic[2]) line("domain.periodic.z", 1.0);
  // A 3D bed also depends on its depth and its placement across it.
  if (d.domain.dimension == 3) {
    line("domain.depth", d.domain.depth);
    line("domain.gravity.z", d.domain.gravity.z);
    line("placement.z_min", pk.z_min);
    line("placement.z_max", pk.z_max);
  }
  line("dem.time_step", d.dt);
  line("dem.skin", d.skin);
  line("settle.kinetic_energy_per_particle", c.settle.kinetic_energy_per_particle);
  line("settle.max_time", c.settle.max_time);
  return s;
}

std::filesystem::path settled_bed_record_path(const std::filesystem::path& cache) {
  return std::filesystem::path(cache.string() + ".record");
}

std::string settle_cache_mismatch(const CaseConfig& config, const std::filesystem::path& cache) {
  std::ifstream in(settled_bed_record_path(cache));
  if (!in) return "no record";
  std::stringstream found;
  found << in.rdbuf();
  std::istringstream a(settled_bed_record(config)), b(found.str());
  std::string la, lb;
  while (true) {
    const bool ga = static_cast<bool>(std::getline(a, la)), gb = static_cast<bool>(std::getline(b, lb));
    if (!ga && !gb) return "";
    if (!ga || !gb || la != lb) {
      return fmt::format("{} (the cache: {})", ga ? la : std::string("nothing"), gb ? lb : std::string("nothing"));
    }
  }
}

std::filesystem::path case_relative_path(const std::string& case_file, const std::string& path) {
  return std::filesystem::path(path).is_absolute() ? std::filesystem::path(path)
                                                   : std::filesystem::path(case_file).parent_path() / path;
}

}  // namespace fluidbed
