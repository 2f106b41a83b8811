#pragma once
// Geometry of a uniform Cartesian grid in Dim dimensions: cell c spans origin + c h to origin + (c + 1) h along
// every axis. `domain` is the whole grid's cell box, `owned` the block this process computes (the whole domain on
// one process; a sub-block of it once the grid is decomposed across ranks), `ghost` the layers of cells around
// the owned block that fields store for stencils: filled by physical boundary conditions at the domain's sides,
// by the neighbouring rank's values elsewhere (Comm::exchange_halo).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "core/index_box.hpp"
#include "core/vec.hpp"

namespace fluidbed {

template <int Dim>
struct Grid {
  IndexBox<Dim> domain{};
  IndexBox<Dim> owned{};
  Vec<Dim> h{};       ///< cell size per axis, m
  Vec<Dim> origin{};  ///< low corner of the domain, m
  int ghost = 1;      ///< ghost layers around `owned`
  /// Periodic axes: the domain's two sides along such an axis are one plane, so there is no physical boundary
  /// there (at_domain_side is false) and the ghosts beyond it hold the values of the opposite side.
  std::array<bool, Dim> periodic{};

  /// The whole box [0, extent] split into n cells per axis, owned entirely by this process.
  static Grid uniform(const Vec<Dim>& extent, const Index<Dim>& n, int ghost_layers = 1) {
    Grid g;
    for (int a = 0; a < Dim; ++a) {
      g.domain.lo[a] = 0;
      g.domain.hi[a] = n[a];
      g.h[a] = extent[a] / n[a];
    }
    g.owned = g.domain;
    g.ghost = ghost_layers;
    return g;
  }

  int n(int a) const { return domain.extent(a); }
  double length(int a) const { return n(a) * h[a]; }
  std::size_t cells() const { return domain.count(); }
  /// Length x width in 2D (per metre of depth), volume in 3D.
  double cell_measure() const {
    double m = 1.0;
    for (int a = 0; a < Dim; ++a) m *= h[a];
    return m;
  }
  /// Area of a face normal to axis a (per metre of depth in 2D).
  double face_measure(int a) const { return cell_measure() / h[a]; }
  double centre(int a, int i) const { return origin[a] + (i + 0.5) * h[a]; }
  Vec<Dim> centre(const Index<Dim>& c) const {
    Vec<Dim> x{};
    for (int a = 0; a < Dim; ++a) x[a] = centre(a, c[a]);
    return x;
  }
  /// Position of face i (the low face of cell i) along axis a.
  double face(int a, int i) const { return origin[a] + i * h[a]; }
  /// Cell of the domain holding x along axis a, clamped to the domain (a point on the far side is in the last cell).
  int cell(int a, double x) const {
    return std::clamp(static_cast<int>(std::floor((x - origin[a]) / h[a])), domain.lo[a], domain.hi[a] - 1);
  }
  Index<Dim> cell(const Vec<Dim>& x) const {
    Index<Dim> c{};
    for (int a = 0; a < Dim; ++a) c[a] = cell(a, x[a]);
    return c;
  }
  /// Whether the owned block touches the domain's side (a physical boundary, not a neighbour rank nor the
  /// opposite side of a periodic axis).
  bool at_domain_side(int a, bool high) const {
    if (periodic[static_cast<std::size_t>(a)]) return false;
    return high ? owned.hi[a] == domain.hi[a] : owned.lo[a] == domain.lo[a];
  }
  bool any_periodic() const {
    bool any = false;
    for (int a = 0; a < Dim; ++a) any = any || periodic[static_cast<std::size_t>(a)];
    return any;
  }
  /// Cell or face index i along axis a mapped into [domain.lo, domain.hi) on a periodic axis (unchanged on the
  /// others): the period is the number of cells, so face n of a periodic axis is face 0.
  int wrap(int a, int i) const {
    if (!periodic[static_cast<std::size_t>(a)]) return i;
    const int n = domain.extent(a);
    const int r = (i - domain.lo[a]) % n;
    return domain.lo[a] + (r < 0 ? r + n : r);
  }
};

}  // namespace fluidbed
