#pragma once
// The discrete-particle model behind the run driver: DEM alone, or CFD-DEM when the case has gas.
#include <memory>
#include <string>

#include "io/case_config.hpp"
#include "io/model_run.hpp"

namespace spdlog { class logger; }

namespace fluidbed {

/// Build the model; with `fresh` the particles are created (read, or placed and settled) and coloured by
/// layer; otherwise the state comes from a checkpoint through load().
std::unique_ptr<ModelRun> make_dem_model(const CaseConfig& config, const std::string& out_dir, bool fresh,
                                         spdlog::logger& log);

/// Particles of a CSV file (`id,x,y,vx,vy,omega,species`), checked against the case (species, domain).
ParticleStore particles_from_csv(const std::string& path, const DemConfig& dem);

}  // namespace fluidbed
