#pragma once
// A small settled bed of the paper's particles (4 mm, 2700 kg/m^3, Table 1), made once per test binary and
// shared by the bed tests: 1000 particles in a 0.1 m wide box (25 diameters), about 0.15 m deep.
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "coupling/cfd_dem.hpp"
#include "coupling/voidage.hpp"
#include "dem/packing.hpp"
#include "dem/settle.hpp"
#include "closures/drag.hpp"

namespace fluidbed::coupling_test {

// Up to a thousand particles and a few hundred cells: OpenMP synchronisation costs more than the work on a
// loaded machine, and results do not depend on the thread count, so the bed tests run on one thread.
class ScopedOneThread {
 public:
  ScopedOneThread() : saved_(omp_get_max_threads()) { omp_set_num_threads(1); }
  ~ScopedOneThread() { omp_set_num_threads(saved_); }
  ScopedOneThread(const ScopedOneThread&) = delete;
  ScopedOneThread& operator=(const ScopedOneThread&) = delete;

 private:
  int saved_;
};

inline constexpr double kWidth = 0.1;
inline constexpr double kHeight = 0.4;
inline constexpr int kNx = 10;  // 1 cm cells, 2.5 particle diameters
inline constexpr int kNy = 40;
inline constexpr int kCount = 1000;

struct SettledBed {
  DemConfig dem;
  ParticleStore<2> particles;
  double bed_height = 0.0;  ///< m
  double eps_interior = 0.0;  ///< mean counted voidage of the cells well inside the bed
  double settle_time = 0.0;
};

inline Grid<2> bed_grid() { return Grid<2>::uniform({kWidth, kHeight}, {kNx, kNy}); }

inline DemConfig bed_dem_config() {
  DemConfig c;  // paper particles, k = 800 N/m, restitution 0.9, friction 0.3
  c.domain.width = kWidth;
  c.domain.height = kHeight;
  c.dt = 2e-4;
  return c;
}

/// Mean counted voidage (bilinear, depth = d_p) over the cells at least one cell away from the side walls and
/// the distributor and two cells below the bed surface, where neither folding nor the surface enters.
inline double interior_voidage(const ParticleStore<2>& p, double bed_height) {
  const Grid<2> g = bed_grid();
  Field<2> eps;
  compute_voidage(p, g, VoidageMethod::Bilinear, Species{}.diameter, eps);
  const int j_top = static_cast<int>(std::floor(bed_height / g.h[1])) - 2;
  double sum = 0.0;
  int n = 0;
  for (int j = 1; j < j_top; ++j) {
    for (int i = 1; i < g.n(0) - 1; ++i) {
      sum += eps(i, j);
      ++n;
    }
  }
  return sum / n;
}

/// Particles placed at random in the box fall and settle in vacuum (the paper's initial condition).
inline const SettledBed& settled_bed() {
  static const SettledBed bed = [] {
    ScopedOneThread one;
    SettledBed b{bed_dem_config(), {}};
    PackingConfig pc;
    pc.count = kCount;
    pc.x_min = 0.0;
    pc.x_max = kWidth;
    pc.y_min = 0.0;
    pc.y_max = 0.3;
    DemSolver<2> dem(b.dem, place_random<2>(b.dem, pc));
    // 1e-8 J per particle is a mean speed of ~15 mm/s: at rest for the gas, whose velocities here are metres
    // per second.
    const SettleResult r = settle_bed(dem, 1e-8, 2.0);
    b.particles = dem.particles();
    b.settle_time = r.time;
    b.bed_height = bed_height<2>(b.particles, kWidth, 10);
    b.eps_interior = interior_voidage(b.particles, b.bed_height);
    std::printf("[ bed      ] %d particles settled in %.2f s (converged %d), bed height %.4f m, interior voidage %.4f\n",
                kCount, r.time, r.converged ? 1 : 0, b.bed_height, b.eps_interior);
    return b;
  }();
  return bed;
}

/// Gas of Table 1 with a pressure outlet on top, no background inflow and no jets (tests add their own).
inline GasConfig bed_gas() {
  GasConfig g;
  g.boundary.inlet_velocity = 0.0;
  g.boundary.jets.clear();
  return g;
}

inline CfdDemSimulation<2> bed_simulation(const GasConfig& gas, double wall_friction = 0.3, bool lid = false) {
  const SettledBed& bed = settled_bed();
  CouplingConfig cc;  // bilinear voidage, depth = one diameter, one DEM step per gas step
  DemConfig dem = bed.dem;
  dem.wall[0].friction = wall_friction;
  dem.walls.top = lid;
  return CfdDemSimulation<2>(DemSolver<2>(dem, bed.particles), GasSolver<2>(bed_grid(), gas), cc);
}

/// A full-width inflow of superficial velocity u for t_start <= t < t_end, expressed as a jet so that a
/// velocity schedule lives in the configuration.
inline InletJet full_width_inflow(double u, double t_start, double t_end) {
  return InletJet{0.5 * kWidth, kWidth, u, t_start, t_end};
}

/// Gas pressure on the distributor: the two bottom cell rows extrapolated linearly to y = 0 (the pressure
/// falls linearly in a packed or uniformly fluidised bed, so this is exact there), averaged over the width.
inline double distributor_pressure(const GasSolver<2>& gas) {
  const Field<2>& p = gas.fields().p;
  const int nx = p.box().extent(0);
  double s = 0.0;
  for (int i = 0; i < nx; ++i) s += 1.5 * p(i, 0) - 0.5 * p(i, 1);
  return s / nx;
}

inline double total_particle_weight(const ParticleStore<2>& p, double g) {
  double m = 0.0;
  for (double mi : p.mass) m += mi;
  return m * g;
}

inline double total_particle_volume(const ParticleStore<2>& p) {
  double v = 0.0;
  for (double r : p.radius) v += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return v;
}

}  // namespace fluidbed::coupling_test
