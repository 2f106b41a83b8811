// Micro-benchmarks of the two-fluid model: the TVD face value kernel and one solver step on the paper's grid.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "numerics/tvd_limiter.hpp"
#include "numerics/band_pressure_solver.hpp"
#include "tfm/tfm_solver.hpp"

namespace {

using fluidbed::tvd::Limiter;

void bm_tvd_face_value(benchmark::State& state) {
  std::vector<double> phi(4096);
  for (std::size_t k = 0; k < phi.size(); ++k) phi[k] = static_cast<double>((k * 7919) % 101) / 101.0;
  for (auto _ : state) {
    double sum = 0.0;
    for (std::size_t k = 2; k + 2 < phi.size(); ++k) {
      sum += fluidbed::tvd::face_value<fluidbed::tvd::SuperbeeLaw>((k & 1) ? 1.0 : -1.0, phi[k - 2], phi[k - 1], phi[k],
                                           phi[k + 1]);
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(phi.size() - 4));
}
BENCHMARK(bm_tvd_face_value);

// One step of the paper's bed (30 x 50 cells) while the jet is on, after 0.05 s of start-up.
void bm_tfm_step(benchmark::State& state) {
  fluidbed::tfm::TfmConfig config;
  config.rheology = static_cast<fluidbed::tfm::SolidsRheology>(state.range(0));
  fluidbed::tfm::TfmSolver<2> solver(config);
  solver.advance_to(0.05);
  for (auto _ : state) benchmark::DoNotOptimize(solver.step(1.0));
  state.counters["sim_time_s"] = solver.time();
}
BENCHMARK(bm_tfm_step)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// The TFM's gas-pressure correction on the paper's 30 x 50 grid (open top, coefficients varying by +-30%): a
// factorisation and two substitutions (Arg 0, as the first solve of a step), or the substitutions alone (Arg 1, as
// the second solve of a step, which reuses the factorisation).
void bm_band_pressure(benchmark::State& state) {
  using namespace fluidbed;
  const Grid<2> grid = Grid<2>::uniform(Vec<2>{0.6, 1.0}, Index<2>{30, 50}, 0);
  const IndexBox<2>& cells = grid.owned;
  FaceFields<2> coeff(cells, 0, 0.0);
  for (int a = 0; a < 2; ++a)
    for_each(cells.faces(a), [&](const Index<2>& f) {
      const bool boundary = f[a] == cells.lo[a] || f[a] == cells.hi[a];
      const double c = 1.0 + 0.3 * std::sin(0.7 * f[0] + 1.3 * f[1] + 0.3 * a);
      coeff[a][f] = boundary ? (a == 1 && f[a] == cells.hi[a] ? 2.0 * c : 0.0) : c;
    });
  Field<2> rhs(cells, 0), x(cells, 0);
  for_each(cells, [&](const Index<2>& c) { rhs[c] = std::cos(0.3 * c[0]) * std::sin(0.2 * c[1] + 0.1); });
  auto solver = make_band_structured_solver<2>(grid);
  solver->solve(coeff, rhs, x, false);
  const bool reuse = state.range(0) == 1;
  for (auto _ : state) {
    solver->solve(coeff, rhs, x, reuse);
    benchmark::DoNotOptimize(x.data().data());
  }
}
BENCHMARK(bm_band_pressure)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
