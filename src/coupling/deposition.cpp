#include "coupling/deposition.hpp"

#include <algorithm>
#include <numbers>
#include <omp.h>

namespace fluidbed {

template <int Dim>
void CellEntries::build(const std::vector<CellWeights<Dim>>& weights, std::span<const std::uint32_t> id_order,
                        std::size_t cells) {
  const std::size_t n = id_order.size();
  const auto chunks = static_cast<std::size_t>(std::max(1, omp_get_max_threads()));
  if (chunk_count_.size() != chunks) chunk_count_.assign(chunks, {});
  // Pass 1, per chunk of the id order: the shares each chunk gives each cell.
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t cc = 0; cc < static_cast<std::ptrdiff_t>(chunks); ++cc) {
    const auto c = static_cast<std::size_t>(cc);
    std::vector<std::size_t>& count = chunk_count_[c];
    count.assign(cells, 0);
    for (std::size_t k = n * c / chunks; k < n * (c + 1) / chunks; ++k) {
      const CellWeights<Dim>& cw = weights[id_order[k]];
      for (int q = 0; q < cw.count; ++q) ++count[cw.cell[static_cast<std::size_t>(q)]];
    }
  }
  // Offsets: cell by cell, chunk after chunk within a cell (so a cell's shares come in id order).
  start_.assign(cells + 1, 0);
  std::size_t at = 0;
  for (std::size_t cell = 0; cell < cells; ++cell) {
    start_[cell] = at;
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::size_t m = chunk_count_[c][cell];
      chunk_count_[c][cell] = at;  // now the chunk's next place in this cell
      at += m;
    }
  }
  start_[cells] = at;
  slot_.resize(at);
  w_.resize(at);
  // Pass 2, per chunk: each share into its place.
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t cc = 0; cc < static_cast<std::ptrdiff_t>(chunks); ++cc) {
    const auto c = static_cast<std::size_t>(cc);
    std::vector<std::size_t>& next = chunk_count_[c];
    for (std::size_t k = n * c / chunks; k < n * (c + 1) / chunks; ++k) {
      const std::uint32_t i = id_order[k];
      const CellWeights<Dim>& cw = weights[i];
      for (int q = 0; q < cw.count; ++q) {
        const std::size_t e = next[cw.cell[static_cast<std::size_t>(q)]]++;
        slot_[e] = i;
        w_[e] = cw.w[static_cast<std::size_t>(q)];
      }
    }
  }
}

template <int Dim>
void Deposition<Dim>::deposit(const ParticleStore<Dim>& p, const std::vector<CellWeights<Dim>>& weights,
                              const Grid<Dim>& g, double depth, const DepositedFields<Dim>& out) {
  order_ = p.slots_in_id_order();
  deposit(p, weights, g, depth, out, order_);
}

template <int Dim>
void Deposition<Dim>::deposit(const ParticleStore<Dim>& p, const std::vector<CellWeights<Dim>>& weights,
                              const Grid<Dim>& g, double depth, const DepositedFields<Dim>& out,
                              std::span<const std::uint32_t> id_order) {
  Field<Dim>& eps = *out.eps;
  if (eps.box() != g.owned) eps = Field<Dim>(g.owned, 0);
  for (std::array<Field<Dim>, Dim>* v : {out.us, out.us_gas}) {
    for (Field<Dim>& f : *v) {
      if (f.box() != eps.box() || f.data().size() != eps.data().size()) f = Field<Dim>(g.owned, 0);
    }
  }
  if (out.beta->box() != eps.box()) *out.beta = Field<Dim>(g.owned, 0);
  const std::size_t ncell = eps.data().size();
  // Each cell's shares in order (a counting sort over the particles in that order, in chunks: the weights are read
  // in sequence, by the threads that wrote them), then per cell (any thread; dynamic chunks, since the bed fills
  // some cells and leaves the freeboard's empty) the sums and the cell values.
  entries_.build(weights, id_order, ncell);
  const double vcell = deposition_volume(g, depth);
  const double* r = p.radius.data();
  const double* kp = p.drag_k.data();
  std::array<const double*, Dim> v{};
  for (int a = 0; a < Dim; ++a) v[static_cast<std::size_t>(a)] = p.velocity(a).data();
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t cc = 0; cc < static_cast<std::ptrdiff_t>(ncell); ++cc) {
    const auto c = static_cast<std::size_t>(cc);
    // Solids volume, volume-weighted velocity sums, K, K-weighted velocity sums.
    std::array<double, 2 + 2 * Dim> s{};
    for (std::size_t e = entries_.begin(c); e < entries_.end(c); ++e) {
      const std::size_t i = entries_.slot(e);
      const double vp = 4.0 / 3.0 * std::numbers::pi * r[i] * r[i] * r[i];
      const double wv = entries_.weight(e) * vp;
      const double wk = entries_.weight(e) * kp[i];
      s[0] += wv;
      s[1 + Dim] += wk;
      for (int a = 0; a < Dim; ++a) {
        s[1 + static_cast<std::size_t>(a)] += wv * v[static_cast<std::size_t>(a)][i];
        s[2 + Dim + static_cast<std::size_t>(a)] += wk * v[static_cast<std::size_t>(a)][i];
      }
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

template void CellEntries::build<2>(const std::vector<CellWeights<2>>&, std::span<const std::uint32_t>, std::size_t);
template void CellEntries::build<3>(const std::vector<CellWeights<3>>&, std::span<const std::uint32_t>, std::size_t);
template class Deposition<2>;
template class Deposition<3>;

}  // namespace fluidbed
