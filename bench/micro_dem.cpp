// DEM kernels on a dense bed of the paper's size (Table 1: 22,000 spheres of 4 mm in a 0.6 m wide bed):
// cell sort with the store permutation, neighbour-list build, contact forces (Eqs. 2-9) and a whole step
// (Eq. 10), in particles per second (particle-steps per second for the step). Run with 1 and 2 OpenMP threads.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <random>

#include "dem/dem_solver.hpp"
#include "dem/neighbor_list.hpp"

namespace {

using namespace fluidbed;

constexpr std::size_t kParticles = 22000;

/// Hexagonal packing standing on the floor, rows 0.05% closer than touching so that every particle has its
/// six contacts, with a 10 um jitter and small random velocities: the contact structure of a settled bed
/// (about 0.51 m high, near the paper's 0.54 m), without spending seconds on settling.
ParticleStore<2> hex_bed(const DemConfig& c) {
  const Species& s = c.species[0];
  const double d = s.diameter, r = s.radius();
  const double row = d * std::sqrt(3.0) / 2.0 * 0.9995;
  std::mt19937_64 rng(1998);
  auto jitter = [&rng](double a) { return a * (2.0 * static_cast<double>(rng() >> 11) * 0x1.0p-53 - 1.0); };
  ParticleStore<2> p;
  std::int64_t id = 0;
  for (int j = 0; static_cast<std::size_t>(id) < kParticles; ++j) {
    const double x0 = r + ((j % 2) ? r : 0.0) + 1e-5;
    for (double x = x0; x <= c.domain.width - r - 1e-5 && static_cast<std::size_t>(id) < kParticles; x += d) {
      p.add(id++, 0, s, {x + jitter(1e-5), r + j * row + jitter(1e-5)}, {jitter(0.01), jitter(0.01)});
    }
  }
  return p;
}

DemConfig bed_config() { return DemConfig{}; }  // the paper's Table 1 values

void set_counters(benchmark::State& state) {
  state.counters["particles/s"] = benchmark::Counter(static_cast<double>(kParticles) * state.iterations(),
                                                     benchmark::Counter::kIsRate);
  state.counters["threads"] = static_cast<double>(omp_get_max_threads());
}

void BM_CellSort(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  const DemConfig c = bed_config();
  ParticleStore<2> p = hex_bed(c);
  const double cell = c.species[0].diameter + c.skin;
  for (auto _ : state) {
    p.permute(sort_by_cell(p, cell));
    benchmark::DoNotOptimize(p.x.data());
  }
  set_counters(state);
}

void BM_NeighborListBuild(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  const DemConfig c = bed_config();
  ParticleStore<2> p = hex_bed(c);
  const double cell = c.species[0].diameter + c.skin;
  p.permute(sort_by_cell(p, cell));
  NeighborList<2> nl;
  for (auto _ : state) {
    build_neighbor_list(p, cell, c.skin, nl);
    benchmark::DoNotOptimize(nl.partner.data());
  }
  state.counters["entries/particle"] = static_cast<double>(nl.entries()) / kParticles;
  set_counters(state);
}

void BM_ContactForces(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  DemSolver<2> s(bed_config(), hex_bed(bed_config()));
  s.step();  // builds the neighbour list
  for (auto _ : state) benchmark::DoNotOptimize(s.compute_forces());
  set_counters(state);
}

void BM_DemStep(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  DemSolver<2> s(bed_config(), hex_bed(bed_config()));
  s.step();
  const std::uint64_t rebuilds0 = s.rebuild_count();
  for (auto _ : state) s.step();
  state.counters["rebuilds/step"] =
      static_cast<double>(s.rebuild_count() - rebuilds0) / static_cast<double>(state.iterations());
  set_counters(state);
}

BENCHMARK(BM_CellSort)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NeighborListBuild)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ContactForces)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DemStep)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
