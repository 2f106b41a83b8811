#include "tfm/packing_limiter.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace fluidbed::tfm {
namespace {

// A cut cell is brought this far (in phi) below its bound, so that the rounding of its update cannot leave it
// over the bound; the check itself has no tolerance, so no cell ever ends above max(phi_max, phi_old).
constexpr double kLandingMargin = 1e-14;

}  // namespace

template <int Dim>
PackingLimitResult limit_packing(const Grid<Dim>& g, const Field<Dim>& phi_old, double dt, double phi_max,
                                 FaceFluxes<Dim>& f, int max_sweeps, const Comm& comm) {
  const IndexBox<Dim>& box = g.owned;
  const IndexBox<Dim>& dom = g.domain;
  std::array<double, Dim> courant{};
  for (int a = 0; a < Dim; ++a) courant[a] = dt / g.h[a];
  PackingLimitResult res;
  // Factor of every cell's inflow faces in this sweep (1: the cell is within its bound).
  // A face on the block's edge is cut by the factor of a neighbour's cell: the factors carry one ghost layer.
  Field<Dim> factor(box, 1, 1.0);
  const std::vector<IndexBox<Dim>> boxes = comm.size() > 1 ? all_boxes<Dim>(comm, box) : std::vector<IndexBox<Dim>>{box};
  // Every cell reads the fluxes as the previous sweep left them, so the factors do not depend on the order the
  // cells are visited in (a Jacobi sweep: it can run on sub-domains with a halo exchange between sweeps).
  auto cell_factor = [&](const Index<Dim>& c) {
    // Same expression as conservative_update, so the bound checked is the bound the update will meet.
    const double value = conservative_cell_update(g, phi_old, f, c, dt);
    const double bound = std::max(phi_max, phi_old[c]);
    if (!(value > bound)) return 1.0;
    const double excess = value - bound + kLandingMargin;
    // Inflow through each face, in units of phi.
    double in = 0.0;
    for (int a = 0; a < Dim; ++a) {
      const double term = courant[a] * (std::max(-f[a][shifted<Dim>(c, a, 1)], 0.0) + std::max(f[a][c], 0.0));
      in = a == 0 ? term : in + term;
    }
    if (!(in > 0.0)) return 1.0;  // cannot happen: without inflow the value cannot rise above phi_old
    // All inflow faces take the same factor: the cell lands on the bound, the outflows stay.
    // (r is kept below 1, so that every cut makes progress.)
    return std::clamp(1.0 - excess / in, 0.0, std::nextafter(1.0, 0.0));
  };
  // A face has one receiving cell (from the sign of its flux), so each face takes at most one factor per sweep.
  auto cut = [&](double& face, double r) {
    if (r == 1.0) return;
    face *= r;
    ++res.faces_limited;
  };
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    res.sweeps = sweep + 1;
    bool over = false;
    for_each(box, [&](const Index<Dim>& c) {
      factor[c] = cell_factor(c);
      over = over || factor[c] != 1.0;
    });
    if (comm.max(over ? 1.0 : 0.0) == 0.0) return res;  // every rank sweeps until no cell anywhere is over
    fill_block_ghosts<Dim>(factor, dom, g.periodic, comm, boxes);
    for (int a = 0; a < Dim; ++a) {
      // On a periodic axis the cell beyond face n is the first one and the cell before face 0 the last: faces 0
      // and n hold the same flux, so they take the same cut and stay equal.
      const bool per = g.periodic[static_cast<std::size_t>(a)];
      auto cell = [&](Index<Dim> c) {
        c[a] = g.wrap(a, c[a]);
        return c;
      };
      for_each(box.faces(a), [&](const Index<Dim>& face_index) {
        double& face = f[a][face_index];
        if (face > 0.0 && (per || face_index[a] < dom.hi[a])) cut(face, factor[cell(face_index)]);
        if (face < 0.0 && (per || face_index[a] > dom.lo[a])) cut(face, factor[cell(shifted<Dim>(face_index, a, -1))]);
      });
    }
  }
  throw_simulation_error("tfm: packing limiter did not bound the solids fraction by " + std::to_string(phi_max) +
                         " within " + std::to_string(max_sweeps) + " sweeps");
}

template <int Dim>
void transfer_to_gas(const FaceFluxes<Dim>& solids_before, const FaceFluxes<Dim>& solids_after,
                     FaceFluxes<Dim>& gas) {
  for (int a = 0; a < Dim; ++a)
    for_each(gas[a].box(), [&](const Index<Dim>& f) { gas[a][f] += solids_before[a][f] - solids_after[a][f]; });
}

template PackingLimitResult limit_packing<2>(const Grid<2>&, const Field<2>&, double, double, FaceFluxes<2>&, int,
                                             const Comm&);
template PackingLimitResult limit_packing<3>(const Grid<3>&, const Field<3>&, double, double, FaceFluxes<3>&, int,
                                             const Comm&);
template void transfer_to_gas<2>(const FaceFluxes<2>&, const FaceFluxes<2>&, FaceFluxes<2>&);
template void transfer_to_gas<3>(const FaceFluxes<3>&, const FaceFluxes<3>&, FaceFluxes<3>&);

}  // namespace fluidbed::tfm
