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

PackingLimitResult limit_packing(const Grid2& g, const Field2& phi_old, double dt, double phi_max, FaceFluxes& f,
                                 int max_sweeps) {
  const int nx = g.nx, ny = g.ny;
  const double cx = dt / g.dx, cy = dt / g.dy;
  PackingLimitResult res;
  // Factor of every cell's inflow faces in this sweep (1: the cell is within its bound).
  Field2 factor(nx, ny);
  // Every cell reads the fluxes as the previous sweep left them, so the factors do not depend on the order the
  // cells are visited in (a Jacobi sweep: it can run on sub-domains with a halo exchange between sweeps).
  auto cell_factor = [&](int i, int j) {
    // Same expression as conservative_update, so the bound checked is the bound the update will meet.
    const double fe = f.x(i + 1, j), fw = f.x(i, j), fn = f.y(i, j + 1), fs = f.y(i, j);
    const double value = conservative_cell_update(phi_old(i, j), fe, fw, fn, fs, dt, g.dx, g.dy);
    const double bound = std::max(phi_max, phi_old(i, j));
    if (!(value > bound)) return 1.0;
    const double excess = value - bound + kLandingMargin;
    // Inflow through each face, in units of phi.
    const double in = cx * (std::max(-fe, 0.0) + std::max(fw, 0.0)) + cy * (std::max(-fn, 0.0) + std::max(fs, 0.0));
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
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        factor(i, j) = cell_factor(i, j);
        over = over || factor(i, j) != 1.0;
      }
    if (!over) return res;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        double& face = f.x(i, j);
        if (face > 0.0 && i < nx) cut(face, factor(i, j));
        if (face < 0.0 && i > 0) cut(face, factor(i - 1, j));
      }
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i) {
        double& face = f.y(i, j);
        if (face > 0.0 && j < ny) cut(face, factor(i, j));
        if (face < 0.0 && j > 0) cut(face, factor(i, j - 1));
      }
  }
  throw_simulation_error("tfm: packing limiter did not bound the solids fraction by " + std::to_string(phi_max) +
                         " within " + std::to_string(max_sweeps) + " sweeps");
}

void transfer_to_gas(const FaceFluxes& solids_before, const FaceFluxes& solids_after, FaceFluxes& gas) {
  for (std::size_t k = 0; k < gas.x.size(); ++k) gas.x.v[k] += solids_before.x.v[k] - solids_after.x.v[k];
  for (std::size_t k = 0; k < gas.y.size(); ++k) gas.y.v[k] += solids_before.y.v[k] - solids_after.y.v[k];
}

}  // namespace fluidbed::tfm
