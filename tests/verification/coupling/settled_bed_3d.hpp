#pragma once
// A small settled 3D bed of the paper's particles (4 mm, 2700 kg/m^3, Table 1) for the 3D bed tests: 2500
// spheres in a 0.05 x 0.05 m column (12.5 diameters each way, walls on all four sides), about 0.06 m deep, with a
// gas grid of 1 cm cubes (2.5 diameters, as the 2D bed tests). A column 10 diameters wide and twice as deep
// slugs: its distributor then carries 3-5% of the bed's weight and its plateau falls 6% short. Settled once per test process (about 2 s on one core).
#include <cmath>
#include <cstdio>
#include <numbers>

#include "coupling/cfd_dem.hpp"
#include "coupling/voidage.hpp"
#include "dem/packing.hpp"
#include "dem/settle.hpp"
#include "closures/drag.hpp"
#include "settled_bed.hpp"  // ScopedOneThread

namespace fluidbed::coupling_test_3d {

using coupling_test::ScopedOneThread;

inline constexpr double kWidth = 0.05;   // x
inline constexpr double kHeight = 0.2;   // y, up
inline constexpr double kDepth = 0.05;   // z
inline constexpr int kNx = 5, kNy = 20, kNz = 5;
inline constexpr int kCount = 2500;

struct SettledBed {
  DemConfig dem;
  ParticleStore<3> particles;
  double bed_height = 0.0;     ///< m
  double eps_interior = 0.0;   ///< mean counted voidage of the cells inside the bed
  double settle_time = 0.0;    ///< simulated, s
};

inline Grid<3> bed_grid() { return Grid<3>::uniform({kWidth, kHeight, kDepth}, {kNx, kNy, kNz}); }

inline DemConfig bed_dem_config() {
  DemConfig c;  // paper particles, k = 800 N/m, restitution 0.9, friction 0.3
  c.domain.dimension = 3;
  c.domain.width = kWidth;
  c.domain.height = kHeight;
  c.domain.depth = kDepth;
  // 1e-4 s, 7.5 steps per contact: at the 2D tests' 2e-4 s (3.7 steps) a 3D packing, with twice the contacts
  // per particle, never comes to rest (its kinetic energy stalls at ~3e-8 J per particle) and creeps denser.
  c.dt = 1e-4;
  return c;
}

/// Mean counted voidage (trilinear) over the cell layers above the bottom one and two below the bed surface. The
/// column is only 5 cells across, so every cell touches a wall; the wall layers' looser packing is part of the mean,
/// as it is of the bed the gas flows through.
inline double interior_voidage(const ParticleStore<3>& p, double bed_height) {
  const Grid<3> g = bed_grid();
  Field<3> eps(g.owned, 0);
  std::vector<CellWeights<3>> w;
  particle_cell_weights(p, g, eps, VoidageMethod::Bilinear, w);
  compute_voidage(p, w, g, 0.0, eps);
  const int j_top = static_cast<int>(std::floor(bed_height / g.h[1])) - 2;
  double sum = 0.0;
  int n = 0;
  for_each(g.owned, [&](const Index<3>& c) {
    if (c[1] >= 1 && c[1] < j_top) {
      sum += eps[c];
      ++n;
    }
  });
  return sum / n;
}

/// Particles placed at random in the column fall and settle in vacuum (the paper's initial condition); about a
/// quarter of a second of simulated time.
inline const SettledBed& settled_bed() {
  static const SettledBed bed = [] {
    ScopedOneThread one;
    SettledBed b{bed_dem_config(), {}};
    PackingConfig pc;
    pc.count = kCount;
    pc.x_max = kWidth;
    pc.y_max = 0.12;
    pc.z_max = kDepth;
    pc.seed = 12;
    DemSolver<3> dem(b.dem, place_random<3>(b.dem, pc));
    // 1e-9 J per particle is a mean speed of ~5 mm/s: at rest for the gas, whose velocities are metres per second.
    const SettleResult r = settle_bed(dem, 1e-9, 1.0);
    b.particles = dem.particles();
    b.settle_time = r.time;
    b.bed_height = bed_height<3>(b.particles, kWidth, kNx);
    b.eps_interior = interior_voidage(b.particles, b.bed_height);
    std::printf("[ bed 3d   ] %d particles settled in %.2f s (converged %d), bed height %.4f m, interior voidage %.4f\n",
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

inline CfdDemSimulation<3> bed_simulation(const GasConfig& gas, double wall_friction = 0.3, int dem_substeps = 1) {
  const SettledBed& bed = settled_bed();
  CouplingConfig cc;  // trilinear voidage, cell volume from the grid
  cc.dem_substeps = dem_substeps;
  DemConfig dem = bed.dem;
  dem.wall[0].friction = wall_friction;
  return CfdDemSimulation<3>(DemSolver<3>(dem, bed.particles), GasSolver<3>(bed_grid(), gas), cc);
}

/// A whole-bottom inflow of superficial velocity u for t_start <= t < t_end: a rectangle covering the bottom face,
/// so that a velocity schedule lives in the configuration.
inline InletJet full_bottom_inflow(double u, double t_start, double t_end) {
  InletJet j{0.5 * kWidth, kWidth, u, t_start, t_end};
  j.shape = InletShape::Rectangle;
  j.z_centre = 0.5 * kDepth;
  j.depth = kDepth;
  return j;
}

/// Gas pressure on the distributor: the two bottom cell layers extrapolated linearly to y = 0 (exact for the linear
/// pressure of a packed or uniformly fluidised bed), averaged over the bottom face.
inline double distributor_pressure(const GasSolver<3>& gas) {
  const Field<3>& p = gas.fields().p;
  const IndexBox<3>& b = p.box();
  double s = 0.0;
  int n = 0;
  for (int k = b.lo[2]; k < b.hi[2]; ++k) {
    for (int i = b.lo[0]; i < b.hi[0]; ++i) {
      s += 1.5 * p(i, 0, k) - 0.5 * p(i, 1, k);
      ++n;
    }
  }
  return s / n;
}

inline double total_particle_weight(const ParticleStore<3>& p, double g) {
  double m = 0.0;
  for (double mi : p.mass) m += mi;
  return m * g;
}

inline double total_particle_volume(const ParticleStore<3>& p) {
  double v = 0.0;
  for (double r : p.radius) v += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return v;
}

}  // namespace fluidbed::coupling_test_3d
