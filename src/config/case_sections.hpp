#pragma once
// The readers of a case file's sections, one file per part of CaseConfig that they fill (dem_sections.cpp,
// tfm_section.cpp, gas_sections.cpp, coupling_section.cpp, analysis_sections.cpp, output_section.cpp); the loader
// (case_loader.cpp) reads [case] and [domain] and calls them in the key table's order. Internal to config/.
#include <cstddef>
#include <optional>
#include <string>

#include "config/case_config.hpp"
#include "config/case_reader.hpp"

namespace fluidbed::case_sections {

/// The grid keys as given (the cells' sizes before the grid rounds them to whole cells) and the number of
/// inlet.jet tables: what the later sections' defaults derive from.
struct GasKeys {
  double dx = 0.0, dy = 0.0, dz = 0.0;  ///< m
  std::size_t jet_tables = 0;
};

// dem_sections.cpp: into c.dem, c.particles, c.settle.
/// The plausibility of a species' smallest and largest particle, named by the key that sets each.
void check_species_plausible(const CaseReader& r, const std::string& p, const Species& sp, const DomainConfig& domain,
                             const std::optional<CaseGrid>& cell);
void read_species(CaseReader& r, CaseConfig& c);
void read_contact(CaseReader& r, CaseConfig& c);
void read_dem(CaseReader& r, CaseConfig& c);
void read_insertion(CaseReader& r, CaseConfig& c);
void read_particles(CaseReader& r, CaseConfig& c);
void read_settle(CaseReader& r, CaseConfig& c);

// tfm_section.cpp: into c.tfm.
void read_tfm(CaseReader& r, CaseConfig& c);

// gas_sections.cpp: into c.grid and c.gas.
void read_grid(CaseReader& r, CaseConfig& c, GasKeys& k);
void read_gas_phase(CaseReader& r, CaseConfig& c, const GasKeys& k);
void read_inlet(CaseReader& r, CaseConfig& c, GasKeys& keys);
void read_plates(CaseReader& r, CaseConfig& c);

// coupling_section.cpp: into c.coupling (and c.tfm through read_tfm for the two-fluid model).
void read_coupling(CaseReader& r, CaseConfig& c);

// analysis_sections.cpp: into c.bubble, c.probes, c.averages.
void read_bubble(CaseReader& r, CaseConfig& c, const GasKeys& k);
void read_probes(CaseReader& r, CaseConfig& c);
void read_averages(CaseReader& r, CaseConfig& c);

// output_section.cpp: into c.output.
void read_output(CaseReader& r, CaseConfig& c);

// parallel_section.cpp: into c.parallel.
void read_parallel(CaseReader& r, CaseConfig& c);

}  // namespace fluidbed::case_sections
