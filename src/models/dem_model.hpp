#pragma once
// The discrete-particle model behind the run driver: DEM alone, or CFD-DEM when the case has gas.
#include <filesystem>
#include <memory>
#include <string>

#include "config/case_config.hpp"
#include "config/settle_record.hpp"
#include "models/model_run.hpp"
#include "parallel/comm.hpp"

namespace spdlog { class logger; }

namespace fluidbed {

/// Build the model; with `fresh` the particles are created (read, or placed and settled) and coloured by
/// layer; otherwise the state comes from a checkpoint through load().
/// On several ranks (comm) the particles are split over them (docs/parallel.md); every call of the model is then
/// collective, and what it gives for output (particles(), save()) is gathered on rank 0.
std::unique_ptr<ModelRun> make_dem_model(const CaseConfig& config, const std::string& out_dir, bool fresh,
                                         spdlog::logger& log, const Comm& comm = serial_comm());

/// Particles of a CSV file (2D `id,x,y,vx,vy,omega,species`; 3D adds z, vz and omega_x, omega_y, omega_z), checked against
/// the case (species, the domain of dem.domain) by check_particle_rows.
template <int Dim>
ParticleStore<Dim> particles_from_csv(const std::string& path, const DemConfig& dem);

}  // namespace fluidbed
