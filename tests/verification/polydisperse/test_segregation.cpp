// A bidisperse bed (issue 14, item 3 acceptance) settles, fluidises and segregates the way density-segregating
// mixtures do: at a gas velocity between the minimum fluidisation velocities of the two species the light
// particles (flotsam) rise to the top and the heavy ones (jetsam) sink (Rowe, Nienow and Agbim 1972; Rowe and
// Nienow 1976; Hoffmann, Janssen and Prins 1993). The heavy species is itself polydisperse (normal, 4 mm +- 5%),
// so the run goes through every per-particle size path of CFD-DEM.
// Measure: the segregation index S = (mean height of flotsam - mean height of jetsam) / bed height. Placed at
// random the two species are mixed: |S| is then within 4 sampling errors, 4 x sqrt(2 / N_s) x 0.29 (the standard
// deviation of a uniform height is 0.29 of the bed) = 0.08 for 200 per species. After fluidising the test asks for
// S above 0.15, twice that band: a bed that did not segregate cannot pass, and the segregated bed measured here
// has S about 0.3 (printed). Fluidised: the mean pressure drop carries the flotsam and at least half the jetsam
// (side-wall friction and the 2D voidage's depth carry some of a narrow bed's weight) and the bed expands by 10%.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <cstdio>

#include "coupling/cfd_dem.hpp"
#include "dem/packing.hpp"
#include "dem/settle.hpp"
#include "closures/drag.hpp"

namespace fluidbed {
namespace {

constexpr double kWidth = 0.08, kHeight = 0.32;
constexpr int kNx = 8, kNy = 32;  // 1 cm cells, 2.5 diameters
constexpr int kCount = 400;

struct Heights {
  double flotsam = 0.0, jetsam = 0.0, top = 0.0;
  double index() const { return (flotsam - jetsam) / top; }
};

Heights heights(const ParticleStore<2>& p) {
  Heights h;
  int nf = 0, nj = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    (p.species[i] == 1 ? h.flotsam : h.jetsam) += p.y[i];
    (p.species[i] == 1 ? nf : nj) += 1;
  }
  h.flotsam /= nf;
  h.jetsam /= nj;
  h.top = bed_height<2>(p, kWidth, 8);
  return h;
}

TEST(Segregation, LightParticlesRiseInABidisperseBed) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);  // a few hundred particles: threads cost more than they save, results do not depend on them
  DemConfig dem;
  dem.domain.width = kWidth;
  dem.domain.height = kHeight;
  dem.dt = 1e-4;
  Species heavy{0.004, 2700.0};
  heavy.size.law = SizeLaw::Normal;
  heavy.size.mean = 0.004;
  heavy.size.std = 0.0002;
  heavy.size.d_min = 0.0034;
  heavy.size.d_max = 0.0046;
  heavy.diameter = size_moments(heavy.size).m1;
  const Species light{0.004, 900.0};
  dem.species = {heavy, light};
  dem.pair.assign(4, InteractionParams{});
  dem.wall.assign(2, InteractionParams{});
  PackingConfig pc;
  pc.count = kCount;
  pc.x_max = kWidth;
  pc.y_max = 0.25;
  pc.species_fraction = {0.5, 0.5};
  DemSolver<2> settler(dem, place_random<2>(dem, pc));
  const SettleResult sr = settle_bed(settler, 1e-8, 1.5);
  const Heights h0 = heights(settler.particles());
  std::printf("[ settled  ] %.2f s (converged %d), bed height %.4f m, S = %.3f\n", sr.time, sr.converged ? 1 : 0,
              h0.top, h0.index());
  EXPECT_TRUE(sr.converged);
  EXPECT_LT(std::abs(h0.index()), 0.08);

  GasConfig gas;
  gas.boundary.jets.clear();
  const double g = 9.81;
  // U_mf of each species alone (Ergun, eps_mf = 0.43 as `check` takes it); the gas between them.
  const double u_heavy = ergun_minimum_fluidisation_velocity(0.43, 0.004, 2700.0, gas.rho_g, gas.mu_g, g);
  const double u_light = ergun_minimum_fluidisation_velocity(0.43, 0.004, 900.0, gas.rho_g, gas.mu_g, g);
  // 1.2 U_mf of the jetsam: the whole bed fluidised (at the geometric mean of the two U_mf this 50:50 mixture
  // stays a fixed bed, S unchanged), bubbling gently enough for the flotsam to gather on top.
  const double u = 1.2 * u_heavy;
  gas.boundary.inlet_velocity = u;
  CouplingConfig cc;
  cc.depth = 0.004;
  CfdDemSimulation<2> sim(DemSolver<2>(dem, settler.particles()), GasSolver<2>(Grid<2>::uniform({kWidth, kHeight}, {kNx, kNy}), gas), cc);
  sim.initialize();
  double flotsam_weight = 0.0, weight = 0.0;
  for (std::size_t i = 0; i < sim.dem().particles().size(); ++i) {
    weight += sim.dem().particles().mass[i] * g;
    if (sim.dem().particles().species[i] == 1) flotsam_weight += sim.dem().particles().mass[i] * g;
  }
  const double t_end = 1.5;
  double dp_sum = 0.0;
  int dp_n = 0;
  while (sim.time() < t_end - 0.5 * sim.macro_dt()) {
    sim.advance();
    if (sim.time() > 0.5) {
      dp_sum += sim.gas().pressure_drop();
      ++dp_n;
    }
  }
  const Heights h1 = heights(sim.dem().particles());
  const double dp = dp_sum / dp_n, dp_flotsam = flotsam_weight / (kWidth * cc.depth);
  const double dp_bed = weight / (kWidth * cc.depth);
  std::printf("[ gas      ] U_mf heavy %.3f m/s, light %.3f m/s, U = %.3f m/s; mean pressure drop %.1f Pa = %.2f of "
              "the bed weight per area %.1f Pa (flotsam alone %.1f Pa)\n", u_heavy, u_light, u, dp, dp / dp_bed, dp_bed,
              dp_flotsam);
  std::printf("[ at %.1f s ] bed height %.4f m (settled %.4f), flotsam mean height %.4f m, jetsam %.4f m, S = %.3f "
              "(required > 0.15)\n", t_end, h1.top, h0.top, h1.flotsam, h1.jetsam, h1.index());
  EXPECT_GT(dp, dp_flotsam + 0.5 * (dp_bed - dp_flotsam));  // the jetsam is carried too, not only the flotsam
  EXPECT_GT(h1.top, 1.1 * h0.top);
  EXPECT_GT(h1.index(), 0.15);
  omp_set_num_threads(saved);
}

}  // namespace
}  // namespace fluidbed
