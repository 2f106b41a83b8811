#include "coupling/deposition.hpp"

#include <algorithm>
#include <numbers>

namespace fluidbed {

template <int Dim>
void Deposition<Dim>::deposit(const ParticleStore<Dim>& p, const std::vector<CellWeights<Dim>>& weights,
                              const Grid<Dim>& g, double depth, const DepositedFields<Dim>& out) {
  Field<Dim>& eps = *out.eps;
  if (eps.box() != g.owned) eps = Field<Dim>(g.owned, 0);
  for (std::array<Field<Dim>, Dim>* v : {out.us, out.us_gas}) {
    for (Field<Dim>& f : *v) {
      if (f.box() != eps.box() || f.data().size() != eps.data().size()) f = Field<Dim>(g.owned, 0);
    }
  }
  if (out.beta->box() != eps.box()) *out.beta = Field<Dim>(g.owned, 0);
  const std::size_t ncell = eps.data().size();
  const std::size_t n = p.size();
  const std::size_t nblock = (n + kBlock - 1) / kBlock;
  if (blocks_.size() < nblock) blocks_.resize(nblock);

  // Pass 1, per block (any thread): the cell range its particles touch, then its partial sums in storage order.
  // Particles are stored in spatial order, so a block's range is a slab of the grid and the buffers stay small.
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t bb = 0; bb < static_cast<std::ptrdiff_t>(nblock); ++bb) {
    const auto b = static_cast<std::size_t>(bb);
    Block& blk = blocks_[b];
    const std::size_t i0 = b * kBlock;
    const std::size_t i1 = std::min(n, i0 + kBlock);
    std::size_t lo = ncell, hi = 0;
    for (std::size_t i = i0; i < i1; ++i) {
      const CellWeights<Dim>& cw = weights[i];
      for (int k = 0; k < cw.count; ++k) {
        lo = std::min(lo, cw.cell[static_cast<std::size_t>(k)]);
        hi = std::max(hi, cw.cell[static_cast<std::size_t>(k)] + 1);
      }
    }
    if (lo > hi) lo = hi = 0;
    blk.first_cell = lo;
    blk.end_cell = hi;
    blk.sums.assign((hi - lo) * kStride, 0.0);
    for (std::size_t i = i0; i < i1; ++i) {
      const double r = p.radius[i];
      const double vp = 4.0 / 3.0 * std::numbers::pi * r * r * r;
      const double kp = p.drag_k[i];
      std::array<double, Dim> v{};
      for (int a = 0; a < Dim; ++a) v[static_cast<std::size_t>(a)] = p.velocity(a)[i];
      const CellWeights<Dim>& cw = weights[i];
      for (int k = 0; k < cw.count; ++k) {
        double* s = blk.sums.data() + (cw.cell[static_cast<std::size_t>(k)] - lo) * kStride;
        const double wv = cw.w[static_cast<std::size_t>(k)] * vp;
        const double wk = cw.w[static_cast<std::size_t>(k)] * kp;
        s[0] += wv;
        s[1 + Dim] += wk;
        for (int a = 0; a < Dim; ++a) {
          s[1 + a] += wv * v[static_cast<std::size_t>(a)];
          s[2 + Dim + a] += wk * v[static_cast<std::size_t>(a)];
        }
      }
    }
  }

  // Pass 2, per cell (any thread): the blocks' sums added in block order, then the cell values.
  const double vcell = deposition_volume(g, depth);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t cc = 0; cc < static_cast<std::ptrdiff_t>(ncell); ++cc) {
    const auto c = static_cast<std::size_t>(cc);
    std::array<double, kStride> s{};
    for (std::size_t b = 0; b < nblock; ++b) {
      const Block& blk = blocks_[b];
      if (c < blk.first_cell || c >= blk.end_cell) continue;
      const double* q = blk.sums.data() + (c - blk.first_cell) * kStride;
      for (std::size_t m = 0; m < kStride; ++m) s[m] += q[m];
    }
    const double vol = s[0];
    const double k = s[1 + Dim];
    eps.data()[c] = 1.0 - vol / vcell;
    out.beta->data()[c] = k / vcell;
    for (int a = 0; a < Dim; ++a) {
      const double us = vol > 0.0 ? s[1 + static_cast<std::size_t>(a)] / vol : 0.0;
      (*out.us)[static_cast<std::size_t>(a)].data()[c] = us;
      (*out.us_gas)[static_cast<std::size_t>(a)].data()[c] = k > 0.0 ? s[2 + Dim + static_cast<std::size_t>(a)] / k : us;
    }
  }
}

template class Deposition<2>;
template class Deposition<3>;

}  // namespace fluidbed
