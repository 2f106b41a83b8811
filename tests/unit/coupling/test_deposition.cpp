// The fused, threaded deposition (src/coupling/deposition.hpp) against the serial reference scatters of
// voidage.hpp (compute_voidage, cell_solids_velocity) and against direct sums for beta and the K-weighted velocity,
// in 2D and 3D, with more particles than one block so that the block partial sums are exercised. The two differ
// only in the order of additions: a cell value is a sum of at most a few hundred terms of one sign, so the
// tolerance is 1e-12 relative. The thread-count independence is exact: every thread count gives the same bits.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "coupling/deposition.hpp"

namespace fluidbed {
namespace {

template <int Dim>
ParticleStore<Dim> random_particles(const Grid<Dim>& g, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0), ud(0.001, 0.004), uv(-2.0, 2.0), uk(0.0, 1e-3);
  ParticleStore<Dim> p;
  for (int k = 0; k < n; ++k) {
    Species s;
    s.diameter = ud(rng);
    Vec<Dim> x{}, v{};
    for (int a = 0; a < Dim; ++a) x[a] = g.origin[a] + u01(rng) * g.length(a);
    for (int a = 0; a < Dim; ++a) v[a] = uv(rng);
    p.add(k, 0, s, x, v);
    p.drag_k.back() = k % 7 == 0 ? 0.0 : uk(rng);
  }
  // Storage sorted along the last axis, as the DEM keeps it (blocks then touch slabs of cells).
  std::vector<std::size_t> order(p.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return p.coord(Dim - 1)[a] < p.coord(Dim - 1)[b]; });
  p.permute(order);
  return p;
}

template <int Dim>
struct Out {
  Field<Dim> eps, beta;
  std::array<Field<Dim>, Dim> us, us_gas;
  DepositedFields<Dim> view() { return {&eps, &us, &beta, &us_gas}; }
};

template <int Dim>
void check_against_reference(const Grid<Dim>& g, int n) {
  const ParticleStore<Dim> p = random_particles(g, n, 5);
  const double depth = 0.004;
  Field<Dim> layout(g.owned, 0);
  std::vector<CellWeights<Dim>> w;
  particle_cell_weights(p, g, layout, VoidageMethod::Bilinear, w);

  Field<Dim> eps_ref;
  std::array<Field<Dim>, Dim> us_ref;
  compute_voidage(p, w, g, depth, eps_ref);
  cell_solids_velocity<Dim>(p, w, g, us_ref);
  const std::size_t ncell = layout.data().size();
  std::vector<double> k(ncell, 0.0);
  std::array<std::vector<double>, Dim> ku;
  for (auto& v : ku) v.assign(ncell, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int m = 0; m < w[i].count; ++m) {
      const std::size_t c = w[i].cell[static_cast<std::size_t>(m)];
      k[c] += w[i].w[static_cast<std::size_t>(m)] * p.drag_k[i];
      for (int a = 0; a < Dim; ++a) ku[a][c] += w[i].w[static_cast<std::size_t>(m)] * p.drag_k[i] * p.velocity(a)[i];
    }
  }
  const double vcell = deposition_volume(g, depth);

  Deposition<Dim> dep;
  Out<Dim> out;
  dep.deposit(p, w, g, depth, out.view());
  double err_eps = 0.0, err_us = 0.0, err_beta = 0.0, err_usg = 0.0;
  for (std::size_t c = 0; c < ncell; ++c) {
    err_eps = std::max(err_eps, std::abs(out.eps.data()[c] - eps_ref.data()[c]));
    err_beta = std::max(err_beta, std::abs(out.beta.data()[c] - k[c] / vcell) / std::max(k[c] / vcell, 1e-300));
    for (int a = 0; a < Dim; ++a) {
      err_us = std::max(err_us, std::abs(out.us[a].data()[c] - us_ref[a].data()[c]));
      const double usg = k[c] > 0.0 ? ku[a][c] / k[c] : us_ref[a].data()[c];
      err_usg = std::max(err_usg, std::abs(out.us_gas[a].data()[c] - usg));
    }
  }
  std::printf("Dim %d, %d particles, %zu cells: max |d eps| %.3g, |d us| %.3g m/s, rel |d beta| %.3g, |d us_gas| %.3g m/s\n",
              Dim, n, ncell, err_eps, err_us, err_beta, err_usg);
  EXPECT_LT(err_eps, 1e-12);
  EXPECT_LT(err_us, 1e-12 * 2.0);
  EXPECT_LT(err_beta, 1e-12);
  EXPECT_LT(err_usg, 1e-12 * 2.0);

  // The same bits for every thread count (and for a second call reusing the buffers).
  for (int threads : {1, 2, 3, 5}) {
    omp_set_num_threads(threads);
    Out<Dim> again;
    dep.deposit(p, w, g, depth, again.view());
    EXPECT_EQ(again.eps.data(), out.eps.data()) << threads << " threads";
    EXPECT_EQ(again.beta.data(), out.beta.data()) << threads << " threads";
    for (int a = 0; a < Dim; ++a) {
      EXPECT_EQ(again.us[a].data(), out.us[a].data()) << threads << " threads";
      EXPECT_EQ(again.us_gas[a].data(), out.us_gas[a].data()) << threads << " threads";
    }
  }
}

TEST(Deposition, MatchesSerialScattersAndIgnoresThreads2d) {
  check_against_reference<2>(Grid<2>::uniform({0.3, 0.5}, {15, 25}, 0), 9000);
}

TEST(Deposition, MatchesSerialScattersAndIgnoresThreads3d) {
  Grid<3> g = Grid<3>::uniform({0.1, 0.12, 0.045}, {5, 6, 3}, 0);
  g.origin = {0.1, -0.05, 0.02};
  check_against_reference<3>(g, 7000);
}

}  // namespace
}  // namespace fluidbed
