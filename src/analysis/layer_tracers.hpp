#pragma once
// Coloured layers of the paper's Fig. 4: (a) DEM particles by initial layer, (b)/(c) one ball per initial bed cell
// moved by the cell-averaged solids velocity of the cell it is in. Layers are horizontal: slabs of height y in 2D
// and 3D alike (the depth coordinate z of a 3D bed rides along).
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "analysis/cell_view.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

/// Layer of a height y in a bed of n_layers equal layers over [y_bottom, y_bottom + bed_height]; heights outside
/// are put in the nearest layer.
int layer_of(double y, double y_bottom, double bed_height, int n_layers);

/// layer[k] = the layer of height y[k] in a bed from y = 0 to bed_height (call once, at t = 0); any dimension,
/// since only the height counts. Throws Error(BadInput) for n_layers < 1, bed_height <= 0 or spans of different
/// lengths.
void assign_layers(std::span<const double> y, std::span<std::int32_t> layer, int n_layers, double bed_height);
/// Sets ParticleStore::layer from the current heights.
template <int Dim>
void assign_layers(ParticleStore<Dim>& particles, int n_layers, double bed_height);

/// Balls of the paper's Fig. 4b/c: one per grid cell whose centre lies below the initial bed height, in 2D or 3D.
template <int Dim>
class BallTracers {
 public:
  /// bed_height: initial bed height above the grid's origin along y, m (e.g. bed_surface_height() of the initial
  /// voidage). The balls are numbered in the cells' storage order (axis 0 fastest).
  BallTracers(const CellGeometry<Dim>& grid, double bed_height, int n_layers);
  /// The balls of a checkpoint: ids, positions (x, y[, z]) and initial layers as saved (a restart must not recolour
  /// them from the bed it restarts in). Throws Error(BadInput) when the arrays differ in length or a ball lies
  /// outside the grid.
  BallTracers(const CellGeometry<Dim>& grid, std::vector<std::int64_t> ids, std::array<std::vector<double>, Dim> pos,
              std::vector<std::int32_t> layers);

  /// x_a += u_a dt along every axis with the solids velocity components (velocity[a] along axis a) of the cell
  /// holding the ball (piecewise constant, no collisions, as the paper); the centre is then clamped to the domain,
  /// or wrapped into it along a periodic axis (set_periodic).
  /// Throws Error(BadInput) when a velocity field's cells differ from the tracers' grid.
  void advance(const std::array<CellView<Dim>, Dim>& velocity, double dt);
  /// Axis a of the domain is periodic: a ball leaving one side re-enters at the other.
  void set_periodic(int a, bool on) { periodic_[static_cast<std::size_t>(a)] = on; }

  std::size_t size() const { return x.size(); }
  const CellGeometry<Dim>& geometry() const { return geometry_; }
  /// The coordinate array of axis a: x, y or z.
  std::vector<double>& coord(int a) { return a == 0 ? x : (a == 1 ? y : z); }
  const std::vector<double>& coord(int a) const { return a == 0 ? x : (a == 1 ? y : z); }

  std::vector<std::int64_t> id;
  std::vector<double> x, y;          ///< m
  std::vector<double> z;             ///< m, 3D only (empty in 2D)
  std::vector<std::int32_t> layer;   ///< initial layer

 private:
  CellGeometry<Dim> geometry_;
  std::array<bool, Dim> periodic_{};
};

}  // namespace fluidbed
