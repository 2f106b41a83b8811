// ParticleStore<Dim>: the one table of attributes (for_each_array) drives add, permute and clear, names every
// array once, and gives the bytes per particle in 2D and 3D.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include <fmt/format.h>

#include "dem/particle_store.hpp"

namespace fluidbed {
namespace {

template <int Dim>
void check_store(std::size_t expected_bytes, std::size_t expected_arrays) {
  ParticleStore<Dim> p;
  std::set<std::string> names;
  std::size_t arrays = 0;
  p.for_each_array([&](const std::string& name, auto&, ArrayRole) {
    names.insert(name);
    ++arrays;
  });
  EXPECT_EQ(names.size(), arrays) << "every array has its own name";
  EXPECT_EQ(arrays, expected_arrays);
  const std::size_t bytes = ParticleStore<Dim>::bytes_per_particle();
  fmt::print("ParticleStore<{}>: {} arrays, {} bytes per particle\n", Dim, arrays, bytes);
  EXPECT_EQ(bytes, expected_bytes);

  const Species s{0.004, 2700.0};
  for (int k = 0; k < 5; ++k) {
    Vec<Dim> x, v;
    for (int a = 0; a < Dim; ++a) {
      x[a] = 0.1 * k + a;
      v[a] = -1.0 * k - a;
    }
    Spin<Dim> w{};
    if constexpr (Dim == 2) {
      w = 3.0 * k;
    } else {
      w = Vec3{3.0 * k, 4.0 * k, 5.0 * k};
    }
    p.add(10 + k, 0, s, x, v, w, k);
  }
  // Every array has one value per particle.
  p.for_each_array([&](const std::string& name, auto& a, ArrayRole) { EXPECT_EQ(a.size(), 5u) << name; });
  p.permute({4, 2, 0});
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p.id[0], 14);
  EXPECT_EQ(p.id[1], 12);
  EXPECT_EQ(p.layer[2], 0);
  EXPECT_EQ(p.pos(0)[Dim - 1], 0.4 + (Dim - 1));
  EXPECT_EQ(p.vel(1)[0], -2.0);
  EXPECT_EQ(p.spin(0), p.spin(0));
  p.sort_by_id();
  EXPECT_EQ(p.id[0], 10);
  EXPECT_EQ(p.pos(2)[Dim - 1], 0.4 + (Dim - 1));
  p.clear();
  p.for_each_array([&](const std::string& name, auto& a, ArrayRole) { EXPECT_TRUE(a.empty()) << name; });
}

// 2D: id, species, layer + 17 doubles = 20 arrays, 16 + 17 x 8 = 152 bytes.
// 3D: id, species, layer + 26 doubles = 29 arrays, 16 + 26 x 8 = 224 bytes.
// (The wall springs, 64 and 144 bytes of every particle when they were attributes here, are in WallSprings.)
TEST(DemParticleStore, OneTableOfAttributesIn2DAnd3D) {
  check_store<2>(160, 21);
  check_store<3>(232, 30);
}

}  // namespace
}  // namespace fluidbed
