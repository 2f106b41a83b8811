// Elastic (e = 1, eta = 0 by Eq. 8), frictionless spheres in a closed 3D box (six walls) conserve their energy:
// the kinetic energy plus the energy stored in the normal springs (Eq. 2), 0.5 k overlap^2 per pair and wall.
// Tolerance as in 2D (test_energy_box.cpp): Eq. 10 is symplectic and conserves a modified energy that differs
// from the true one by about omega dt / 2 (3% at 50 steps per contact) of the energy held in the springs at the
// instant, a few percent of the total, so about 1e-3 of the total, plus a random-sign (pi / N)^2 error of each
// contact that opens or closes between steps; 0.5% is the acceptance criterion.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dem/dem_solver.hpp"
#include "dem/packing.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

double spring_energy(const ParticleStore<3>& p, double k, Vec3 box) {
  double e = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double ov = p.radius[i] + p.radius[j] - norm(p.pos(j) - p.pos(i));
      if (ov > 0.0) e += 0.5 * k * ov * ov;
    }
    for (int a = 0; a < 3; ++a) {
      for (double ov : {p.radius[i] - p.coord(a)[i], p.radius[i] - (box[a] - p.coord(a)[i])}) {
        if (ov > 0.0) e += 0.5 * k * ov * ov;
      }
    }
  }
  return e;
}

constexpr double kTol = 0.005;

TEST(DemEnergyBoxIn3D, ElasticFrictionlessGasInAClosedBoxConservesEnergy) {
  const test::ScopedThreads one_thread(1);
  const double k = 800.0;
  const Vec3 box{0.06, 0.06, 0.06};
  const Species sp{0.004, 2700.0};
  const double t_c = contact_duration(reduced_mass(sp.mass(), sp.mass()), k, 0.0);
  const double dt = t_c / 50.0;
  DemConfig c = test::one_species_config_3d(sp.diameter, sp.density, k, 1.0, 0.0, dt, {0.0, 0.0, 0.0}, box,
                                            test::closed_box());
  // A gap of 1 mm: 6 mm lattice sites, 1000 sites, every one taken.
  ParticleStore<3> p = place_random<3>(c, test::box_packing(box, 1000, 7, 0.001));
  std::mt19937_64 rng(11);
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < 3; ++a) p.velocity(a)[i] = 2.0 * uniform() - 1.0;
  }
  DemSolver<3> s(c, std::move(p));
  const double e0 = s.kinetic_energy() + spring_energy(s.particles(), k, box);
  test::Table t("Elastic frictionless gas, 1000 spheres in a closed 6 cm box, dt = t_contact(pair) / 50",
                {"step", "E kinetic", "E spring", "E total", "rel change"});
  double worst = 0.0;
  std::uint64_t contacts_seen = 0;
  for (int n = 1; n <= 5000; ++n) {
    s.step();
    if (s.max_overlap() > 0.0) ++contacts_seen;
    if (n % 100 == 0) {
      const double ek = s.kinetic_energy();
      const double es = spring_energy(s.particles(), k, box);
      const double drift = std::abs(ek + es - e0) / e0;
      worst = std::max(worst, drift);
      if (n % 1000 == 0) t.row({static_cast<double>(n), ek, es, ek + es, (ek + es - e0) / e0});
      EXPECT_LE(drift, kTol) << "step " << n;
    }
  }
  fmt::print("max |E - E0| / E0 over 50 samples: {:.3g}; steps with a contact: {}; rebuilds: {}\n", worst,
             contacts_seen, s.rebuild_count());
  EXPECT_GT(contacts_seen, 4000u);  // a gas with collisions all the time, not free flight
}

}  // namespace
}  // namespace fluidbed
