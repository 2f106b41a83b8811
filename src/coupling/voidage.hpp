#pragma once
// Particle -> grid: voidage and mean solids velocity per gas cell; grid -> particle: the same kernel. Generic over
// the dimension: a particle shares its volume with the 2^Dim nearest cell centres (cloud-in-cell), or all of it
// with the cell holding its centre (the paper's counting).
#include <array>
#include <cstddef>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "coupling/coupling_config.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

/// Cells (entries of a cell field on the grid's owned box, as Field<Dim>::index gives them) and weights (summing
/// to 1) that a point shares its volume with; weights that would fall outside the domain are folded back into the
/// boundary cells, so no volume is lost at walls, and wrap to the opposite side on a periodic axis (Grid::periodic).
template <int Dim>
struct CellWeights {
  static constexpr int kMax = 1 << Dim;
  std::array<std::size_t, kMax> cell{};
  std::array<double, kMax> w{};
  int count = 0;
};

/// The weights of a point x for cell fields of the layout `layout` (any field on the grid's owned box; its ghost
/// width fixes the indices).
template <int Dim>
CellWeights<Dim> cell_weights(const Grid<Dim>& grid, const Field<Dim>& layout, VoidageMethod method, const Vec<Dim>& x);

/// The kernel weights of every particle (computed in parallel; one entry per particle, in storage order).
template <int Dim>
void particle_cell_weights(const ParticleStore<Dim>& p, const Grid<Dim>& grid, const Field<Dim>& layout,
                           VoidageMethod method, std::vector<CellWeights<Dim>>& out);

/// Voidage of every cell from weights of particle_cell_weights: eps = 1 - (particle volume in the cell) / V_cell,
/// not clipped; V_cell is the grid's cell volume in 3D and its area times `depth` in 2D.
template <int Dim>
void compute_voidage(const ParticleStore<Dim>& p, const std::vector<CellWeights<Dim>>& weights, const Grid<Dim>& grid,
                     double depth, Field<Dim>& eps);

/// Volume-weighted mean particle velocity of every cell (0 where a cell holds no particle), one field per axis.
template <int Dim>
void cell_solids_velocity(const ParticleStore<Dim>& p, const std::vector<CellWeights<Dim>>& weights,
                          const Grid<Dim>& grid, std::array<Field<Dim>, Dim>& us);

/// The value of a cell field at a point with the same kernel as the deposition.
template <int Dim>
double gather(const Field<Dim>& f, const CellWeights<Dim>& cw) {
  double s = 0.0;
  for (int k = 0; k < cw.count; ++k) s += cw.w[static_cast<std::size_t>(k)] * f.data()[cw.cell[static_cast<std::size_t>(k)]];
  return s;
}

/// Cell volume the deposition divides by: the grid's in 3D, the area times the monolayer depth in 2D.
template <int Dim>
double deposition_volume(const Grid<Dim>& grid, double depth) {
  return Dim == 3 ? grid.cell_measure() : grid.cell_measure() * depth;
}

/// The voidage of particles p on cell field eps, the kernel weights computed here: for a caller that deposits
/// once (the coupling keeps its weights for the gather instead). eps not on the grid's owned box is made a
/// ghost-free field on it.
template <int Dim>
void compute_voidage(const ParticleStore<Dim>& p, const Grid<Dim>& grid, VoidageMethod method, double depth,
                     Field<Dim>& eps) {
  if (eps.box() != grid.owned) eps = Field<Dim>(grid.owned, 0);
  std::vector<CellWeights<Dim>> w;
  particle_cell_weights(p, grid, eps, method, w);
  compute_voidage(p, w, grid, depth, eps);
}

/// The mean solids velocity of particles p on cell fields us, the weights computed here (fields not on the
/// grid's owned box made ghost-free ones on it).
template <int Dim>
void cell_solids_velocity(const ParticleStore<Dim>& p, const Grid<Dim>& grid, VoidageMethod method,
                          std::array<Field<Dim>, Dim>& us) {
  for (Field<Dim>& u : us) {
    if (u.box() != grid.owned) u = Field<Dim>(grid.owned, 0);
  }
  std::vector<CellWeights<Dim>> w;
  particle_cell_weights(p, grid, us[0], method, w);
  cell_solids_velocity<Dim>(p, w, grid, us);
}

}  // namespace fluidbed
