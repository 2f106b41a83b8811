#pragma once
// Coloured layers of the paper's Fig. 4: (a) DEM particles by initial layer, (b)/(c) one ball per initial bed cell
// moved by the cell-averaged solids velocity of the cell it is in.
#include <cstdint>
#include <string>
#include <vector>

#include "core/field2.hpp"
#include "core/grid2.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

/// Layer of a height y in a bed of n_layers equal layers over [y_bottom, y_bottom + bed_height]; heights outside
/// are put in the nearest layer.
int layer_of(double y, double y_bottom, double bed_height, int n_layers);

/// Sets ParticleStore<2>::layer from the current heights (call once, at t = 0), bed from y = 0 to bed_height.
void assign_layers(ParticleStore<2>& particles, int n_layers, double bed_height);

/// Balls of the paper's Fig. 4b/c: one per grid cell whose centre lies below the initial bed height.
class CellTracers {
 public:
  /// bed_height: initial bed height above grid.y0, m (e.g. bed_surface_height() of the initial voidage).
  CellTracers(const Grid2& grid, double bed_height, int n_layers);
  /// The balls of a checkpoint: ids, positions and initial layers as saved (a restart must not recolour them
  /// from the bed it restarts in). Throws Error(BadInput) when the arrays differ in length or a ball lies
  /// outside the grid.
  CellTracers(const Grid2& grid, std::vector<std::int64_t> ids, std::vector<double> xs, std::vector<double> ys,
              std::vector<std::int32_t> layers);

  /// x += us dt, y += vs dt with the velocity of the cell holding the ball (piecewise constant, no collisions, as
  /// the paper); the centre is then clamped to the domain [x0, x0 + width] x [y0, y0 + height].
  void advance(const Field2& us, const Field2& vs, double dt);

  std::size_t size() const { return x.size(); }
  const Grid2& grid() const { return grid_; }

  std::vector<std::int64_t> id;
  std::vector<double> x, y;          ///< m
  std::vector<std::int32_t> layer;   ///< initial layer

 private:
  Grid2 grid_;
};

/// tracers/NNNNNN.csv content: header ball_id,x,y,layer and one line per ball (shortest round-trip numbers).
std::string tracer_csv(const CellTracers& tracers);

}  // namespace fluidbed
