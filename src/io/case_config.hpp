#pragma once
// The whole case: one config struct per module, filled from the TOML case file by load_case().
#include <cstdint>
#include <string>
#include <vector>

#include "analysis/bubble_tracker.hpp"
#include "core/domain.hpp"
#include "core/grid2.hpp"
#include "core/vec2.hpp"
#include "coupling/coupling_config.hpp"
#include "dem/dem_config.hpp"
#include "fluid/gas_config.hpp"
#include "tfm/tfm_config.hpp"
#include "dem/packing.hpp"

namespace fluidbed {

enum class Model { Dem, Tfm };
enum class ParticleSource { Random, File };

/// Settling of the random placement under gravity in vacuum (the paper's initial packed bed).
struct SettleConfig {
  bool enabled = true;
  double kinetic_energy_per_particle = 1e-10;  ///< J; settled when the mean kinetic energy falls below
  double max_time = 3.0;                       ///< s of settling at most
  std::string cache;                           ///< CSV file of the settled bed, reused when present
};

struct ParticleInit {
  ParticleSource source = ParticleSource::Random;
  std::string file;
  PackingConfig packing{};
  int layers = 6;  ///< colour layers of the initial bed (paper, Fig. 4)
};

struct OutputConfig {
  double interval = 0.01;          ///< field frames, tracers, bubble samples, s
  double particle_interval = 0.01; ///< particle frames (DEM), s: a whole multiple of `interval`
  double monitor_interval = 0.001; ///< monitor.csv rows, s
  double checkpoint_interval = 0.25;  ///< s (0: only at the end)
  int checkpoint_keep = 3;            ///< periodic checkpoints kept (the newest ones)
  bool fields = true;
  bool particles = true;
  bool particles_csv = false;
  bool tracers = true;
};

struct RunConfig {
  double end_time = 1.0;
  double max_wall_time = 0.0;  ///< s; 0 means no limit
};

struct CaseConfig {
  std::string name = "case";
  std::string description;
  std::string source_path;
  Model model = Model::Dem;
  std::uint64_t seed = 1998;
  RunConfig run{};
  DomainConfig domain{};
  DemConfig dem{};
  ParticleInit particles{};
  SettleConfig settle{};
  OutputConfig output{};
  bool gas_enabled = true;
  Grid2 grid{};
  GasConfig gas{};
  CouplingConfig coupling{};
  BubbleConfig bubble{};
  tfm::TfmConfig tfm{};
  double max_overlap_fraction = 0.1;  ///< a run fails when an overlap exceeds this fraction of the diameter
  /// What the loader wants the user to read before a run: defaults it derived from other keys (and how), values
  /// that are allowed but look like a unit slip. `check` prints them; a run logs them.
  std::vector<std::string> notes;
};

}  // namespace fluidbed
