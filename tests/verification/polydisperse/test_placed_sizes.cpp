// The sizes a random placement gives a species against the distribution asked for (issue 14, item 3 acceptance):
// a log-normal bed's sample has the truncated log-normal's moments and CDF within the sampling error for its N.
// Tolerances: each sample moment within 4 standard errors s_k / sqrt(N) of the exact truncated moment (a
// 6e-5 chance per moment of failing a correct sampler); the Kolmogorov-Smirnov distance below 1.95 / sqrt(N), the
// 0.1% critical value (Kolmogorov 1933; Massey 1951). The exact moments and CDF are evaluated here by quadrature of
// the log-normal density, independently of the code's closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <vector>
#include <unistd.h>

#include "dem/packing.hpp"
#include "io/csv.hpp"

namespace fluidbed {
namespace {

constexpr double kMedian = 0.003, kSigma = 0.25;
constexpr double kMin = 0.002, kMax = 0.005;

Species log_normal_species() {
  Species s;
  s.density = 2500.0;
  s.size.law = SizeLaw::LogNormal;
  s.size.median = kMedian;
  s.size.sigma = kSigma;
  s.size.d_min = kMin;
  s.size.d_max = kMax;
  s.diameter = size_moments(s.size).m1;
  return s;
}

// Log-normal number density of d (untruncated).
double lognormal_pdf(double d) {
  const double z = std::log(d / kMedian) / kSigma;
  return std::exp(-0.5 * z * z) / (d * kSigma * std::sqrt(2.0 * std::numbers::pi));
}

// int_{kMin}^{x} d^k f(d) dd by composite Simpson in ln d (smooth there), 20000 intervals.
double integral(int k, double x) {
  const int n = 20000;
  const double a = std::log(kMin), b = std::log(x), h = (b - a) / n;
  double s = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double d = std::exp(a + i * h);
    const double c = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    s += c * std::pow(d, k) * lognormal_pdf(d) * d;  // dd = d dln d
  }
  return s * h / 3.0;
}

PackingConfig region(std::int64_t n) {
  PackingConfig pc;
  pc.count = n;
  pc.x_min = 0.0;
  pc.x_max = 0.5;
  pc.y_min = 0.0;
  pc.y_max = 0.5;
  pc.min_gap = 0.0002;
  pc.seed = 14;
  return pc;
}

TEST(PlacedSizes, LogNormalBedMatchesTheRequestedDistribution) {
  DemConfig dem;
  dem.species = {log_normal_species()};
  const std::int64_t n = 8000;
  const ParticleStore<2> p = place_random<2>(dem, region(n));
  ASSERT_EQ(p.size(), static_cast<std::size_t>(n));
  std::vector<double> d(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) d[i] = 2.0 * p.radius[i];
  const double z = integral(0, kMax);
  for (int k = 1; k <= 3; ++k) {
    const double exact = integral(k, kMax) / z;
    double s = 0.0, s2 = 0.0;
    for (double x : d) {
      s += std::pow(x, k);
      s2 += std::pow(x, 2 * k);
    }
    const double mean = s / n, sd = std::sqrt(s2 / n - mean * mean), se = sd / std::sqrt(static_cast<double>(n));
    std::printf("[ moment %d ] exact %.6e m^%d, placed %.6e, error %.2e (%.2f standard errors)\n", k, exact, k, mean,
                mean - exact, (mean - exact) / se);
    EXPECT_NEAR(mean, exact, 4.0 * se) << "moment " << k;
  }
  // The code's own closed-form moments against the quadrature (exact to the quadrature's error).
  const SizeMoments m = size_moments(dem.species[0].size);
  EXPECT_NEAR(m.m1, integral(1, kMax) / z, 1e-9 * m.m1);
  EXPECT_NEAR(m.d32(), integral(3, kMax) / integral(2, kMax), 1e-9 * m.d32());
  // Kolmogorov-Smirnov distance of the sample from the truncated CDF.
  std::sort(d.begin(), d.end());
  EXPECT_GE(d.front(), kMin);
  EXPECT_LE(d.back(), kMax);
  double ks = 0.0;
  for (std::size_t i = 0; i < d.size(); i += 8) {  // the CDF at every 8th point: the quadrature is the cost
    const double f = integral(0, d[i]) / z;
    ks = std::max({ks, std::abs(f - static_cast<double>(i) / n), std::abs(f - static_cast<double>(i + 1) / n)});
  }
  const double critical = 1.95 / std::sqrt(static_cast<double>(n));
  std::printf("[ KS       ] D = %.4f, critical (0.1%%) %.4f\n", ks, critical);
  EXPECT_LT(ks, critical);
  // Every particle is a sphere of its own size, and the placement still keeps its gap.
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    const double mass = 2500.0 * 4.0 / 3.0 * std::numbers::pi * r * r * r;
    ASSERT_NEAR(p.mass[i], mass, 1e-12 * mass);
    ASSERT_NEAR(1.0 / p.inv_inertia[i], 0.4 * mass * r * r, 1e-12 * mass * r * r);
  }
}

TEST(PlacedSizes, ListByMassGivesTheMassFractions) {
  // Two sizes, half the mass each: by number 8 : 1 for d and 2 d. The mass share of the small ones in a sample
  // of n is within 4 binomial standard errors of the number fraction, carried over to mass.
  DemConfig dem;
  Species s;
  s.size.law = SizeLaw::List;
  s.size.diameters = {0.002, 0.004};
  s.size.fractions = {8.0 / 9.0, 1.0 / 9.0};  // what case_loader makes of fraction_basis = "mass", [0.5, 0.5]
  s.size.d_min = 0.002;
  s.size.d_max = 0.004;
  dem.species = {s};
  const std::int64_t n = 4000;
  const ParticleStore<2> p = place_random<2>(dem, region(n));
  std::size_t small = 0;
  double m_small = 0.0, m_all = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool is_small = p.radius[i] == 0.001;
    ASSERT_TRUE(is_small || p.radius[i] == 0.002);
    small += is_small ? 1 : 0;
    (is_small ? m_small : m_all) += p.mass[i];
  }
  m_all += m_small;
  const double f = 8.0 / 9.0, se = std::sqrt(f * (1.0 - f) / n);
  std::printf("[ list     ] number fraction of 2 mm: exact %.4f, placed %.4f; mass fraction exact 0.5, placed %.4f\n",
              f, static_cast<double>(small) / n, m_small / m_all);
  EXPECT_NEAR(static_cast<double>(small) / n, f, 4.0 * se);
  // Mass share x = f / (f + 8 (1 - f)) from the number share: dx/df = 8 / (f + 8 (1 - f))^2 = 4.5 at f = 8/9.
  EXPECT_NEAR(m_small / m_all, 0.5, 4.0 * 4.5 * se);
}

TEST(PlacedSizes, FixedSpeciesAreUnchangedAndSizesSurviveTheParticleFile) {
  // A bed of fixed sizes has no sizes of its own (its files and checkpoints stay as they were: cli.oracle); a
  // mixed bed's own sizes go through the CSV's diameter column bit for bit, in 2D and 3D.
  DemConfig fixed;
  fixed.species = {Species{0.004, 2700.0}};
  const ParticleStore<2> a = place_random<2>(fixed, region(500));
  EXPECT_FALSE(a.has_own_sizes(fixed.species));
  DemConfig mixed;
  mixed.species = {Species{0.004, 2700.0}, log_normal_species()};
  mixed.pair.assign(4, InteractionParams{});
  mixed.wall.assign(2, InteractionParams{});
  PackingConfig pc = region(500);
  pc.species_fraction = {0.5, 0.5};
  const ParticleStore<2> b = place_random<2>(mixed, pc);
  ASSERT_TRUE(b.has_own_sizes(mixed.species));
  const auto dir = std::filesystem::temp_directory_path() / ("fluidbed-poly-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  ParticleArrays view = particle_arrays(b);
  view.own_sizes = true;
  write_particles_csv(dir / "b.csv", view);
  const std::vector<ParticleCsvRow> rows = read_particles_csv(dir / "b.csv", 2);
  ASSERT_EQ(rows.size(), b.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].id, b.id[i]);
    ASSERT_EQ(rows[i].diameter, 2.0 * b.radius[i]);
  }
  mixed.domain.dimension = 3;
  pc.z_min = 0.0;
  pc.z_max = 0.05;
  const ParticleStore<3> c = place_random<3>(mixed, pc);
  ParticleArrays view3 = particle_arrays(c);
  view3.own_sizes = true;
  write_particles_csv(dir / "c.csv", view3);
  const std::vector<ParticleCsvRow> rows3 = read_particles_csv(dir / "c.csv", 3);
  ASSERT_EQ(rows3.size(), c.size());
  for (std::size_t i = 0; i < rows3.size(); ++i) {
    ASSERT_EQ(rows3[i].z, c.z[i]);
    ASSERT_EQ(rows3[i].diameter, 2.0 * c.radius[i]);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fluidbed
