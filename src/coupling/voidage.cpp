#include "coupling/voidage.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fluidbed {

template <int Dim>
CellWeights<Dim> cell_weights(const Grid<Dim>& g, const Field<Dim>& layout, VoidageMethod method, const Vec<Dim>& x) {
  CellWeights<Dim> cw;
  if (method == VoidageMethod::Centre) {
    cw.cell[0] = layout.index(g.cell(x));
    cw.w[0] = 1.0;
    cw.count = 1;
    return cw;
  }
  // Multilinear weights between the 2^Dim surrounding cell centres; an index outside the domain is clamped, which
  // folds the weight of the missing cell into the boundary cell, or wrapped on a periodic axis (the cell beyond
  // the plane is the one at the other end).
  std::array<int, Dim> lo{}, hi{};
  std::array<double, Dim> frac{};
  for (int a = 0; a < Dim; ++a) {
    const double f = (x[a] - g.origin[a]) / g.h[a] - 0.5;
    const double ff = std::floor(f);
    frac[a] = std::clamp(f - ff, 0.0, 1.0);
    const int i0 = static_cast<int>(ff);
    if (g.periodic[static_cast<std::size_t>(a)]) {
      lo[a] = g.wrap(a, i0);
      hi[a] = g.wrap(a, i0 + 1);
    } else {
      lo[a] = std::clamp(i0, g.domain.lo[a], g.domain.hi[a] - 1);
      hi[a] = std::clamp(i0 + 1, g.domain.lo[a], g.domain.hi[a] - 1);
    }
  }
  // Corner k takes the high neighbour along axis a when bit a of k is set (axis 0 fastest, as the 2D code had it).
  for (int k = 0; k < CellWeights<Dim>::kMax; ++k) {
    Index<Dim> c{};
    double w = 1.0;
    for (int a = 0; a < Dim; ++a) {
      const bool up = (k >> a) & 1;
      c[a] = up ? hi[a] : lo[a];
      w = a == 0 ? (up ? frac[a] : 1.0 - frac[a]) : w * (up ? frac[a] : 1.0 - frac[a]);
    }
    cw.cell[static_cast<std::size_t>(k)] = layout.index(c);
    cw.w[static_cast<std::size_t>(k)] = w;
  }
  cw.count = CellWeights<Dim>::kMax;
  return cw;
}

template <int Dim>
void particle_cell_weights(const ParticleStore<Dim>& p, const Grid<Dim>& g, const Field<Dim>& layout,
                           VoidageMethod method, std::vector<CellWeights<Dim>>& out) {
  out.resize(p.size());
  const auto n = static_cast<std::ptrdiff_t>(p.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    out[i] = cell_weights(g, layout, method, p.pos(i));
  }
}

// The scatters below run serially in storage order: a fixed order makes the sums independent of the thread
// count, and they cost little next to the contact forces.
template <int Dim>
void compute_voidage(const ParticleStore<Dim>& p, const std::vector<CellWeights<Dim>>& weights, const Grid<Dim>& g,
                     double depth, Field<Dim>& eps) {
  if (eps.box() != g.owned) eps = Field<Dim>(g.owned, 0);
  std::vector<double> vol(eps.data().size(), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double vp = 4.0 / 3.0 * M_PI * p.radius[i] * p.radius[i] * p.radius[i];
    const CellWeights<Dim>& cw = weights[i];
    for (int k = 0; k < cw.count; ++k) vol[cw.cell[static_cast<std::size_t>(k)]] += cw.w[static_cast<std::size_t>(k)] * vp;
  }
  const double vcell = deposition_volume(g, depth);
  for (std::size_t c = 0; c < vol.size(); ++c) eps.data()[c] = 1.0 - vol[c] / vcell;
}

template <int Dim>
void cell_solids_velocity(const ParticleStore<Dim>& p, const std::vector<CellWeights<Dim>>& weights,
                          const Grid<Dim>& g, std::array<Field<Dim>, Dim>& us) {
  for (Field<Dim>& f : us) {
    if (f.box() != g.owned) f = Field<Dim>(g.owned, 0);
  }
  const std::size_t n = us[0].data().size();
  std::vector<double> vol(n, 0.0);
  std::array<std::vector<double>, Dim> mom;
  for (auto& m : mom) m.assign(n, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double vp = p.radius[i] * p.radius[i] * p.radius[i];  // constant factor cancels
    const CellWeights<Dim>& cw = weights[i];
    for (int k = 0; k < cw.count; ++k) {
      const std::size_t c = cw.cell[static_cast<std::size_t>(k)];
      const double w = cw.w[static_cast<std::size_t>(k)] * vp;
      vol[c] += w;
      for (int a = 0; a < Dim; ++a) mom[a][c] += w * p.velocity(a)[i];
    }
  }
  for (std::size_t c = 0; c < n; ++c) {
    for (int a = 0; a < Dim; ++a) us[a].data()[c] = vol[c] > 0.0 ? mom[a][c] / vol[c] : 0.0;
  }
}


#define FLUIDBED_VOIDAGE(D)                                                                                       \
  template CellWeights<D> cell_weights(const Grid<D>&, const Field<D>&, VoidageMethod, const Vec<D>&);           \
  template void particle_cell_weights(const ParticleStore<D>&, const Grid<D>&, const Field<D>&, VoidageMethod,   \
                                      std::vector<CellWeights<D>>&);                                             \
  template void compute_voidage(const ParticleStore<D>&, const std::vector<CellWeights<D>>&, const Grid<D>&,     \
                                double, Field<D>&);                                                              \
  template void cell_solids_velocity<D>(const ParticleStore<D>&, const std::vector<CellWeights<D>>&, const Grid<D>&, \
                                     std::array<Field<D>, D>&);
FLUIDBED_VOIDAGE(2)
FLUIDBED_VOIDAGE(3)
#undef FLUIDBED_VOIDAGE

}  // namespace fluidbed
