#pragma once
// Particle -> grid: voidage and mean solids velocity per gas cell; grid -> particle: the same kernel.
#include <array>
#include <cstddef>
#include <vector>

#include "core/field2.hpp"
#include "core/grid2.hpp"
#include "coupling/coupling_config.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

/// Cells and weights (summing to 1) that a point shares its volume with; weights that would fall outside the
/// domain are folded back into the boundary cells, so no volume is lost at walls.
struct CellWeights {
  std::array<std::size_t, 4> cell{};
  std::array<double, 4> w{};
  int count = 0;
};

CellWeights cell_weights(const Grid2& grid, VoidageMethod method, double x, double y);

/// The kernel weights of every particle (computed in parallel; one entry per particle, in storage order).
void particle_cell_weights(const ParticleStore<2>& p, const Grid2& grid, VoidageMethod method,
                           std::vector<CellWeights>& out);

/// Voidage of every cell: eps = 1 - (particle volume in the cell) / (dx dy depth), not clipped.
void compute_voidage(const ParticleStore<2>& p, const Grid2& grid, VoidageMethod method, double depth, Field2& eps);
/// The same from weights already computed by particle_cell_weights.
void compute_voidage(const ParticleStore<2>& p, const std::vector<CellWeights>& weights, const Grid2& grid, double depth,
                     Field2& eps);

/// Volume-weighted mean particle velocity of every cell (0 where a cell holds no particle).
void cell_solids_velocity(const ParticleStore<2>& p, const Grid2& grid, VoidageMethod method, Field2& us, Field2& vs);
void cell_solids_velocity(const ParticleStore<2>& p, const std::vector<CellWeights>& weights, const Grid2& grid,
                          Field2& us, Field2& vs);

/// The value of a cell-centred field at a point with the same kernel as the deposition.
double gather(const Field2& f, const CellWeights& cw);

}  // namespace fluidbed
