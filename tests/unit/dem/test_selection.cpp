// Selections of slots kept in place (dem/selection.hpp): the particles that stay on a rank after a migration. Each
// holder's in-place path must give what its copying path gives for the same selection, bit for bit.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "dem/held_springs.hpp"
#include "dem/particle_store.hpp"
#include "dem/selection.hpp"
#include "dem/wall_springs.hpp"

namespace fluidbed {
namespace {

TEST(DemSelection, AscendingSelectionsAreRecognised) {
  EXPECT_TRUE(is_ascending_selection({}));
  EXPECT_TRUE(is_ascending_selection({0, 1, 2}));
  EXPECT_TRUE(is_ascending_selection({1, 4, 7}));
  EXPECT_FALSE(is_ascending_selection({1, 1, 2}));  // a slot named twice is not a selection in place
  EXPECT_FALSE(is_ascending_selection({2, 1}));
}

TEST(DemSelection, InPlaceWithAStrideKeepsTheNamedSlots) {
  std::vector<int> v{0, 1, 10, 11, 20, 21, 30, 31, 40, 41};
  select_in_place(v, {0, 2, 4}, 2);
  EXPECT_EQ(v, (std::vector<int>{0, 1, 20, 21, 40, 41}));
}

TEST(DemSelection, AnyOrderWithAStrideGoesThroughACopy) {
  std::vector<int> v{0, 1, 10, 11, 20, 21, 30, 31};
  select_slots(v, {3, 0, 2}, 2);  // slot 0 takes slot 3: not in place
  EXPECT_EQ(v, (std::vector<int>{30, 31, 0, 1, 20, 21}));
  select_slots(v, {1, 2}, 2);  // reads forward: in place
  EXPECT_EQ(v, (std::vector<int>{0, 1, 20, 21}));
}

// The store's arrays, the wall springs and the held springs each under one ascending selection (in place) and under
// the same selection followed by a no-op swap that forces the copying path: the same contents.
TEST(DemSelection, HoldersGiveTheSameContentsInPlaceAndByCopy) {
  ParticleStore<3> a;
  HeldSprings<3> ha;
  ha.clear(0, true);
  WallSprings<3> wa;
  wa.reset(0);
  const Species s{0.004, 2700.0};
  for (int k = 0; k < 9; ++k) {
    a.add(100 + k, 0, s, Vec3{0.1 * k, 0.2 * k, 0.3 * k}, Vec3{-1.0 * k, 0.5, 2.0}, Vec3{3.0 * k, 4.0, 5.0}, k);
    ha.add_particle();
    wa.push_back();
    for (int e = 0; e < k % 3; ++e) ha.add(200 + 10 * k + e, Vec3{1.0 * k, -2.0 * e, 0.5}, Vec3{0.0, 1.0 * e, 0.0});
    if (k % 2 == 1) wa.set(static_cast<std::size_t>(k), 1, Vec3{0.25 * k, 0.0, -0.0});
  }
  ParticleStore<3> b = a;
  HeldSprings<3> hb = ha;
  WallSprings<3> wb = wa;
  const std::vector<std::size_t> keep{1, 2, 4, 5, 8};
  a.permute(keep);
  ha.select(keep);
  wa.permute(keep);
  // The copying path: the selection reversed, then reversed back (neither order ascending).
  std::vector<std::size_t> reversed(keep.rbegin(), keep.rend());
  const std::vector<std::size_t> back{4, 3, 2, 1, 0};
  b.permute(reversed);
  b.permute(back);
  hb.select(reversed);
  hb.select(back);
  wb.permute(reversed);
  wb.permute(back);
  ASSERT_EQ(a.size(), keep.size());
  a.for_each_array([&](const std::string& name, auto& arr, ArrayRole) {
    b.for_each_array([&](const std::string& other, auto& brr, ArrayRole) {
      if constexpr (std::is_same_v<std::decay_t<decltype(arr)>, std::decay_t<decltype(brr)>>) {
        if (name == other) {
          EXPECT_EQ(arr, brr) << name;
        }
      }
    });
  });
  EXPECT_EQ(ha.offset, hb.offset);
  EXPECT_EQ(ha.partner_id, hb.partner_id);
  ASSERT_EQ(ha.xi.size(), hb.xi.size());
  for (std::size_t q = 0; q < ha.xi.size(); ++q) {
    EXPECT_EQ(ha.xi[q], hb.xi[q]);
    EXPECT_EQ(ha.roll[q], hb.roll[q]);
  }
  EXPECT_EQ(wa.records(), wb.records());
  for (std::size_t i = 0; i < keep.size(); ++i) {
    for (int w = 0; w < 6; ++w) EXPECT_EQ(wa.get(i, w), wb.get(i, w)) << i << " " << w;
  }
}

}  // namespace
}  // namespace fluidbed
