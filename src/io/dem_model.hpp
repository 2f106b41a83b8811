#pragma once
// The discrete-particle model behind the run driver: DEM alone, or CFD-DEM when the case has gas.
#include <filesystem>
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

/// Where the record of the settle cache `cache` is kept.
std::filesystem::path settled_bed_record_path(const std::filesystem::path& cache);

/// Why the existing settle cache `cache` cannot stand for the bed of `config`: "" when its record matches, "no
/// record" when it has none, else the first differing line and the cache's ("key = v (the cache: key = w)").
std::string settle_cache_mismatch(const CaseConfig& config, const std::filesystem::path& cache);

/// A path of the case file (particles.file, settle.cache): absolute as given, else relative to the case's folder.
std::filesystem::path case_relative_path(const std::string& case_file, const std::string& path);

/// Particles of a CSV file (2D `id,x,y,vx,vy,omega,species`; 3D adds z, vz and omega_x, omega_y, omega_z), checked against
/// the case (species, the domain of dem.domain) by check_particle_rows.
template <int Dim>
ParticleStore<Dim> particles_from_csv(const std::string& path, const DemConfig& dem);

}  // namespace fluidbed
