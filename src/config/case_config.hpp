#pragma once
// The whole case: one config struct per module, filled from the TOML case file by load_case().
#include <cstdint>
#include <string>
#include <vector>

#include "analysis/bubble_tracker.hpp"
#include "analysis/probes.hpp"
#include "analysis/time_average.hpp"
#include "core/domain.hpp"
#include "core/grid.hpp"
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

/// [parallel]: how a run over several ranks deals its blocks (docs/parallel.md). Nothing here changes a result.
struct ParallelConfig {
  double rebalance_threshold = 1.2;  ///< deal the blocks again when the largest rank cost exceeds this times the mean
};

struct RunConfig {
  double end_time = 1.0;
  double max_wall_time = 0.0;  ///< s; 0 means no limit
};

/// The gas grid of a case in either dimension: cells and cell sizes per axis (x across, y up, z the depth between
/// front and back; nz = 1 and dz = 0 in 2D), the origin at the bottom-left(-front) corner of the domain. One grid
/// serves the gas, the voidage and the two-fluid model; each model takes the form it works on.
struct CaseGrid {
  int dimension = 2;
  int nx = 0, ny = 0, nz = 1;
  double dx = 0.0, dy = 0.0, dz = 0.0;  ///< m

  int n(int axis) const { return axis == 0 ? nx : axis == 1 ? ny : nz; }
  double h(int axis) const { return axis == 0 ? dx : axis == 1 ? dy : dz; }
  std::size_t cells() const {
    return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
  }
  /// The whole grid, owned by this process, with `ghost` layers (Dim = 2 ignores z).
  template <int Dim>
  Grid<Dim> grid_of(int ghost = 1) const {
    Grid<Dim> g;
    for (int a = 0; a < Dim; ++a) {
      g.domain.lo[a] = 0;
      g.domain.hi[a] = n(a);
      g.h[a] = h(a);
      g.origin[a] = 0.0;
    }
    g.owned = g.domain;
    g.ghost = ghost;
    return g;
  }
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
  ParallelConfig parallel{};
  bool gas_enabled = true;
  CaseGrid grid{};
  GasConfig gas{};
  CouplingConfig coupling{};
  BubbleConfig bubble{};
  ProbesConfig probes{};  ///< [probes], [[probe]] (issue 15)
  AveragesConfig averages{};  ///< [averages]: time-averaged fields over a window (issue 15)
  tfm::TfmConfig tfm{};
  double max_overlap_fraction = 0.1;  ///< a run fails when an overlap exceeds this fraction of the diameter
  /// What the loader wants the user to read before a run: defaults it derived from other keys (and how), values
  /// that are allowed but look like a unit slip. `check` prints them; a run logs them.
  std::vector<std::string> notes;
};

}  // namespace fluidbed
