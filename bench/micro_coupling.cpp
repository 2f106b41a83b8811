// CFD-DEM coupling kernels for the paper's case: 22,000 particles of 4 mm on the 30 x 50 grid (0.6 x 1.0 m).
// The particles sit on a random non-overlapping lattice placement in the lower 0.65 m (the settled bed of
// the paper would need a long settling run first); the mapping costs do not depend on the contacts.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "coupling/cfd_dem.hpp"
#include "coupling/voidage.hpp"
#include "dem/packing.hpp"
#include "closures/drag.hpp"

namespace {

using namespace fluidbed;

constexpr std::int64_t kParticles = 22000;

DemConfig paper_dem() {
  DemConfig c;  // Table 1: 0.6 x 1.0 m, 4 mm, 2700 kg/m^3, k = 800 N/m
  c.dt = 1e-4;
  return c;
}

ParticleStore<2> paper_particles(const DemConfig& dem) {
  PackingConfig pc;  // 22,000 particles, seed 1998
  pc.count = kParticles;
  return place_random<2>(dem, pc);
}

Grid<2> paper_grid() { return Grid<2>::uniform({0.6, 1.0}, {30, 50}); }

// Particle -> grid: counted voidage and the mean solids velocity (both scatters of the coupling).
void BM_VoidageAndSolidsVelocity(benchmark::State& state) {
  const DemConfig dem = paper_dem();
  const ParticleStore<2> p = paper_particles(dem);
  const Grid<2> grid = paper_grid();
  const auto method = static_cast<VoidageMethod>(state.range(0));
  Field<2> eps;
  std::array<Field<2>, 2> us;
  for (auto _ : state) {
    compute_voidage(p, grid, method, dem.species[0].diameter, eps);
    cell_solids_velocity<2>(p, grid, method, us);
    benchmark::DoNotOptimize(eps.data().data());
    benchmark::DoNotOptimize(us[0].data().data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(p.size()));
  state.SetLabel(method == VoidageMethod::Bilinear ? "bilinear" : "centre");
}
BENCHMARK(BM_VoidageAndSolidsVelocity)
    ->Arg(static_cast<int>(VoidageMethod::Bilinear))
    ->Arg(static_cast<int>(VoidageMethod::Centre))
    ->Unit(benchmark::kMicrosecond);

// Grid -> particle: what the coupling does for every particle after a gas step (gathered voidage, gas
// velocity and pressure gradient at the particle, Eq. 13 drag coefficient), written with the public API.
void BM_DragMapping(benchmark::State& state) {
  const DemConfig dem = paper_dem();
  ParticleStore<2> p = paper_particles(dem);
  const Grid<2> grid = paper_grid();
  GasConfig gc;
  GasSolver<2> gas(grid, gc);
  Field<2> eps;
  compute_voidage(p, grid, VoidageMethod::Bilinear, dem.species[0].diameter, eps);
  for (double& e : eps.data()) e = std::clamp(e, 0.3, 1.0);
  for (auto _ : state) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      const CellWeights cw = cell_weights(grid, eps, VoidageMethod::Bilinear, p.pos(i));
      const double e = std::min(gather(eps, cw), 1.0 - 1e-9);
      const Vec2 ug = gas.velocity_at(p.pos(i));
      const Vec2 gp = gas.pressure_gradient_at(p.pos(i));
      const double r = p.radius[i];
      const double vp = 4.0 / 3.0 * std::numbers::pi * r * r * r;
      const double beta = beta_ergun_wen_yu(DragInput{e, 2.0 * r, gc.rho_g, gc.mu_g, norm(ug - p.vel(i)) + 1.8});
      p.drag_k[i] = vp * beta / (1.0 - e);
      p.ugx[i] = ug.x;
      p.ugy[i] = ug.y;
      p.fx_ext[i] = -vp * gp.x;
      p.fy_ext[i] = -vp * gp.y;
    }
    benchmark::DoNotOptimize(p.drag_k.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(p.size()));
}
BENCHMARK(BM_DragMapping)->Unit(benchmark::kMicrosecond);

// One full CfdDemSimulation::advance: dem_substeps DEM steps, deposition, one gas step (paper inflow and jet),
// particle forces. Rate counter: particle-steps (particles x DEM steps) per second.
void BM_CfdDemAdvance(benchmark::State& state) {
  const DemConfig dem = paper_dem();
  CouplingConfig cc;
  cc.dem_substeps = static_cast<int>(state.range(0));
  CfdDemSimulation<2> sim(DemSolver<2>(dem, paper_particles(dem)), GasSolver<2>(paper_grid(), GasConfig{}), cc);
  sim.initialize();
  for (auto _ : state) sim.advance();
  state.counters["particle_steps_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(kParticles) * cc.dem_substeps,
      benchmark::Counter::kIsRate);
  state.counters["simple_iterations"] = benchmark::Counter(sim.last_gas_report().simple_iterations);
}
BENCHMARK(BM_CfdDemAdvance)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
