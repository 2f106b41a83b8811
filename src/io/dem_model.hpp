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

/// What a settled bed depends on (particles, placement, contact law, time step, settling criteria), one
/// `key = value` line each at full precision: stored beside the settle cache as `<cache>.record` and compared
/// before the cache is reused, so a bed settled with other parameters is never taken for this one.
std::string settled_bed_record(const CaseConfig& config);

/// The first line in which two settled-bed records differ ("" when they are equal), for messages.
std::string settled_bed_record_difference(const std::string& wanted, const std::string& found);

/// Particles of a CSV file (`id,x,y,vx,vy,omega,species`), checked against the case (species, domain).
ParticleStore particles_from_csv(const std::string& path, const DemConfig& dem);

}  // namespace fluidbed
