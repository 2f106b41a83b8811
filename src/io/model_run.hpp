#pragma once
// The narrow interface between the run driver (outputs, checkpoints, progress) and a model (CFD-DEM or TFM).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/field2.hpp"
#include "core/grid2.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

class Hdf5File;

/// Cell-centred views of a model's grid fields for observers (bubble tracker, tracers, field output).
struct FieldView {
  const Grid2* grid = nullptr;  ///< null when the model has no grid (DEM without gas)
  const Field2* eps = nullptr;  ///< voidage
  const Field2* p = nullptr;    ///< gas pressure, Pa
  const Field2* ug = nullptr;   ///< interstitial gas velocity, cell centres, m/s
  const Field2* vg = nullptr;
  const Field2* us = nullptr;   ///< solids velocity, cell centres (DEM: cell-averaged particle velocity), m/s
  const Field2* vs = nullptr;
  const Field2* theta = nullptr;  ///< granular temperature (TFM kinetic theory), m^2/s^2
};

struct CostInfo {
  std::uint64_t particles = 0;
  std::uint64_t cells = 0;
  std::uint64_t time_steps = 0;  ///< DEM steps, or TFM/gas steps
};

class ModelRun {
 public:
  virtual ~ModelRun() = default;
  virtual double time() const = 0;
  /// One macro step: a gas step with its DEM sub-steps, a DEM step alone, or a TFM step. The step never goes
  /// past `t_end` (the run's end time): a model shortens its last step to land on it.
  virtual void advance(double t_end) = 0;
  /// Time step of advance(), s: half of it is the slack of output scheduling; 0 for a model whose adaptive steps
  /// land on the output times themselves.
  virtual double macro_dt() const = 0;
  virtual std::vector<std::string> monitor_columns() const = 0;
  virtual std::vector<std::optional<double>> monitor_values() = 0;
  virtual FieldView fields() = 0;
  virtual const ParticleStore<2>* particles() const { return nullptr; }
  virtual void save(Hdf5File& file) const = 0;
  virtual void load(const Hdf5File& file) = 0;
  virtual CostInfo cost() const = 0;
  virtual std::string describe() const = 0;
};

}  // namespace fluidbed
