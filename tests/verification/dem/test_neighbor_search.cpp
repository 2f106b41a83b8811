// The cell-list Verlet list holds exactly the pairs within r_i + r_j + skin (brute force), each pair once in
// each partner's list.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "dem/neighbor_list.hpp"
#include "dem_closed_form.hpp"

namespace fluidbed {
namespace {

struct Cloud {
  const char* name;
  ParticleStore<2> p;
  double cell_size;
  double skin;
};

/// n particles at uniform random positions in [x0, x1] x [y0, y1] (overlaps allowed), diameters drawn from `d`.
ParticleStore<2> random_cloud(std::size_t n, double x0, double x1, double y0, double y1, const std::vector<double>& d,
                           std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  ParticleStore<2> p;
  for (std::size_t i = 0; i < n; ++i) {
    const auto s = static_cast<std::size_t>(uniform() * static_cast<double>(d.size())) % d.size();
    p.add(static_cast<std::int64_t>(i) * 3 + 5, static_cast<std::int32_t>(s), Species{d[s], 2700.0},
          {x0 + (x1 - x0) * uniform(), y0 + (y1 - y0) * uniform()});
  }
  return p;
}

std::vector<Cloud> clouds() {
  std::vector<Cloud> c;
  const std::vector<double> mono{0.004}, poly{0.002, 0.0035, 0.006};
  c.push_back({"dense mono", random_cloud(3000, 0.0, 0.12, 0.0, 0.12, mono, 1), 0.004 + 4e-4, 4e-4});
  c.push_back({"sparse mono", random_cloud(600, 0.0, 1.0, 0.0, 1.0, mono, 2), 0.004 + 4e-4, 4e-4});
  c.push_back({"dense poly", random_cloud(3000, 0.0, 0.15, 0.0, 0.1, poly, 3), 0.006 + 5e-4, 5e-4});
  c.push_back({"poly, skin 0", random_cloud(2000, 0.0, 0.1, 0.0, 0.1, poly, 4), 0.006, 0.0});
  {
    // Outside the domain and far apart: negative coordinates, one column and one row, and strays so far away
    // that the cell grid hits its size cap and its edge cells are far larger than the rest.
    ParticleStore<2> p = random_cloud(1500, -0.05, 0.05, -0.05, 0.05, poly, 5);
    const ParticleStore<2> strays = random_cloud(40, 500.0, 500.01, -300.0, -299.99, poly, 6);
    for (std::size_t i = 0; i < strays.size(); ++i) {
      p.add(100000 + static_cast<std::int64_t>(i), strays.species[i], Species{2.0 * strays.radius[i], 2700.0},
            strays.pos(i));
    }
    c.push_back({"strays, capped grid", std::move(p), 0.006 + 5e-4, 5e-4});
  }
  {
    // Particles exactly on cell edges, and pairs a hair inside and outside the reach.
    ParticleStore<2> p;
    const double cs = 0.0045, d = 0.004, skin = 5e-4;
    std::int64_t id = 0;
    for (int j = 0; j < 20; ++j) {
      for (int i = 0; i < 20; ++i) p.add(id++, 0, Species{d, 2700.0}, {i * cs, j * cs});
    }
    for (int q = 0; q < 50; ++q) {
      const double reach = d + skin;
      const double x = 1.0 + 0.02 * q, y = 1.0;
      p.add(id++, 0, Species{d, 2700.0}, {x, y});
      p.add(id++, 0, Species{d, 2700.0}, {x + reach * (1.0 + ((q % 2) ? 1e-12 : -1e-12)), y});
    }
    c.push_back({"cell edges, reach +-1e-12", std::move(p), cs, skin});
  }
  {
    // Only one particle, and one column.
    ParticleStore<2> p;
    p.add(0, 0, Species{0.004, 2700.0}, {0.3, 0.3});
    c.push_back({"single particle", std::move(p), 0.0044, 4e-4});
    c.push_back({"one column", random_cloud(400, 0.2, 0.2, 0.0, 0.5, mono, 7), 0.0044, 4e-4});
  }
  return c;
}

TEST(DemNeighborSearch, VerletListEqualsBruteForceAndIsSymmetric) {
  test::Table t("Neighbour list vs brute force (pairs with centre distance < r_i + r_j + skin)",
                {"particles", "pairs brute", "pairs list", "missing", "extra", "asymmetric"}, 28);
  for (Cloud& c : clouds()) {
    ParticleStore<2>& p = c.p;
    p.permute(sort_by_cell(p, c.cell_size));
    NeighborList<2> nl;
    build_neighbor_list(p, c.cell_size, c.skin, nl);
    ASSERT_EQ(nl.offset.size(), p.size() + 1) << c.name;
    ASSERT_EQ(nl.history.size(), nl.partner.size()) << c.name;

    // Every entry i -> j must have exactly one mirror j -> i, and no list may name a partner twice or itself.
    std::map<std::pair<std::size_t, std::size_t>, int> entries;
    for (std::size_t i = 0; i < p.size(); ++i) {
      for (std::size_t k = nl.offset[i]; k < nl.offset[i + 1]; ++k) {
        EXPECT_NE(nl.partner[k], i) << c.name;
        ++entries[{i, nl.partner[k]}];
      }
    }
    std::size_t asymmetric = 0, duplicates = 0;
    std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
    for (const auto& [ij, count] : entries) {
      if (count != 1) ++duplicates;
      if (!entries.contains({ij.second, ij.first})) ++asymmetric;
      if (ij.first < ij.second) {
        const std::int64_t a = p.id[ij.first], b = p.id[ij.second];
        pairs.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
    std::sort(pairs.begin(), pairs.end());
    const auto brute = brute_force_contacts(p, c.skin);
    std::vector<std::pair<std::int64_t, std::int64_t>> missing, extra;
    std::set_difference(brute.begin(), brute.end(), pairs.begin(), pairs.end(), std::back_inserter(missing));
    std::set_difference(pairs.begin(), pairs.end(), brute.begin(), brute.end(), std::back_inserter(extra));
    t.labelled_row(c.name, {static_cast<double>(p.size()), static_cast<double>(brute.size()), static_cast<double>(pairs.size()),
           static_cast<double>(missing.size()), static_cast<double>(extra.size()), static_cast<double>(asymmetric)});
    EXPECT_EQ(duplicates, 0u) << c.name;
    EXPECT_EQ(asymmetric, 0u) << c.name;
    EXPECT_TRUE(missing.empty()) << c.name << ": " << missing.size() << " pairs missing";
    EXPECT_TRUE(extra.empty()) << c.name << ": " << extra.size() << " pairs too many";
    EXPECT_EQ(2 * pairs.size(), nl.entries()) << c.name;
    if (std::string(c.name) != "single particle") {
      EXPECT_GT(brute.size(), 0u) << c.name << ": the configuration must test something";
    }
  }
}

}  // namespace
}  // namespace fluidbed
