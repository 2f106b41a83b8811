#include "tfm/packing_limiter.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <utility>

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
  // Factor of every cell's inflow faces (a cell over its bound) and of its outflow faces (a cell below zero) in this
  // sweep, 1 where the cell is within its bounds. A face on the block's edge is cut by the factor of a neighbour's
  // cell: the factors carry one ghost layer.
  Field<Dim> in_factor(box, 1, 1.0), out_factor(box, 1, 1.0);
  const std::vector<IndexBox<Dim>> boxes = comm.size() > 1 ? all_boxes<Dim>(comm, box) : std::vector<IndexBox<Dim>>{box};
  // In and out of cell c through its faces, in units of phi: (inflow, outflow).
  auto flows = [&](const Index<Dim>& c) {
    double in = 0.0, out = 0.0;
    for (int a = 0; a < Dim; ++a) {
      const double hi = f[a][shifted<Dim>(c, a, 1)], lo = f[a][c];
      const double t_in = courant[a] * (std::max(-hi, 0.0) + std::max(lo, 0.0));
      const double t_out = courant[a] * (std::max(hi, 0.0) + std::max(-lo, 0.0));
      in = a == 0 ? t_in : in + t_in;
      out = a == 0 ? t_out : out + t_out;
    }
    return std::pair{in, out};
  };
  // Every cell reads the fluxes as the previous sweep left them, so the factors do not depend on the order the
  // cells are visited in (a Jacobi sweep: it can run on sub-domains with a halo exchange between sweeps).
  auto cell_factors = [&](const Index<Dim>& c, double& r_in, double& r_out) {
    r_in = r_out = 1.0;
    // Same expression as conservative_update, so the bound checked is the bound the update will meet.
    const double value = conservative_cell_update(g, phi_old, f, c, dt);
    const double bound = std::max(phi_max, phi_old[c]);
    // (r is kept below 1, so that every cut makes progress.)
    if (value > bound) {
      // All inflow faces take the same factor: the cell lands on the bound, the outflows stay. Without inflow the
      // value cannot rise above phi_old, so `in` is positive here.
      const double in = flows(c).first;
      if (in > 0.0) r_in = std::clamp(1.0 - (value - bound + kLandingMargin) / in, 0.0, std::nextafter(1.0, 0.0));
    } else if (1.0 - value > 1.0) {
      // Emptied past zero (the voidage 1 - phi would exceed 1): an undershoot of the implicit step's deferred
      // high-order correction. All outflow faces take the same factor and the cell lands on zero: a rounding
      // residue below it leaves the voidage at 1 exactly, and a trace above it would get the kinetic theory's
      // granular temperature of a nearly empty cell (unbounded as eps_s -> 0).
      const double out = flows(c).second;
      if (out > 0.0) r_out = std::clamp(1.0 + value / out, 0.0, std::nextafter(1.0, 0.0));
    }
  };
  // A face has one receiving and one donor cell (from the sign of its flux); it takes the smaller of the receiver's
  // inflow factor and the donor's outflow factor, once per sweep.
  auto cut = [&](double& face, double r) {
    if (r == 1.0) return;
    face *= r;
    ++res.faces_limited;
  };
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    res.sweeps = sweep + 1;
    bool over = false, under = false;
    for_each(box, [&](const Index<Dim>& c) {
      cell_factors(c, in_factor[c], out_factor[c]);
      over = over || in_factor[c] != 1.0;
      under = under || out_factor[c] != 1.0;
    });
    std::array<double, 2> any{over ? 1.0 : 0.0, under ? 1.0 : 0.0};
    comm.max(std::span<double>(any));  // every rank sweeps until no cell anywhere is out of bounds
    if (any[0] == 0.0 && any[1] == 0.0) return res;
    if (any[0] != 0.0) fill_block_ghosts<Dim>(in_factor, dom, g.periodic, comm, boxes);
    if (any[1] != 0.0) fill_block_ghosts<Dim>(out_factor, dom, g.periodic, comm, boxes);
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
        const bool has_hi = per || face_index[a] < dom.hi[a], has_lo = per || face_index[a] > dom.lo[a];
        const Index<Dim> hi = cell(face_index), lo = cell(shifted<Dim>(face_index, a, -1));
        // Upward (positive) flux: from lo into hi; downward: from hi into lo. A boundary face has one cell only.
        if (face > 0.0) cut(face, std::min(has_hi ? in_factor[hi] : 1.0, has_lo ? out_factor[lo] : 1.0));
        if (face < 0.0) cut(face, std::min(has_lo ? in_factor[lo] : 1.0, has_hi ? out_factor[hi] : 1.0));
      });
    }
  }
  throw_simulation_error("tfm: packing limiter did not bound the solids fraction by [0, " + std::to_string(phi_max) +
                         "] within " + std::to_string(max_sweeps) + " sweeps");
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
