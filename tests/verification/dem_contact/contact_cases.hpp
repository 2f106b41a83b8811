#pragma once
// Set-ups shared by the contact-law verification tests: a Hertz-Mindlin configuration of one material, and a
// head-on impact of two spheres (or of a sphere on the floor) measured as a DEM run.
#include <algorithm>
#include <cmath>

#include "dem/dem_solver.hpp"
#include "verification/dem/dem_closed_form.hpp"

namespace fluidbed::test {

/// Glass-like spheres (E = 70 GPa, nu = 0.25), the walls of the same material, Hertz + Tsuji + Mindlin.
inline DemConfig hertz_config(int dim, double d, double rho, double e, double mu, double dt, ElasticMaterial mat = {}) {
  DemConfig c = dim == 3 ? one_species_config_3d(d, rho, 1.0, e, mu, dt, {0.0, 0.0, 0.0}, {0.1, 0.1, 0.1}, closed_box())
                         : one_species_config(d, rho, 1.0, e, mu, dt, {0.0, 0.0}, 0.1, 0.1, WallConfig{true, true, true, true});
  c.contact.normal = NormalModel::Hertz;
  c.contact.damping = DampingModel::Tsuji;
  c.contact.tangential = TangentialModel::Mindlin;
  c.contact.wall_material = mat;
  c.material = {mat};
  c.skin = 0.0;
  return c;
}

struct ImpactResult {
  double duration;     ///< s, touch to separation, interpolated within the last step
  double max_overlap;  ///< m
  double restitution;  ///< separating over closing normal speed
};

/// Two spheres closing head-on at speed v (each at v / 2), touching at t = 0; or one sphere hitting the floor at
/// v (wall = true). Stepped until the overlap is negative again.
template <int Dim>
ImpactResult head_on(const DemConfig& c, double v, bool wall) {
  const double r = c.species[0].radius();
  ParticleStore<Dim> p;
  Vec<Dim> x0{}, x1{};
  for (int a = 0; a < Dim; ++a) x0[a] = x1[a] = 0.05;
  Vec<Dim> v0{}, v1{};
  if (wall) {
    x0[1] = r;
    v0[1] = -v;
  } else {
    x0[1] = 0.05 - r;
    x1[1] = 0.05 + r;
    v0[1] = 0.5 * v;
    v1[1] = -0.5 * v;
  }
  p.add(0, 0, c.species[0], x0, v0);
  if (!wall) p.add(1, 0, c.species[0], x1, v1);
  DemSolver<Dim> s(c, std::move(p));
  const auto& q = s.particles();
  auto overlap = [&] {
    if (wall) return r - q.y[0];
    const std::size_t lo = q.id[0] == 0 ? 0 : 1, hi = 1 - lo;
    return 2.0 * r - (q.y[hi] - q.y[lo]);
  };
  auto closing = [&] {
    if (wall) return -q.vy[0];
    const std::size_t lo = q.id[0] == 0 ? 0 : 1, hi = 1 - lo;
    return q.vy[lo] - q.vy[hi];
  };
  double max_ov = 0.0, prev = 0.0;
  for (long k = 1; k < 10000000; ++k) {
    s.step();
    const double ov = overlap();
    if (ov < 0.0) {
      const double frac = prev / (prev - ov);  // zero crossing inside the last step
      return {(static_cast<double>(k - 1) + frac) * c.dt, max_ov, -closing() / v};
    }
    max_ov = std::max(max_ov, ov);
    prev = ov;
  }
  return {std::nan(""), max_ov, std::nan("")};
}

}  // namespace fluidbed::test
