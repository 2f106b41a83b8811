#pragma once
// The narrow interface between the run driver (outputs, checkpoints, progress) and a model (CFD-DEM or TFM).
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "analysis/cell_view.hpp"
#include "io/particle_arrays.hpp"

namespace fluidbed {

class Hdf5File;

/// Cell-centred views of a model's grid fields for observers (bubble tracker, tracers, field output), in either
/// dimension: the grid's shape and, per field, a pointer to its interior values as one contiguous array of
/// n[0] n[1] n[2] cells, axis 0 fastest (cell (i, j, k) at i + n[0] (j + n[1] k)); n[2] = 1 in 2D. A null pointer
/// is a field the model does not have. The arrays belong to the model and stay valid until its next advance().
struct FieldView {
  int dimension = 2;
  std::array<int, 3> n{0, 0, 1};          ///< cells per axis; n[0] = 0 when the model has no grid (DEM without gas)
  std::array<double, 3> h{0.0, 0.0, 0.0};  ///< cell size per axis, m (h[2] = 0 in 2D)
  std::array<double, 3> origin{0.0, 0.0, 0.0};  ///< low corner of the grid, m
  const double* eps = nullptr;  ///< voidage
  const double* p = nullptr;    ///< gas pressure, Pa
  std::array<const double*, 3> ug{};  ///< interstitial gas velocity per axis, cell centres, m/s (ug[2]: 3D)
  /// Solids velocity per axis, cell centres (DEM: cell-averaged particle velocity), m/s.
  std::array<const double*, 3> us{};
  const double* theta = nullptr;  ///< granular temperature (TFM kinetic theory), m^2/s^2

  bool has_grid() const { return n[0] > 0; }
  std::size_t cells() const {
    return static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) * static_cast<std::size_t>(n[2]);
  }
  /// Whether the gas (or solids) velocity has all its components.
  bool has_gas_velocity() const { return ug[0] && ug[1] && (dimension == 2 || ug[2]); }
  bool has_solids_velocity() const { return us[0] && us[1] && (dimension == 2 || us[2]); }
  /// The cells of a view of dimension Dim, as the analysis reads them.
  template <int Dim>
  CellGeometry<Dim> geometry() const {
    CellGeometry<Dim> g;
    for (int a = 0; a < Dim; ++a) {
      g.n[a] = n[static_cast<std::size_t>(a)];
      g.h[a] = h[static_cast<std::size_t>(a)];
      g.origin[a] = origin[static_cast<std::size_t>(a)];
    }
    return g;
  }
};

struct CostInfo {
  std::uint64_t particles = 0;
  std::uint64_t cells = 0;
  std::uint64_t time_steps = 0;  ///< DEM steps, or TFM/gas steps
};

/// What the observers will read of a model's fields after a step: nothing, the solids velocity (the cell tracers
/// of every step), or every field (frames, probes, averages). The runner decides it alike on every rank.
enum class FieldNeed { None = 0, SolidsVelocity = 1, All = 2 };

class ModelRun {
 public:
  virtual ~ModelRun() = default;
  virtual double time() const = 0;
  /// One macro step: a gas step with its DEM sub-steps, a DEM step alone, or a TFM step. The step never goes
  /// past `t_end` (the run's end time): a model shortens its last step to land on it.
  virtual void advance(double t_end) = 0;
  /// Length of the last advance() as the model stepped it (its dt, not the clock's difference): the clock may be
  /// set to t_end on landing, so the difference of times would round differently in a run that stops there and in
  /// one that runs on, and the cell tracers advected with it would not restart bit for bit.
  virtual double last_step() const = 0;
  /// Time step of advance(), s: half of it is the slack of output scheduling; 0 for a model whose adaptive steps
  /// land on the output times themselves.
  virtual double macro_dt() const = 0;
  virtual std::vector<std::string> monitor_columns() const = 0;
  virtual std::vector<std::optional<double>> monitor_values() = 0;
  virtual FieldView fields() = 0;
  /// Makes fields() current for `need` after an advance(): collective on several ranks, where a model whose fields
  /// are spread over the ranks gathers on rank 0 what is needed and no more (a model whose fields are whole on every
  /// rank has nothing to do). Before the first advance() every field is current.
  virtual void share_fields(FieldNeed need) { (void)need; }
  /// The particles as plain arrays (either dimension), valid until the next advance(); empty for a model without
  /// particles.
  virtual std::optional<ParticleArrays> particles() const { return std::nullopt; }
  /// Writes the model's state into `file` (rank 0 of a distributed run; null on the other ranks, which take part in
  /// gathering it: collective).
  virtual void save(Hdf5File* file) const = 0;
  virtual void load(const Hdf5File& file) = 0;
  virtual CostInfo cost() const = 0;
  virtual std::string describe() const = 0;
  /// On several ranks, how the work is split (a line for the log; collective); empty on one rank.
  virtual std::string parallel_summary() const { return {}; }
};

}  // namespace fluidbed
