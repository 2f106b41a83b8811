// The per-particle and per-pair work allocates nothing once its buffers have grown to the bed (issue 31, item 5:
// the kernels a GPU port will reuse take arrays and keep their work space; an allocation inside a step is also
// a lock and a page fault on the critical path). This program replaces malloc, calloc and realloc (glibc's
// interposition, forwarding to __libc_*) and counts the calls made on any thread while a window is open. It is
// a verification program, not built under the sanitizers, which intercept malloc themselves.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <cstdio>

#include "../dem/dem_closed_form.hpp"
#include "coupling/cfd_dem.hpp"
#include "dem/dem_solver.hpp"
#include "dem/packing.hpp"

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
}

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_calls{0};
inline void count() {
  if (g_counting.load(std::memory_order_relaxed)) g_calls.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

extern "C" {
void* malloc(std::size_t n) {
  count();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) {
  count();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) {
  count();
  return __libc_realloc(p, n);
}
}

namespace fluidbed {
namespace {

// The allocations `work` makes.
template <class F>
long allocations_in(F&& work) {
  g_calls = 0;
  g_counting = true;
  work();
  g_counting = false;
  return g_calls.load();
}

// 2000 of the paper's particles falling into a 0.1 m box from random places: contacts made and broken, the
// neighbour list rebuilt every few steps.
ParticleStore<2> falling_bed(const DemConfig& c) {
  PackingConfig pc;
  pc.count = 2000;
  pc.x_max = 0.1;
  pc.y_max = 0.42;
  pc.seed = 3;
  return place_random<2>(c, pc);
}

// Steps of `sim` (a DemSolver or a CfdDemSimulation) whose neighbour list was not rebuilt, and their allocations.
struct Window {
  int steps = 0, rebuilds = 0;
  long quiet_allocations = 0, rebuild_allocations = 0;
};
template <class Step, class Rebuilds>
Window count_steps(int n, Step&& step, Rebuilds&& rebuilds) {
  Window w;
  for (int s = 0; s < n; ++s) {
    const std::uint64_t before = rebuilds();
    const long calls = allocations_in(step);
    const bool rebuilt = rebuilds() != before;
    ++w.steps;
    w.rebuilds += rebuilt ? 1 : 0;
    (rebuilt ? w.rebuild_allocations : w.quiet_allocations) += calls;
  }
  std::printf("%d steps: %d rebuilt the list (%ld allocations), %d did not (%ld allocations)\n", w.steps, w.rebuilds,
              w.rebuild_allocations, w.steps - w.rebuilds, w.quiet_allocations);
  return w;
}

TEST(NoAllocation, DemStepsBetweenRebuilds2d) {
  const DemConfig c =
      test::one_species_config(0.004, 2700.0, 800.0, 0.9, 0.3, 2e-4, {0.0, -9.81}, 0.1, 1.0, WallConfig{});
  DemSolver<2> dem(c, falling_bed(c));
  for (int s = 0; s < 4000; ++s) dem.step();  // the bed lands: lists and springs grow to their size
  const Window w = count_steps(500, [&] { dem.step(); }, [&] { return dem.rebuild_count(); });
  ASSERT_GT(w.steps - w.rebuilds, 100);
  EXPECT_EQ(w.quiet_allocations, 0);
}

TEST(NoAllocation, DemStepsBetweenRebuilds3d) {
  const Vec3 box{0.04, 0.2, 0.04};
  const DemConfig c = test::one_species_config_3d(0.004, 2700.0, 800.0, 0.9, 0.3, 1e-4, {0.0, -9.81, 0.0}, box,
                                                  test::closed_box());
  PackingConfig pc = test::box_packing(box, 2000, 7);
  pc.y_max = 0.15;
  DemSolver<3> dem(c, place_random<3>(c, pc));
  for (int s = 0; s < 4000; ++s) dem.step();
  const Window w = count_steps(500, [&] { dem.step(); }, [&] { return dem.rebuild_count(); });
  ASSERT_GT(w.steps - w.rebuilds, 100);
  EXPECT_EQ(w.quiet_allocations, 0);
}

// A coupled gas step: two DEM steps, the kernel weights, the deposition, the gas (SIMPLE, the pressure solve), the
// fluid forces on the particles. A 5 m/s jet keeps the bed moving: contacts made and broken, the list rebuilt
// every other step or so.
TEST(NoAllocation, CoupledStepsBetweenRebuilds2d) {
  const DemConfig c =
      test::one_species_config(0.004, 2700.0, 800.0, 0.9, 0.3, 1e-4, {0.0, -9.81}, 0.1, 1.0, WallConfig{});
  GasConfig gas;
  gas.boundary.inlet_velocity = 1.0;
  gas.boundary.jets = {InletJet{0.05, 0.02, 1.5, 0.0, 10.0}};
  CouplingConfig cc;
  cc.dem_substeps = 2;
  DemSolver<2> landed(c, falling_bed(c));
  for (int s = 0; s < 4000; ++s) landed.step();  // the bed lands without gas first (cheaper)
  CfdDemSimulation<2> sim(DemSolver<2>(c, landed.particles()),
                          GasSolver<2>(Grid<2>::uniform({0.1, 1.0}, {10, 100}), gas), cc);
  sim.initialize();
  for (int s = 0; s < 600; ++s) sim.advance();
  const Window w = count_steps(200, [&] { sim.advance(); }, [&] { return sim.dem().rebuild_count(); });
  ASSERT_GT(w.steps - w.rebuilds, 50);
  EXPECT_EQ(w.quiet_allocations, 0);
}

}  // namespace
}  // namespace fluidbed
