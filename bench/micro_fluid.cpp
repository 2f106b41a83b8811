// One gas step (Eqs. 11-12, SIMPLEC) on the paper's 30 x 50 grid with a packed-bed voidage and Ergun beta.
#include <benchmark/benchmark.h>

#include <cmath>

#include "closures/drag.hpp"
#include "fluid/gas_solver.hpp"

namespace {

using namespace fluidbed;

void BM_GasStepPaperGrid(benchmark::State& state) {
  const Grid<2> grid = Grid<2>::uniform({0.6, 1.0}, {30, 50});
  GasConfig cfg;  // paper defaults: U_mf = 1.8 m/s everywhere, 30 m/s jet at the centre
  const PressureSolverKind kind = state.range(1) == 0 ? PressureSolverKind::Direct : PressureSolverKind::ConjugateGradient;
  GasSolver<2> gas(grid, cfg, kind);
  Field<2> eps = cell_field(grid, 1.0), beta = cell_field(grid, 0.0);
  const Field<2> zero = cell_field(grid, 0.0);
  for (int j = 0; j < 50; ++j)
    for (int i = 0; i < 30; ++i) {
      // Packed bed of height 0.54 m (Table 1) at eps = 0.4, freeboard above.
      eps(i, j) = grid.centre(1, j) < 0.54 ? 0.4 : 1.0;
      beta(i, j) = eps(i, j) < 1.0 ? beta_ergun_wen_yu({eps(i, j), 0.004, cfg.rho_g, cfg.mu_g, 1.8 / eps(i, j)}) : 0.0;
    }
  const double dt = static_cast<double>(state.range(0)) * 1e-5;
  double t = 0.0;
  int iterations = 0;
  for (auto _ : state) {
    t += dt;
    const GasStepReport rep = gas.advance(t, dt, eps, eps, beta, {zero, zero});
    iterations += rep.simple_iterations;
    benchmark::DoNotOptimize(rep);
  }
  state.counters["simple_iterations_per_step"] =
      benchmark::Counter(static_cast<double>(iterations) / static_cast<double>(state.iterations()));
}
// Second argument: the pressure-correction solver, 0 direct LDLT (the default), 1 warm-started CG + IC.
BENCHMARK(BM_GasStepPaperGrid)->ArgsProduct({{10, 20, 100}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
