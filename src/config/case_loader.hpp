#pragma once
// Case file -> CaseConfig, with every key checked (type, range, cross-checks) and registered.
#include <string>
#include <vector>

#include "config/case_config.hpp"
#include "config/case_reader.hpp"

namespace fluidbed {

struct LoadedCase {
  CaseConfig config;
  std::string resolved_toml;   ///< every key read, defaults filled in
  std::vector<KeyInfo> keys;   ///< what was read, for docs and --help
};

/// Load and validate a case; `overrides` are `--set SECTION.KEY=VALUE` assignments. Throws Error(BadInput)
/// naming file, line and key for any problem.
LoadedCase load_case(const std::string& path, const std::vector<std::string>& overrides = {});
/// The same from TOML text (tests and the fuzzer).
LoadedCase load_case_text(const std::string& text, const std::string& name,
                          const std::vector<std::string>& overrides = {});

/// Every key of both models as a Markdown table (docs/case-format.md is this output).
std::string case_keys_markdown();

/// Largest stable DEM time step for the symplectic Euler update of the stiffest contact (lightest pair,
/// strongest damping): omega dt < 2 (sqrt(1 + zeta^2) - zeta).
double dem_stable_time_step(const DemConfig& dem);

/// Largest stable step for the collective spin mode of a packed bed with sticking contacts, which is stiffer than
/// any single contact: neighbours spinning the same way counter-slide at every contact, so omega^2 = 2 Z k_t r^2 / I
/// with the coordination Z of the densest packing (6 in 2D, 12 in 3D). Sliding caps the mode, so a larger step is
/// noted rather than refused (docs/performance.md, the time-step analysis).
double dem_packed_bed_time_step(const DemConfig& dem);

}  // namespace fluidbed
