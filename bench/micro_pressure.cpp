// One gas step's pressure solves through each structured backend (docs/performance.md section 12): a fresh solve
// (factorisation or multigrid set-up), then 8 more with the coefficients moved by 1e-3 and a warm start, as the
// SIMPLE loop calls them. The problem: a (2 Dim + 1)-point Laplacian with coefficients varying by +-30% (as a
// voidage-weighted pressure correction has them), fixed-pressure faces on the low and high sides of the last axis.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "numerics/band_pressure_solver.hpp"
#include "numerics/multigrid_cg.hpp"
#include "numerics/pressure_correction.hpp"
#include "numerics/structured_solver_hypre.hpp"

namespace {

using namespace fluidbed;

template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> backend(const Grid<Dim>& grid, int kind) {
  if (kind == 0) return make_eigen_structured_solver<Dim>(grid);
  if (kind == 1) return make_eigen_structured_solver<Dim>(grid, PressureSolverKind::ConjugateGradient);
  if (kind == 2) return make_hypre_structured_solver<Dim>(grid);
  if (kind == 4) return make_band_structured_solver<Dim>(grid, BandReuse::Preconditioner);
  return make_multigrid_cg_solver<Dim>(grid, serial_comm(), {.tolerance = 1e-12});
}

template <int Dim>
void BM_PressureStep(benchmark::State& state, Index<Dim> n) {
  const int kind = static_cast<int>(state.range(0));
  if (kind == 2 && !hypre_available()) {
    state.SkipWithError("built without hypre");
    return;
  }
  Vec<Dim> ext{};
  for (int a = 0; a < Dim; ++a) ext[a] = 1.0;
  const Grid<Dim> grid = Grid<Dim>::uniform(ext, n, 0);
  const IndexBox<Dim>& cells = grid.owned;
  FaceFields<Dim> coeff(cells, 0, 0.0);
  for (int a = 0; a < Dim; ++a) {
    for_each(cells.faces(a), [&](const Index<Dim>& f) {
      const bool boundary = f[a] == cells.lo[a] || f[a] == cells.hi[a];
      coeff[a][f] = boundary ? (a == Dim - 1 ? 2.0 : 0.0) : 1.0 + 0.3 * std::sin(0.7 * f[0] + 0.3 * a);
    });
  }
  Field<Dim> rhs(cells, 0);
  for_each(cells, [&](const Index<Dim>& c) { rhs[c] = std::sin(0.37 * c[0] + 0.11 * c[Dim - 1]); });
  std::unique_ptr<StructuredSolver<Dim>> solver = backend<Dim>(grid, kind);
  for (auto _ : state) {
    Field<Dim> x(cells, 0);
    FaceFields<Dim> c = coeff;
    for (int it = 0; it < 9; ++it) {
      for (int a = 0; a < Dim; ++a)
        for (double& v : c[a].data()) v *= 1.0 + 1e-3 * ((it + a) % 3 - 1);
      solver->solve(c, rhs, x, it > 0);
    }
    benchmark::DoNotOptimize(x.data().data());
  }
}

void BM_PressureStepPaperGrid(benchmark::State& state) { BM_PressureStep<2>(state, {30, 50}); }
void BM_PressureStep3d100k(benchmark::State& state) { BM_PressureStep<3>(state, {40, 60, 42}); }

// Argument: the backend, 0 Eigen's Cholesky reused as CG preconditioner, 1 eigen-cg (IC-CG), 2 hypre-pfmg, 3
// cg-multigrid, 4 the band LDL^T reused as CG preconditioner (what "eigen" runs on a 2D grid since section 35).
// In 3D Eigen's factorisation of 100,800 cells takes minutes: only the iterative backends, IC-CG once.
BENCHMARK(BM_PressureStepPaperGrid)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PressureStep3d100k)->Arg(1)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PressureStep3d100k)->Arg(2)->Arg(3)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
