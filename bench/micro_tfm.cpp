// Micro-benchmarks of the two-fluid model: the TVD face value kernel and one solver step on the paper's grid.
#include <benchmark/benchmark.h>

#include <vector>

#include "core/tvd_limiter.hpp"
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

}  // namespace

BENCHMARK_MAIN();
