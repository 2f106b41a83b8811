#pragma once
// Probes of a run (issue 15, item 4): the gas pressure, voidage, gas and solids velocity at points and as
// cross-section means on horizontal lines (2D) or planes (3D), and the pressure drop between two heights, as an
// experimenter's pressure taps, optical probes and capacitance planes measure them. Pure functions of
// cell-centred fields (CellView), so CFD-DEM and TFM, 2D and 3D share them. docs/analysis.md ("Probes").
#include <array>
#include <span>
#include <string>
#include <vector>

#include "analysis/cell_view.hpp"

namespace fluidbed {

/// What a probe measures where.
enum class ProbeKind {
  Point,         ///< the fields interpolated (bi-/trilinear) at `position`
  Plane,         ///< the fields' mean over the horizontal line (2D) or plane (3D) at height `height`
  PressureDrop,  ///< mean pressure at `height` minus mean pressure at `height_top` (Pa, > 0 for a fluidised bed)
  BedHeight,     ///< highest height where the cross-section mean solids fraction falls to `solids_fraction` (m)
  ParticleTop,   ///< the `percentile` of the particles' tops (centre + radius), m: the surface a camera sees
};

/// One probe of the case file ([[probe]]).
struct ProbeSpec {
  ProbeKind kind = ProbeKind::Point;
  std::string name;                      ///< column prefix, unique within the case
  std::array<double, 3> position{};      ///< m, Point (z ignored in 2D)
  double height = 0.0;                   ///< m above the bottom, Plane and the lower tap of PressureDrop
  double height_top = 0.0;               ///< m, the upper tap of PressureDrop
  double solids_fraction = 0.3;          ///< BedHeight's threshold of the mean solids fraction 1 - eps
  double percentile = 99.0;              ///< ParticleTop: percent of the particles' tops at or below the value
};

/// The probes of a case and their sampling.
struct ProbesConfig {
  /// s between probe rows; 0 samples after every model step (every gas step of CFD-DEM, every TFM step).
  double interval = 0.001;
  std::vector<ProbeSpec> probes;
};

/// The cell-centred fields a probe reads; `us` may be null (no solids velocity field).
template <int Dim>
struct ProbeFields {
  CellGeometry<Dim> geometry;
  const double* p = nullptr;
  const double* eps = nullptr;
  std::array<const double*, Dim> ug{};
  std::array<const double*, Dim> us{};
  /// The particles' tops (centre + radius along y), any order; empty for a model without particles.
  std::span<const double> particle_tops;
  bool has_solids_velocity() const {
    for (const double* c : us)
      if (!c) return false;
    return true;
  }
};

/// Mean over the cells' columns (all x, and z in 3D) of a cell-centred field interpolated linearly in height to
/// y (clamped to the outermost cell centres): the cell-weighted cross-section mean, exact for a field linear in y.
template <int Dim>
double plane_mean(const CellView<Dim>& f, double y);

/// Bed height from the voidage: the highest y at which the cross-section mean solids fraction 1 - eps, linear in
/// height between the rows of cell centres, falls to `solids_fraction` (exact for a profile linear between
/// centres). The top of the column when its top row is still that dense; 0 when no row is (no bed).
template <int Dim>
double bed_height(const CellView<Dim>& eps, double solids_fraction);

/// The p-th percentile (0 <= p <= 100) of `values`, linear between the order statistics around rank
/// p / 100 (n - 1) (Hyndman and Fan's definition 7, numpy's default): a function of the values alone, not of their
/// order; 0 for no values.
double percentile(std::span<const double> values, double p);

/// probes.csv header columns after time_s, per probe in order: Point and Plane `NAME_p_Pa,NAME_eps,NAME_ug_x_m_s,
/// NAME_ug_y_m_s[,NAME_ug_z_m_s][,NAME_us_x_m_s,NAME_us_y_m_s[,NAME_us_z_m_s]]` (us with `solids`), PressureDrop
/// `NAME_dp_Pa`, BedHeight `NAME_bed_height_m`, ParticleTop `NAME_top_m`.
std::vector<std::string> probe_columns(const std::vector<ProbeSpec>& probes, int dimension, bool solids);

/// The values of one probes.csv row after time_s, in probe_columns() order.
template <int Dim>
std::vector<double> sample_probes(const std::vector<ProbeSpec>& probes, const ProbeFields<Dim>& fields);

}  // namespace fluidbed
