// The 3D cell-list Verlet list (3 x 3 x 3 cells) holds exactly the pairs within r_i + r_j + skin found by brute
// force, each pair once in each partner's list; dense, sparse and polydisperse clouds, particles outside the
// box, and strays far enough to cap the cell grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "dem/neighbor_list.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

ParticleStore<3> random_cloud(std::size_t n, Vec3 lo, Vec3 hi, const std::vector<double>& d, std::uint64_t seed,
                              std::int64_t id0 = 5) {
  std::mt19937_64 rng(seed);
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  ParticleStore<3> p;
  for (std::size_t i = 0; i < n; ++i) {
    const auto s = static_cast<std::size_t>(uniform() * static_cast<double>(d.size())) % d.size();
    Vec3 x;
    for (int a = 0; a < 3; ++a) x[a] = lo[a] + (hi[a] - lo[a]) * uniform();
    p.add(id0 + static_cast<std::int64_t>(i) * 3, static_cast<std::int32_t>(s), Species{d[s], 2700.0}, x);
  }
  return p;
}

TEST(DemNeighborSearchIn3D, VerletListEqualsBruteForceAndIsSymmetric) {
  const std::vector<double> mono{0.004}, poly{0.002, 0.0035, 0.006};
  struct Cloud {
    const char* name;
    ParticleStore<3> p;
    double cell_size, skin;
  };
  std::vector<Cloud> clouds;
  clouds.push_back({"dense mono", random_cloud(4000, {0, 0, 0}, {0.05, 0.05, 0.05}, mono, 1), 0.0044, 4e-4});
  clouds.push_back({"sparse mono", random_cloud(800, {0, 0, 0}, {0.3, 0.3, 0.3}, mono, 2), 0.0044, 4e-4});
  clouds.push_back({"dense poly", random_cloud(4000, {0, 0, 0}, {0.08, 0.04, 0.05}, poly, 3), 0.0065, 5e-4});
  clouds.push_back({"poly, skin 0", random_cloud(3000, {0, 0, 0}, {0.05, 0.05, 0.05}, poly, 4), 0.006, 0.0});
  {
    ParticleStore<3> p = random_cloud(2000, {-0.03, -0.03, -0.03}, {0.03, 0.03, 0.03}, poly, 5);
    const ParticleStore<3> strays = random_cloud(40, {500.0, -300.0, 80.0}, {500.01, -299.99, 80.01}, poly, 6, 100000);
    for (std::size_t i = 0; i < strays.size(); ++i) {
      p.add(strays.id[i], strays.species[i], Species{2.0 * strays.radius[i], 2700.0}, strays.pos(i));
    }
    clouds.push_back({"strays, capped grid", std::move(p), 0.0065, 5e-4});
  }
  test::Table t("3D neighbour search against brute force", {"particles", "pairs brute", "pairs list", "missing",
                                                             "extra", "asymmetric"}, 20);
  for (Cloud& c : clouds) {
    const std::vector<std::size_t> order = sort_by_cell(c.p, c.cell_size);
    c.p.permute(order);
    NeighborList<3> nl;
    build_neighbor_list(c.p, c.cell_size, c.skin, nl);
    const auto brute = brute_force_contacts(c.p, c.skin);
    std::vector<std::pair<std::int64_t, std::int64_t>> listed;
    std::size_t asym = 0;
    for (std::size_t i = 0; i < c.p.size(); ++i) {
      for (std::size_t k = nl.offset[i]; k < nl.offset[i + 1]; ++k) {
        const std::size_t j = nl.partner[k];
        if (c.p.id[i] < c.p.id[j]) listed.emplace_back(c.p.id[i], c.p.id[j]);
        bool back = false;
        for (std::size_t q = nl.offset[j]; q < nl.offset[j + 1]; ++q) back = back || nl.partner[q] == i;
        if (!back) ++asym;
      }
    }
    std::sort(listed.begin(), listed.end());
    std::vector<std::pair<std::int64_t, std::int64_t>> missing, extra;
    std::set_difference(brute.begin(), brute.end(), listed.begin(), listed.end(), std::back_inserter(missing));
    std::set_difference(listed.begin(), listed.end(), brute.begin(), brute.end(), std::back_inserter(extra));
    t.labelled_row(c.name, {static_cast<double>(c.p.size()), static_cast<double>(brute.size()),
                            static_cast<double>(listed.size()), static_cast<double>(missing.size()),
                            static_cast<double>(extra.size()), static_cast<double>(asym)});
    EXPECT_TRUE(missing.empty()) << c.name;
    EXPECT_TRUE(extra.empty()) << c.name;
    EXPECT_EQ(asym, 0u) << c.name;
    EXPECT_EQ(2 * listed.size(), nl.entries()) << c.name;
    EXPECT_GT(brute.size(), 0u) << c.name;
  }
}

}  // namespace
}  // namespace fluidbed
