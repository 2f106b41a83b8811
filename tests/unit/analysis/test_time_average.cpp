// TimeAverage on analytic fields, 2D and 3D. Exact answers and their tolerances:
// - fields f_k = a + A cos(2 pi k / K + phi_c) over K samples: the discrete cosine sums to 0, so every time mean is
//   a; the sum of K terms of size <= a + A carries rounding of about K eps (a + A), so 1e-13 for K = 64;
// - a cell alternating between (eps_s, us) = (0.2, 1) and (0.6, 3): cell-weighted mean 2, particle (solids
//   volume) weighted (0.2 + 1.8) / 0.8 = 2.5; a cell empty half the time: cell mean over the other half only;
//   rounding of a few terms, 1e-14;
// - granular temperature of four particles at V + (+-u, 0), V + (0, +-v): Theta = (2 u^2 + 2 v^2) / (4 Dim),
//   two-pass sums of four terms, 1e-14 relative; of N particles with normal velocities of deviation sigma per
//   axis in one cell: Theta = sigma^2 with the sampling error of a variance, sd sigma^2 sqrt(2 / (Dim N)), so a
//   tolerance of 5 sd (N = 40000, 2D: 2.5% of sigma^2) that a wrong 1/Dim or a missed mean fails by far;
// - TFM Theta weighted by eps_s: (0.2 x 1 + 0.6 x 5) / 0.8 = 4 exactly to rounding.
// Visiting the particles in id order makes the temperature independent of the storage order bit for bit, and a
// state restored into a fresh average continues bit for bit (what the checkpoint relies on).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>
#include <random>
#include <vector>

#include "analysis/time_average.hpp"

namespace fluidbed {
namespace {

template <int Dim>
CellGeometry<Dim> grid() {
  CellGeometry<Dim> g;
  g.n[0] = 6;
  g.n[1] = 5;
  if constexpr (Dim == 3) g.n[2] = 3;
  g.h.fill(0.02);
  g.origin.fill(0.0);
  return g;
}

void report(const char* what, double exact, double computed, double tol) {
  std::printf("%-58s exact %.12g computed %.12g error %.3g (tol %.3g)\n", what, exact, computed,
              std::abs(computed - exact), tol);
}

/// Sample k of K of the cosine fields: field f of cell c is base_f(c) + A cos(2 pi k / K + 0.3 c).
template <int Dim>
struct CosineFields {
  CellGeometry<Dim> g = grid<Dim>();
  std::vector<double> eps;
  std::array<std::vector<double>, Dim> ug, us;
  static double base(int f, std::size_t c) { return f == 0 ? 0.5 + 0.01 * static_cast<double>(c % 7) : 0.2 * f - 0.03 * c; }
  static constexpr double kAmp[2] = {0.2, 1.5};  // voidage, velocities
  void sample(int k, int K) {
    const std::size_t n = g.cells();
    eps.resize(n);
    for (auto& v : ug) v.resize(n);
    for (auto& v : us) v.resize(n);
    for (std::size_t c = 0; c < n; ++c) {
      const double w = std::cos(2.0 * std::numbers::pi * k / K + 0.3 * static_cast<double>(c));
      eps[c] = base(0, c) + kAmp[0] * w;
      for (int a = 0; a < Dim; ++a) {
        ug[a][c] = base(1 + a, c) + kAmp[1] * w;
        us[a][c] = base(1 + Dim + a, c) + kAmp[1] * w;
      }
    }
  }
  AverageFields<Dim> view() const {
    AverageFields<Dim> f;
    f.geometry = g;
    f.eps = eps.data();
    for (int a = 0; a < Dim; ++a) {
      f.ug[a] = ug[a].data();
      f.us[a] = us[a].data();
    }
    return f;
  }
};

template <int Dim>
void cosine_means() {
  CosineFields<Dim> f;
  TimeAverage<Dim> avg(f.g);
  constexpr int K = 64;
  for (int k = 0; k < K; ++k) {
    f.sample(k, K);
    avg.add(f.view());
  }
  EXPECT_EQ(avg.samples(), K);
  const auto eps = avg.voidage();
  const auto ug = avg.gas_velocity();
  const auto us = avg.solids_velocity_cell();
  double e_eps = 0.0, e_u = 0.0;
  for (std::size_t c = 0; c < f.g.cells(); ++c) {
    e_eps = std::max(e_eps, std::abs(eps[c] - CosineFields<Dim>::base(0, c)));
    for (int a = 0; a < Dim; ++a) {
      e_u = std::max(e_u, std::abs(ug[a][c] - CosineFields<Dim>::base(1 + a, c)));
      e_u = std::max(e_u, std::abs(us[a][c] - CosineFields<Dim>::base(1 + Dim + a, c)));
    }
  }
  std::printf("Dim %d, %d samples of cosine fields over %zu cells:\n", Dim, K, f.g.cells());
  report("  voidage time mean, max error", 0.0, e_eps, 1e-13);
  report("  gas and solids velocity time means, max error", 0.0, e_u, 1e-13);
  EXPECT_LT(e_eps, 1e-13);
  EXPECT_LT(e_u, 1e-13);
}

TEST(TimeAverage, CosineFieldsAverageToTheirMean2D) { cosine_means<2>(); }
TEST(TimeAverage, CosineFieldsAverageToTheirMean3D) { cosine_means<3>(); }

template <int Dim>
void weightings() {
  const CellGeometry<Dim> g = grid<Dim>();
  const std::size_t n = g.cells();
  TimeAverage<Dim> avg(g);
  std::vector<double> eps(n), theta(n);
  std::array<std::vector<double>, Dim> ug, us;
  for (int a = 0; a < Dim; ++a) {
    ug[a].assign(n, 0.0);
    us[a].assign(n, 0.0);
  }
  AverageFields<Dim> f;
  f.geometry = g;
  f.eps = eps.data();
  f.theta = theta.data();
  for (int a = 0; a < Dim; ++a) {
    f.ug[a] = ug[a].data();
    f.us[a] = us[a].data();
  }
  // Cell 0 alternates (eps_s, us, Theta) = (0.2, 1, 1) and (0.6, 3, 5); cell 1 is empty (eps = 1) every other sample.
  for (int k = 0; k < 10; ++k) {
    const bool odd = k % 2;
    std::fill(eps.begin(), eps.end(), 0.5);
    eps[0] = odd ? 0.4 : 0.8;
    eps[1] = odd ? 1.0 : 0.7;
    for (int a = 0; a < Dim; ++a) {
      us[a][0] = odd ? 3.0 : 1.0;
      us[a][1] = odd ? 0.0 : -2.0;  // an empty cell's velocity is 0, as the CFD-DEM deposition leaves it
    }
    theta[0] = odd ? 5.0 : 1.0;
    avg.add(f);
  }
  const auto cell = avg.solids_velocity_cell();
  const auto part = avg.solids_velocity_particle();
  const auto th = avg.granular_temperature();
  const auto presence = avg.solids_presence();
  std::printf("Dim %d, weightings:\n", Dim);
  report("  cell-weighted solids velocity, alternating cell", 2.0, cell[Dim - 1][0], 1e-14);
  report("  particle-weighted solids velocity, alternating cell", 2.5, part[Dim - 1][0], 1e-14);
  report("  TFM Theta, solids-volume weighted", 4.0, th[0], 1e-14);
  report("  cell-weighted solids velocity, cell empty half the time", -2.0, cell[0][1], 1e-14);
  report("  solids presence of that cell", 0.5, presence[1], 0.0);
  for (int a = 0; a < Dim; ++a) {
    EXPECT_NEAR(cell[a][0], 2.0, 1e-14);
    EXPECT_NEAR(part[a][0], 2.5, 1e-14);
    EXPECT_NEAR(cell[a][1], -2.0, 1e-14);
    EXPECT_NEAR(part[a][1], -2.0, 1e-14);
  }
  EXPECT_NEAR(th[0], 4.0, 1e-14);
  EXPECT_EQ(presence[1], 0.5);
  EXPECT_EQ(presence[2], 1.0);
  // No sample at all: undefined, not 0.
  TimeAverage<Dim> empty(g);
  EXPECT_TRUE(std::isnan(empty.voidage()[0]));
  EXPECT_TRUE(std::isnan(empty.solids_velocity_particle()[0][0]));
}

TEST(TimeAverage, CellAndParticleWeightedSolidsVelocity2D) { weightings<2>(); }
TEST(TimeAverage, CellAndParticleWeightedSolidsVelocity3D) { weightings<3>(); }

/// Particles as plain arrays.
template <int Dim>
struct Cloud {
  std::array<std::vector<double>, Dim> x, v;
  std::vector<double> r;
  std::vector<std::size_t> order;
  void add(const std::array<double, Dim>& pos, const std::array<double, Dim>& vel, double radius) {
    for (int a = 0; a < Dim; ++a) {
      x[a].push_back(pos[a]);
      v[a].push_back(vel[a]);
    }
    r.push_back(radius);
  }
  AverageParticles<Dim> view() const {
    AverageParticles<Dim> p;
    for (int a = 0; a < Dim; ++a) {
      p.x[a] = x[a];
      p.v[a] = v[a];
    }
    p.radius = r;
    p.order = order;
    return p;
  }
};

template <int Dim>
void four_particles() {
  const CellGeometry<Dim> g = grid<Dim>();
  Cloud<Dim> p;
  const double u = 0.3, w = 0.7;
  std::array<double, Dim> centre{}, mean{};
  centre.fill(0.01);  // inside cell 0
  for (int a = 0; a < Dim; ++a) mean[a] = 1.0 + a;
  for (int s = 0; s < 4; ++s) {
    std::array<double, Dim> vel = mean;
    vel[s / 2] += (s % 2 ? -1.0 : 1.0) * (s / 2 == 0 ? u : w);
    p.add(centre, vel, 0.002);
  }
  // A lone particle in another cell: no temperature there.
  std::array<double, Dim> far{};
  far.fill(0.05);
  p.add(far, mean, 0.002);
  std::vector<double> theta, weight;
  particle_granular_temperature(g, p.view(), theta, weight);
  const double exact = (2.0 * u * u + 2.0 * w * w) / (4.0 * Dim);
  std::printf("Dim %d, four particles about their mean:\n", Dim);
  report("  Theta = (2 u^2 + 2 v^2) / (4 Dim)", exact, theta[0], 1e-14 * exact);
  EXPECT_NEAR(theta[0], exact, 1e-14 * exact);
  EXPECT_NEAR(weight[0], 4.0 * 4.0 / 3.0 * std::numbers::pi * 8e-9, 1e-22);
  Index<Dim> c{};
  for (int a = 0; a < Dim; ++a) c[a] = g.cell(a, 0.05);
  EXPECT_EQ(weight[g.index(c)], 0.0);
  // Time average over the two: the lone particle's cell has no sample.
  TimeAverage<Dim> avg(g);
  CosineFields<Dim> f;
  f.sample(0, 4);
  const AverageParticles<Dim> view = p.view();
  avg.add(f.view(), &view);
  EXPECT_NEAR(avg.granular_temperature()[0], exact, 1e-14 * exact);
  EXPECT_TRUE(std::isnan(avg.granular_temperature()[g.index(c)]));
}

TEST(ParticleGranularTemperature, FourParticlesAboutTheirMean2D) { four_particles<2>(); }
TEST(ParticleGranularTemperature, FourParticlesAboutTheirMean3D) { four_particles<3>(); }

template <int Dim>
void maxwellian() {
  const CellGeometry<Dim> g = grid<Dim>();
  Cloud<Dim> p;
  std::mt19937_64 rng(42);
  const double sigma = 0.25;
  std::normal_distribution<double> normal(0.0, sigma);
  std::uniform_real_distribution<double> inside(0.001, 0.019);
  std::uniform_real_distribution<double> radius(0.001, 0.002);
  constexpr int N = 40000;
  for (int k = 0; k < N; ++k) {
    std::array<double, Dim> pos{}, vel{};
    for (int a = 0; a < Dim; ++a) {
      pos[a] = inside(rng);
      vel[a] = 2.0 + normal(rng);  // a mean flow the temperature must not see
    }
    p.add(pos, vel, radius(rng));
  }
  std::vector<double> theta, weight;
  particle_granular_temperature(g, p.view(), theta, weight);
  // Weights by volume: the effective count is (sum w)^2 / sum w^2, a little below N; 5 sd of that count.
  double s1 = 0.0, s2 = 0.0;
  for (double r : p.r) {
    const double w = r * r * r;
    s1 += w;
    s2 += w * w;
  }
  const double n_eff = s1 * s1 / s2;
  const double tol = 5.0 * sigma * sigma * std::sqrt(2.0 / (Dim * n_eff));
  std::printf("Dim %d, %d particles with normal velocities (n_eff %.0f):\n", Dim, N, n_eff);
  report("  Theta = sigma^2", sigma * sigma, theta[0], tol);
  EXPECT_NEAR(theta[0], sigma * sigma, tol);

  // Stored in another order, visited in the same (id) order: the same bits.
  std::vector<std::size_t> perm(N);
  std::iota(perm.begin(), perm.end(), std::size_t{0});
  std::shuffle(perm.begin(), perm.end(), rng);
  Cloud<Dim> q;  // slot s of q holds particle perm[s] of p
  for (int s = 0; s < N; ++s) {
    std::array<double, Dim> pos{}, vel{};
    for (int a = 0; a < Dim; ++a) {
      pos[a] = p.x[a][perm[s]];
      vel[a] = p.v[a][perm[s]];
    }
    q.add(pos, vel, p.r[perm[s]]);
  }
  q.order.resize(N);
  for (int s = 0; s < N; ++s) q.order[perm[s]] = static_cast<std::size_t>(s);
  std::vector<double> theta_q, weight_q;
  particle_granular_temperature(g, q.view(), theta_q, weight_q);
  EXPECT_EQ(theta_q, theta);
  EXPECT_EQ(weight_q, weight);
}

TEST(ParticleGranularTemperature, MaxwellianCloudGivesSigmaSquared2D) { maxwellian<2>(); }
TEST(ParticleGranularTemperature, MaxwellianCloudGivesSigmaSquared3D) { maxwellian<3>(); }

template <int Dim>
void restored() {
  CosineFields<Dim> f;
  TimeAverage<Dim> whole(f.g), first(f.g);
  constexpr int K = 20;
  for (int k = 0; k < K; ++k) {
    f.sample(k, K);
    whole.add(f.view());
    if (k < K / 2) first.add(f.view());
  }
  TimeAverage<Dim> second(f.g);
  second.restore(first.state());
  for (int k = K / 2; k < K; ++k) {
    f.sample(k, K);
    second.add(f.view());
  }
  EXPECT_EQ(second.samples(), whole.samples());
  EXPECT_EQ(second.state().sums, whole.state().sums);
  EXPECT_EQ(second.voidage(), whole.voidage());
  // Another grid's state is refused.
  CellGeometry<Dim> other = f.g;
  other.n[0] += 1;
  TimeAverage<Dim> wrong(other);
  EXPECT_THROW(wrong.restore(first.state()), std::invalid_argument);
}

TEST(TimeAverage, RestoredStateContinuesBitForBit2D) { restored<2>(); }
TEST(TimeAverage, RestoredStateContinuesBitForBit3D) { restored<3>(); }

}  // namespace
}  // namespace fluidbed
