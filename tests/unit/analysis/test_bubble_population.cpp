// BubblePopulation on synthetic voidage fields, 2D and 3D: boxes of eps = 1 in a bed of eps = 0.43 under a
// freeboard of eps = 1. Every size is a whole number of cells, so sizes are compared exactly; the nose and the
// centroid of a box moving by whole cells per sample move by exactly those cells (the sub-cell contour offset is the
// same at every sample), so the velocities are exact up to rounding (tolerance 1e-9 of the speed).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "analysis/bubble_population.hpp"
#include "core/error.hpp"
#include "run/analysis_csv.hpp"

namespace fluidbed {
namespace {

constexpr double eps_bed = 0.43;
constexpr double h = 0.01;  // cell size, m
constexpr int nx = 40, ny = 60, nz = 8;
constexpr int freeboard_row = 50;  // rows from here up are freeboard (eps = 1): bed surface at 0.50 m

// A box of cells [i0, i1) x [j0, j1) (x [2, 6) in depth in 3D).
struct Box {
  int i0, i1, j0, j1;
  std::size_t cells(int dim) const { return static_cast<std::size_t>((i1 - i0) * (j1 - j0) * (dim == 3 ? 4 : 1)); }
};

template <int Dim>
struct Bed {
  CellGeometry<Dim> g;
  std::vector<double> v;
  Bed() {
    g.n[0] = nx;
    g.n[1] = ny;
    if constexpr (Dim == 3) g.n[2] = nz;
    g.h.fill(h);
    g.origin.fill(0.0);
  }
  CellView<Dim> frame(const std::vector<Box>& boxes, bool freeboard = true) {
    v.assign(g.cells(), eps_bed);
    for (std::size_t k = 0; k < v.size(); ++k) {
      const Index<Dim> c = g.cell_of(k);
      if (freeboard && c[1] >= freeboard_row) v[k] = 1.0;
      if (Dim == 3 && (c[Dim - 1] < 2 || c[Dim - 1] >= 6)) continue;
      for (const Box& b : boxes)
        if (c[0] >= b.i0 && c[0] < b.i1 && c[1] >= b.j0 && c[1] < b.j1) v[k] = 1.0;
    }
    return {g, v.data()};
  }
};

template <class T>
class BubblePopulationTest : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(BubblePopulationTest, Dims);

std::vector<BubbleEventRecord> events_of(const std::vector<BubbleEventRecord>& all, BubbleEvent e) {
  std::vector<BubbleEventRecord> out;
  for (const auto& r : all)
    if (r.event == e) out.push_back(r);
  return out;
}

TYPED_TEST(BubblePopulationTest, TwoBubblesRiseAndCoalesce) {
  constexpr int Dim = TypeParam::value;
  Bed<Dim> bed;
  PopulationConfig cfg;
  BubblePopulation<Dim> pop(cfg);
  const Box a0{5, 9, 5, 9}, b0{12, 18, 5, 9};
  auto r0 = pop.observe(0.0, bed.frame({a0, b0}));
  ASSERT_EQ(r0.size(), 2u);
  const int id_a = r0[0].id, id_b = r0[1].id;  // a is met first in storage order
  EXPECT_EQ(r0[0].event, BubbleEvent::Birth);
  EXPECT_NE(id_a, id_b);
  // Rising one row per sample and drifting together; at the third sample they touch.
  auto r1 = pop.observe(0.1, bed.frame({{6, 10, 6, 10}, {11, 17, 6, 10}}));
  ASSERT_EQ(r1.size(), 2u);
  EXPECT_EQ(r1[0].id, id_a);
  EXPECT_EQ(r1[1].id, id_b);
  auto r2 = pop.observe(0.2, bed.frame({{7, 11, 7, 11}, {11, 17, 7, 11}}));
  ASSERT_EQ(r2.size(), 1u);
  const std::size_t exact = a0.cells(Dim) + b0.cells(Dim);
  std::printf("coalescence %dD: cells exact %zu computed %zu, surviving id %d (larger parent %d)\n", Dim, exact,
              r2[0].cells, r2[0].id, id_b);
  EXPECT_EQ(r2[0].cells, exact);
  EXPECT_DOUBLE_EQ(r2[0].size, static_cast<double>(exact) * (Dim == 2 ? h * h : h * h * h));
  EXPECT_EQ(r2[0].id, id_b);  // the larger parent's id survives
  EXPECT_EQ(r2[0].event, BubbleEvent::Coalescence);
  EXPECT_EQ(r2[0].parents, (std::vector<int>{id_a, id_b}));
  EXPECT_FALSE(r2[0].u_centroid);  // the merger restarts the velocity
  const auto co = events_of(pop.events(), BubbleEvent::Coalescence);
  ASSERT_EQ(co.size(), 1u);
  EXPECT_EQ(co[0].id, id_b);
  EXPECT_EQ(co[0].others, std::vector<int>{id_a});
  EXPECT_TRUE(events_of(pop.events(), BubbleEvent::Disappearance).empty());
  EXPECT_TRUE(events_of(pop.events(), BubbleEvent::Split).empty());
  EXPECT_EQ(pop.frames().back().bubbles, 1);
}

TYPED_TEST(BubblePopulationTest, OneBubbleSplitsIntoTwoChildren) {
  constexpr int Dim = TypeParam::value;
  Bed<Dim> bed;
  BubblePopulation<Dim> pop(PopulationConfig{});
  auto r0 = pop.observe(0.0, bed.frame({{5, 15, 10, 14}}));
  ASSERT_EQ(r0.size(), 1u);
  const int parent = r0[0].id;
  auto r1 = pop.observe(0.1, bed.frame({{5, 9, 11, 15}, {11, 15, 11, 15}}));
  std::printf("split %dD: children %zu (exact 2)\n", Dim, r1.size());
  ASSERT_EQ(r1.size(), 2u);
  for (const auto& c : r1) {
    EXPECT_EQ(c.event, BubbleEvent::Split);
    EXPECT_EQ(c.parents, std::vector<int>{parent});
    EXPECT_NE(c.id, parent);
    EXPECT_EQ(c.cells, (Box{0, 4, 0, 4}.cells(Dim)));
  }
  EXPECT_NE(r1[0].id, r1[1].id);
  const auto sp = events_of(pop.events(), BubbleEvent::Split);
  ASSERT_EQ(sp.size(), 1u);
  EXPECT_EQ(sp[0].id, parent);
  EXPECT_EQ(sp[0].others, (std::vector<int>{r1[0].id, r1[1].id}));
  // The children then rise as ordinary bubbles with their own ids.
  auto r2 = pop.observe(0.2, bed.frame({{5, 9, 12, 16}, {11, 15, 12, 16}}));
  ASSERT_EQ(r2.size(), 2u);
  EXPECT_EQ(r2[0].id, r1[0].id);
  EXPECT_EQ(r2[0].event, BubbleEvent::None);
}

TYPED_TEST(BubblePopulationTest, EruptionAtTheSurfaceAndDisappearanceInTheBed) {
  constexpr int Dim = TypeParam::value;
  Bed<Dim> bed;
  PopulationConfig cfg;
  cfg.min_size = 2.0 * (Dim == 2 ? h * h : h * h * h * 4);
  BubblePopulation<Dim> pop(cfg);
  // A bubble two rows below the surface, a second one deep in the bed, and a one-cell void below min_size.
  auto r0 = pop.observe(0.0, bed.frame({{10, 16, 44, 48}, {25, 30, 10, 14}, {35, 36, 20, 21}}));
  ASSERT_EQ(r0.size(), 2u);  // the freeboard and the small void are not bubbles
  const int rising = r0[1].id, fading = r0[0].id;
  EXPECT_GT(r0[1].centroid[1], r0[0].centroid[1]);
  auto r1 = pop.observe(0.1, bed.frame({{10, 16, 46, 50}}));  // reaches the freeboard; the deep one has collapsed
  EXPECT_TRUE(r1.empty());
  const auto er = events_of(pop.events(), BubbleEvent::Eruption);
  const auto gone = events_of(pop.events(), BubbleEvent::Disappearance);
  std::printf("eruption %dD: %zu eruption (id %d), %zu disappearance\n", Dim, er.size(), er.empty() ? -1 : er[0].id,
              gone.size());
  ASSERT_EQ(er.size(), 1u);
  EXPECT_EQ(er[0].id, rising);
  EXPECT_DOUBLE_EQ(er[0].time, 0.1);
  ASSERT_EQ(gone.size(), 1u);
  EXPECT_EQ(gone[0].id, fading);
  ASSERT_TRUE(pop.frames().back().bed_height);
  EXPECT_DOUBLE_EQ(*pop.frames().back().bed_height, freeboard_row * h);
}

TYPED_TEST(BubblePopulationTest, GrowingAttachedBubbleNoseTwiceTheCentroid) {
  // A bubble on the bottom face, 6 cells wide, whose top rises by two cells per sample: the centroid is half its
  // height and rises h per sample, the nose (top face less a constant sub-cell offset) 2 h: ratio exactly 2.
  constexpr int Dim = TypeParam::value;
  Bed<Dim> bed;
  PopulationConfig cfg;
  BubblePopulation<Dim> pop(cfg);
  const double dt = 0.02;
  std::vector<BubbleRecord<Dim>> r;
  for (int s = 0; s < 4; ++s) r = pop.observe(s * dt, bed.frame({{17, 23, 0, 4 + 2 * s}}));
  ASSERT_EQ(r.size(), 1u);
  ASSERT_TRUE(r[0].u_centroid && r[0].u_nose);
  const double uc = h / dt, un = 2.0 * h / dt;
  std::printf("growing %dD: u_centroid exact %.6g computed %.6g; u_nose exact %.6g computed %.6g; ratio %.12g\n", Dim,
              uc, *r[0].u_centroid, un, *r[0].u_nose, *r[0].u_nose / *r[0].u_centroid);
  EXPECT_NEAR(*r[0].u_centroid, uc, 1e-9 * uc);
  EXPECT_NEAR(*r[0].u_nose, un, 1e-9 * un);
  EXPECT_NEAR(*r[0].u_nose / *r[0].u_centroid, 2.0, 1e-9);
  // Contour offset: eps falls from 1 to 0.43 between centres, crossing 0.8 at (1 - 0.8) / (1 - 0.43) of a cell
  // beyond the bubble's last centre, i.e. off = 0.5 - 0.2 / 0.57 cells inside its faces. The tail is the bottom face.
  const double off = (0.5 - 0.2 / 0.57) * h;
  // Width: 6 cells along x; in 3D the mean of that and the 4 cells along z.
  const double height = 10 * h, width = (Dim == 2 ? 6 : 5) * h;
  EXPECT_NEAR(r[0].nose, height - off, 1e-12);
  EXPECT_NEAR(r[0].tail, 0.0, 1e-12);
  EXPECT_NEAR(r[0].aspect_ratio, (height - off) / (width - 2.0 * off), 1e-12);
  // A distributor zone of two cells excludes the attached bubble.
  cfg.distributor_height = 2 * h;
  BubblePopulation<Dim> excluded(cfg);
  EXPECT_TRUE(excluded.observe(0.0, bed.frame({{17, 23, 0, 4}})).empty());
  EXPECT_EQ(excluded.observe(0.1, bed.frame({{17, 23, 3, 7}})).size(), 1u);
  EXPECT_EQ(excluded.events().back().event, BubbleEvent::Birth);
}

TYPED_TEST(BubblePopulationTest, SteadyRiseCentroidAndNoseAtThePrescribedSpeed) {
  constexpr int Dim = TypeParam::value;
  Bed<Dim> bed;
  PopulationConfig cfg;
  cfg.velocity_samples = 3;
  BubblePopulation<Dim> pop(cfg);
  const double u = 0.5, dt = h / u;  // one row per sample
  std::vector<BubbleRecord<Dim>> r;
  int id = -1;
  for (int s = 0; s < 6; ++s) {
    r = pop.observe(1.0 + s * dt, bed.frame({{14, 22, 8 + s, 14 + s}}));
    ASSERT_EQ(r.size(), 1u);
    if (s == 0) id = r[0].id;
    EXPECT_EQ(r[0].id, id);
  }
  ASSERT_TRUE(r[0].u_centroid && r[0].u_nose);
  std::printf("steady %dD: exact %.6g, u_centroid %.15g (error %.2g), u_nose %.15g (error %.2g)\n", Dim, u,
              *r[0].u_centroid, *r[0].u_centroid - u, *r[0].u_nose, *r[0].u_nose - u);
  EXPECT_NEAR(*r[0].u_centroid, u, 1e-9 * u);
  EXPECT_NEAR(*r[0].u_nose, u, 1e-9 * u);
  EXPECT_EQ(pop.events().size(), 1u);  // the birth only
}

TYPED_TEST(BubblePopulationTest, RestoredStateSamplesTheSame) {
  // A checkpoint after the third sample (the merger): the restored population gives the same rows, velocities and
  // events, byte for byte, and the next new bubble the next id.
  constexpr int Dim = TypeParam::value;
  Bed<Dim> bed;
  PopulationConfig cfg;
  cfg.velocity_samples = 3;
  const std::vector<std::vector<Box>> frames = {{{5, 9, 5, 9}, {12, 18, 5, 9}},
                                                {{6, 10, 6, 10}, {11, 17, 6, 10}},
                                                {{7, 11, 7, 11}, {11, 17, 7, 11}},
                                                {{7, 11, 8, 12}, {11, 17, 8, 12}},
                                                {{7, 11, 9, 13}, {11, 17, 9, 13}, {30, 34, 20, 24}}};
  const auto rows = [](const std::vector<BubbleRecord<Dim>>& r, const std::vector<BubbleEventRecord>& e) {
    std::string out;
    for (const auto& b : r) out += bubbles_csv_row(b) + "\n";
    for (const auto& x : e) out += bubble_events_csv_row(x) + "\n";
    return out;
  };
  BubblePopulation<Dim> whole(cfg), first(cfg), second(cfg);
  std::vector<std::string> expected, got;
  for (std::size_t s = 0; s < frames.size(); ++s) {
    const auto& r = whole.observe(0.01 * static_cast<double>(s), bed.frame(frames[s]));
    expected.push_back(rows(r, whole.sample_events()));
  }
  for (std::size_t s = 0; s < 3; ++s) first.observe(0.01 * static_cast<double>(s), bed.frame(frames[s]));
  second.restore(first.state());
  for (std::size_t s = 3; s < frames.size(); ++s) {
    const auto& r = second.observe(0.01 * static_cast<double>(s), bed.frame(frames[s]));
    got.push_back(rows(r, second.sample_events()));
  }
  for (std::size_t s = 3; s < frames.size(); ++s) EXPECT_EQ(got[s - 3], expected[s]) << "sample " << s;
  EXPECT_TRUE(second.current().front().u_centroid);  // from the sample before the checkpoint
  EXPECT_NE(expected[4].find("birth"), std::string::npos);
  EXPECT_NE(expected[2].find("coalescence"), std::string::npos);
}

// A 0.06 m column, 6 cells of 0.01 m across (and 6 deep in 3D), bed surface at 0.5 m. Voids are boxes of cells
// [i0, i1) x [j0, j1) x [k0, k1) (k ignored in 2D).
template <int Dim>
struct Column {
  using Void = std::array<int, 6>;
  CellGeometry<Dim> g;
  std::vector<double> v;
  Column() {
    g.n[0] = 6;
    g.n[1] = ny;
    if constexpr (Dim == 3) g.n[2] = 6;
    g.h.fill(h);
    g.origin.fill(0.0);
  }
  CellView<Dim> frame(const std::vector<Void>& voids, int lift) {
    v.assign(g.cells(), eps_bed);
    for (std::size_t k = 0; k < v.size(); ++k) {
      const Index<Dim> c = g.cell_of(k);
      if (c[1] >= freeboard_row) v[k] = 1.0;
      for (const Void& b : voids) {
        const bool in_z = Dim == 2 || (c[Dim - 1] >= b[4] && c[Dim - 1] < b[5]);
        if (in_z && c[0] >= b[0] && c[0] < b[1] && c[1] >= b[2] + lift && c[1] < b[3] + lift) v[k] = 1.0;
      }
    }
    return {g, v.data()};
  }
};

TYPED_TEST(BubblePopulationTest, AVoidAcrossTheColumnIsASlugNotABubble) {
  // A plug lifted off the distributor leaves a void across the whole section: two overlapping boxes, a step between
  // them, that together hold every column (and every depth in 3D); 4 x 6 + 3 x 6 - 3 = 39 cells per depth, D_eq =
  // 0.070 m in 2D (0.077 m in 3D) in the 0.06 m column. A free bubble of 3 x 3 (x 3) cells rises above it; a void
  // on the left wall across half the width is no slug, nor (3D) one across the width but half the depth.
  constexpr int Dim = TypeParam::value;
  Column<Dim> col;
  using Void = typename Column<Dim>::Void;
  std::vector<Void> voids = {{0, 4, 10, 16, 0, 6}, {3, 6, 13, 19, 0, 6}, {1, 4, 30, 33, 1, 4}, {0, 3, 40, 43, 0, 6}};
  if (Dim == 3) voids.push_back({0, 6, 45, 47, 0, 3});
  const std::size_t slug_cells = (4 * 6 + 3 * 6 - 3) * (Dim == 3 ? 6 : 1);
  const std::size_t others = Dim == 3 ? 1 + 2 : 1 + 1;  // the bubble, the wall void (and the half-depth one)
  BubblePopulation<Dim> pop(PopulationConfig{});
  const double dt = 0.02;
  int slug_id = -1;
  for (int s = 0; s < 2; ++s) {
    const auto r = pop.observe(s * dt, col.frame(voids, s));  // everything one row higher at the second sample
    ASSERT_EQ(r.size(), others + 1);
    double measure = 0.0;
    std::size_t slugs = 0;
    for (const BubbleRecord<Dim>& b : r) {
      const std::string row = bubbles_csv_row(b);
      EXPECT_EQ(row.substr(row.rfind(',')), b.slug ? ",1" : ",0") << row;
      if (!b.slug) {
        measure += b.size;
        continue;
      }
      ++slugs;
      EXPECT_EQ(b.cells, slug_cells);
      std::printf("slug %dD, sample %d: cells exact %zu computed %zu, D_eq %.4f m, id %d\n", Dim, s, slug_cells,
                  b.cells, b.equivalent_diameter, b.id);
      if (s == 0) {
        slug_id = b.id;
      } else {
        // Followed like a bubble: the same id, rising one row per sample.
        EXPECT_EQ(b.id, slug_id);
        EXPECT_EQ(b.event, BubbleEvent::None);
        ASSERT_TRUE(b.u_centroid);
        EXPECT_NEAR(*b.u_centroid, h / dt, 1e-9 * h / dt);
      }
    }
    EXPECT_EQ(slugs, 1u);
    const BubbleFrame& f = pop.frames().back();
    std::printf("frame %dD, sample %d: bubbles %d (exact %zu), slugs %d (exact 1)\n", Dim, s, f.bubbles, others,
                f.slugs);
    EXPECT_EQ(f.bubbles, static_cast<int>(others));
    EXPECT_EQ(f.slugs, 1);
    EXPECT_DOUBLE_EQ(f.bubble_measure, measure);
    const std::string frame = bubble_frames_csv_row(f);
    EXPECT_EQ(frame.substr(frame.rfind(',')), ",1") << frame;
  }
}

TEST(BubblePopulation, CsvColumns) {
  BubbleRecord<3> b;
  b.time = 0.5;
  b.id = 3;
  b.event = BubbleEvent::Coalescence;
  b.parents = {1, 3};
  b.size = 2e-3;
  b.centroid = {0.1, 0.2, 0.3};
  b.u_centroid = 0.25;
  EXPECT_EQ(bubbles_csv_header(3),
            "time_s,id,event,parents,volume_m3,equivalent_diameter_m,centroid_x_m,centroid_y_m,centroid_z_m,nose_m,"
            "tail_m,aspect_ratio,u_centroid_m_s,u_nose_m_s,slug");
  EXPECT_EQ(bubbles_csv_row(b), "0.5,3,coalescence,1;3,0.002,0,0.1,0.2,0.3,0,0,0,0.25,,0");
  b.slug = true;
  EXPECT_EQ(bubbles_csv_row(b), "0.5,3,coalescence,1;3,0.002,0,0.1,0.2,0.3,0,0,0,0.25,,1");
  EXPECT_EQ(bubbles_csv_header(2), "time_s,id,event,parents,area_m2,equivalent_diameter_m,centroid_x_m,centroid_y_m,"
                                   "nose_m,tail_m,aspect_ratio,u_centroid_m_s,u_nose_m_s,slug");
  BubbleFrame f;
  f.time = 0.5;
  f.bed_height = 0.4;
  f.bed_measure = 0.2;
  f.bubble_measure = 0.05;
  f.bubbles = 2;
  f.slugs = 1;
  EXPECT_EQ(bubble_frames_csv_header(), "time_s,bed_height_m,bed_measure,bubble_measure,bubbles,bubble_fraction,slugs");
  EXPECT_EQ(bubble_frames_csv_row(f), "0.5,0.4,0.2,0.05,2,0.25,1");
  EXPECT_THROW(BubblePopulation<2>(PopulationConfig{.eps_threshold = 1.5}), Error);
}

}  // namespace
}  // namespace fluidbed
