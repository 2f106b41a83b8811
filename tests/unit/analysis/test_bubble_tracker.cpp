// Bubble tracker on synthetic voidage fields whose nose, speed, attachment and eruption are known in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "analysis/bed_surface.hpp"
#include "analysis/bubble_tracker.hpp"
#include "analysis/rise_velocity.hpp"
#include "run/analysis_csv.hpp"

namespace fluidbed {
namespace {

constexpr double eps_bed = 0.43;
constexpr double thr = 0.8;

// A void of voidage 1 inside radius r_in, falling linearly to the bed value at r_out (a smoothly bounded disc).
struct RampDisc {
  double xc, yc, r_in, r_out;
  double eps(double x, double y) const {
    const double r = std::hypot(x - xc, y - yc);
    const double s = std::clamp((r_out - r) / (r_out - r_in), 0.0, 1.0);
    return eps_bed + (1.0 - eps_bed) * s;
  }
  // Height of the eps = thr contour on the vertical line through the centre.
  double nose() const { return yc + r_out - (thr - eps_bed) / (1.0 - eps_bed) * (r_out - r_in); }
};

Field<2> disc_field(const Grid<2>& g, const RampDisc& d, double bed_top = 1e300) {
  Field<2> f(cell_field(g));
  for (int j = 0; j < g.n(1); ++j)
    for (int i = 0; i < g.n(0); ++i) f(i, j) = g.centre(1, j) < bed_top ? d.eps(g.centre(0, i), g.centre(1, j)) : 1.0;
  return f;
}

// One sample of the tracker from ghost-free cell fields on the grid: voidage and vertical gas velocity.
BubbleSample observe_2d(BubbleTracker& tracker, double t, const Grid<2>& g, const Field<2>& eps, const Field<2>& vg) {
  return tracker.observe<2>(t, cell_view(g, eps, "eps"), cell_view(g, vg, "vg"));
}

BubbleConfig fine_config(const Grid<2>& g, double jet_x) {
  BubbleConfig c;
  c.cells = {g.n(0), g.n(1), 0};
  c.jet_x = jet_x;
  c.jet_width = 0.02;
  c.min_area = 4.0 * g.h[0] * g.h[1];
  return c;
}

TEST(BubbleTracker, RiseVelocityOfMovingDisc) {
  // 0.6 x 1 m at 5 mm: the ramp (20 mm = 4 cells) holds both cell centres bracketing the threshold (1.4 cells
  // inside it, 2.6 cells from its outer edge), so the linear interpolation of the nose is exact and so is the speed.
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {120, 200});
  const double x_line = g.centre(0, 60);
  BubbleTracker tracker(fine_config(g, x_line));
  const Field<2> zero(cell_field(g, 0.0));
  const double u_b = 0.7, dt = 0.0137;
  for (int n = 0; n < 20; ++n) {
    const double t = n * dt;
    const RampDisc d{x_line, 0.3 + u_b * t, 0.04, 0.06};
    const BubbleSample s = observe_2d(tracker, t, g, disc_field(g, d), zero);
    ASSERT_TRUE(s.nose_height.has_value());
    EXPECT_NEAR(*s.nose_height, d.nose(), 1e-12);
    if (n == 0) {
      EXPECT_FALSE(s.rise_velocity.has_value());
      continue;
    }
    ASSERT_TRUE(s.rise_velocity.has_value());
    // The acceptance asks for 1%; the estimator is exact here, so the error is round-off.
    EXPECT_NEAR(*s.rise_velocity, u_b, 0.01 * u_b);
    EXPECT_NEAR(*s.rise_velocity, u_b, 1e-9);
    EXPECT_EQ(s.bubble_id, 0);
    EXPECT_FALSE(*s.attached);
  }
}

TEST(BubbleTracker, ThroughflowFromKnownGasField) {
  // A gas velocity linear in x and y is reproduced exactly by bilinear interpolation, so
  // U_th/U_mf = (v(x_nose, nose + dy/2) - U_b)/U_mf holds to round-off.
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {120, 200});
  const double x_line = g.centre(0, 60);
  BubbleConfig c = fine_config(g, x_line);
  c.u_mf = 1.8;
  BubbleTracker tracker(c);
  const auto v_exact = [](double x, double y) { return 2.5 + 0.7 * x + 3.1 * y; };
  Field<2> ug(cell_field(g, 0.0)), vg(cell_field(g));
  for (int j = 0; j < g.n(1); ++j)
    for (int i = 0; i < g.n(0); ++i) vg(i, j) = v_exact(g.centre(0, i), g.centre(1, j));
  const double u_b = 0.55, dt = 0.01;
  for (int n = 0; n < 6; ++n) {
    const RampDisc d{x_line, 0.25 + u_b * n * dt, 0.04, 0.06};
    const BubbleSample s = observe_2d(tracker, n * dt, g, disc_field(g, d), vg);
    ASSERT_TRUE(s.nose_gas_velocity.has_value());
    EXPECT_NEAR(*s.nose_gas_velocity, v_exact(x_line, d.nose() + 0.5 * g.h[1]), 1e-12);
    if (n == 0) continue;
    ASSERT_TRUE(s.throughflow_ratio.has_value());
    EXPECT_NEAR(*s.throughflow_ratio, (v_exact(x_line, d.nose() + 0.5 * g.h[1]) - u_b) / c.u_mf, 1e-9);
  }
}

TEST(BubbleTracker, DetachmentAtTheExactSample) {
  // A sharply bounded disc (eps = 1 where the cell centre is inside) starting over the jet and rising; it is
  // attached while a bottom-row cell above the jet has its centre inside the disc.
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {60, 100});  // 1 cm cells
  const double jet_x = 0.3, jet_w = 0.02;              // jet over columns 29 and 30
  BubbleConfig c = fine_config(g, jet_x);
  c.jet_width = jet_w;
  BubbleTracker tracker(c);
  const Field<2> zero(cell_field(g, 0.0));
  const double radius = 0.05, u_b = 0.8, dt = 0.004;
  int expected = -1, detected = -1;
  for (int n = 0; n < 40; ++n) {
    const double yd = 0.03 + u_b * n * dt;
    Field<2> eps(cell_field(g, eps_bed));
    for (int j = 0; j < g.n(1); ++j)
      for (int i = 0; i < g.n(0); ++i)
        if (std::hypot(g.centre(0, i) - jet_x, g.centre(1, j) - yd) < radius) eps(i, j) = 1.0;
    bool touches = false;
    for (int i = 0; i < g.n(0); ++i) {
      const bool over_jet = g.centre(0, i) + 0.5 * g.h[0] > jet_x - 0.5 * jet_w && g.centre(0, i) - 0.5 * g.h[0] < jet_x + 0.5 * jet_w;
      if (over_jet && std::hypot(g.centre(0, i) - jet_x, g.centre(1, 0) - yd) < radius) touches = true;
    }
    if (!touches && expected < 0) expected = n;
    const BubbleSample s = observe_2d(tracker, n * dt, g, eps, zero);
    ASSERT_TRUE(s.attached.has_value());
    EXPECT_EQ(*s.attached, touches) << "sample " << n;
    if (s.detached && detected < 0) detected = n;
  }
  ASSERT_GT(expected, 0);
  EXPECT_EQ(detected, expected);
  ASSERT_TRUE(tracker.detachment_time().has_value());
  EXPECT_DOUBLE_EQ(*tracker.detachment_time(), expected * dt);
}

TEST(BubbleTracker, FollowsTheDetachedBubbleNotTheJetVoid) {
  // A void that stays on the jet (2 x 2 cells) while the bubble that grew from it rises: after they split, the
  // tracker keeps the rising bubble (most cells shared with the previous sample), now detached.
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {60, 100});
  BubbleTracker tracker(fine_config(g, 0.3));
  const Field<2> zero(cell_field(g, 0.0));
  const double dt = 0.01, u_b = 1.0;
  bool split_seen = false;
  for (int n = 0; n < 30; ++n) {
    const RampDisc d{g.centre(0, 30), 0.04 + u_b * n * dt, 0.03, 0.05};
    Field<2> eps = disc_field(g, d);
    for (int j = 0; j < 2; ++j)
      for (int i = 29; i < 31; ++i) eps(i, j) = 1.0;
    const BubbleSample s = observe_2d(tracker, n * dt, g, eps, zero);
    ASSERT_TRUE(s.nose_height.has_value());
    EXPECT_EQ(s.bubble_id, 0) << "sample " << n;
    // The nose on the line x = 0.3 lies between columns 29 and 30, half a cell off the disc centre: within a cell.
    EXPECT_NEAR(*s.nose_height, d.nose(), g.h[1]) << "sample " << n;
    if (!*s.attached) split_seen = true;
    if (split_seen) {
      EXPECT_FALSE(*s.attached) << "sample " << n;
    }
  }
  EXPECT_TRUE(split_seen);
  ASSERT_TRUE(tracker.detachment_time().has_value());
}

TEST(BubbleTracker, NoBubbleNoError) {
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {30, 50});
  BubbleConfig c;
  c.cells = {g.n(0), g.n(1), 0};
  BubbleTracker tracker(c);
  const Field<2> zero(cell_field(g, 0.0));
  // A packed bed with a freeboard and no void: bed height at the top face of the last bed row.
  Field<2> bed(cell_field(g, 1.0));
  for (int j = 0; j < 27; ++j)
    for (int i = 0; i < g.n(0); ++i) bed(i, j) = eps_bed;
  const BubbleSample s = observe_2d(tracker, 0.1, g, bed, zero);
  EXPECT_FALSE(s.nose_height || s.rise_velocity || s.nose_gas_velocity || s.throughflow_ratio || s.area || s.attached);
  ASSERT_TRUE(s.bed_height.has_value());
  EXPECT_NEAR(*s.bed_height, 27 * g.h[1], 1e-12);
  EXPECT_EQ(bubble_csv_row(s), "0.1,,,,,,,,0.54,0,,");
  EXPECT_EQ(bed_surface_row(cell_view(g, bed, "eps")), 26);
  EXPECT_NEAR(*bed_surface_height(cell_view(g, bed, "eps")), 27 * g.h[1], 1e-12);
  // All gas (no bed at all) and all bed (no freeboard).
  const BubbleSample empty = observe_2d(tracker, 0.2, g, cell_field(g, 1.0), zero);
  EXPECT_FALSE(empty.nose_height || empty.bed_height || empty.attached);
  const BubbleSample packed = observe_2d(tracker, 0.3, g, cell_field(g, eps_bed), zero);
  EXPECT_FALSE(packed.nose_height || packed.attached);
  EXPECT_FALSE(tracker.detachment_time() || tracker.eruption_time());
}

TEST(BubbleTracker, NoseExactForLinearProfile) {
  // eps = a - b y in every column: the crossing of the threshold is y* = (a - thr)/b, also off the cell centres
  // (jet line between two columns).
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {30, 50});
  const double a = 1.0, b = 0.57;
  Field<2> eps(cell_field(g));
  for (int j = 0; j < g.n(1); ++j)
    for (int i = 0; i < g.n(0); ++i) eps(i, j) = a - b * g.centre(1, j);
  for (double jet_x : {0.3, 0.31, 0.017}) {
    BubbleConfig c;
    c.cells = {g.n(0), g.n(1), 0};
    c.jet_x = jet_x;
    BubbleTracker tracker(c);
    const Field<2> zero(cell_field(g, 0.0));
    const BubbleSample s = observe_2d(tracker, 0.0, g, eps, zero);
    ASSERT_TRUE(s.nose_height.has_value());
    EXPECT_NEAR(*s.nose_height, (a - thr) / b, 1e-12);
    EXPECT_TRUE(*s.attached);
  }
}

TEST(BubbleTracker, EruptionAtTheBedSurfaceThenNextBubble) {
  // Bed up to 0.5 m, freeboard above; the disc erupts at the first sample where its void cells join the freeboard.
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {60, 100});
  BubbleTracker tracker(fine_config(g, 0.305));
  const Field<2> zero(cell_field(g, 0.0));
  const double bed_top = 0.5, dt = 0.01, u_b = 1.0;
  int erupted_at = -1;
  for (int n = 0; n < 40 && erupted_at < 0; ++n) {
    const RampDisc d{0.305, 0.2 + u_b * n * dt, 0.04, 0.06};
    const BubbleSample s = observe_2d(tracker, n * dt, g, disc_field(g, d, bed_top), zero);
    // The void joins the freeboard once the centre of the top bed row (every cell of it borders the freeboard)
    // lies inside the eps = thr contour.
    const bool joined = d.nose() > bed_top - 0.5 * g.h[1];
    EXPECT_EQ(s.erupted, joined) << "sample " << n;
    if (s.erupted) {
      erupted_at = n;
      EXPECT_FALSE(s.nose_height.has_value());
    } else {
      ASSERT_TRUE(s.nose_height.has_value()) << n;
      EXPECT_NEAR(*s.bed_height, bed_top, 1e-12);
    }
  }
  ASSERT_GT(erupted_at, 0);
  EXPECT_DOUBLE_EQ(*tracker.eruption_time(), erupted_at * dt);
  // A new void at the jet afterwards is a new bubble.
  const RampDisc next{0.305, 0.03, 0.04, 0.06};
  const BubbleSample s = observe_2d(tracker, 1.0, g, disc_field(g, next, bed_top), zero);
  ASSERT_TRUE(s.nose_height.has_value());
  EXPECT_EQ(s.bubble_id, 1);
  EXPECT_TRUE(*s.attached);
}

TEST(BubbleTracker, AreaAndEquivalentDiameter) {
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {60, 100});
  BubbleTracker tracker(fine_config(g, 0.3));
  Field<2> eps(cell_field(g, eps_bed));
  for (int j = 40; j < 46; ++j)
    for (int i = 25; i < 35; ++i) eps(i, j) = 0.95;
  const Field<2> zero(cell_field(g, 0.0));
  const BubbleSample s = observe_2d(tracker, 0.0, g, eps, zero);
  ASSERT_TRUE(s.area.has_value());
  const double area = 60 * g.h[0] * g.h[1];
  EXPECT_NEAR(*s.area, area, 1e-15);
  EXPECT_NEAR(*s.equivalent_diameter, std::sqrt(4.0 * area / std::numbers::pi), 1e-15);
  EXPECT_NEAR(*s.centroid_y, 0.5 * (g.centre(1, 40) + g.centre(1, 45)), 1e-12);
  // Sharp top: eps 0.95 over 0.43, crossing (0.95 - 0.8)/(0.95 - 0.43) of the way to the next centre.
  EXPECT_NEAR(*s.nose_height, g.centre(1, 45) + (0.95 - thr) / (0.95 - eps_bed) * g.h[1], 1e-12);
}

TEST(BubbleTracker, CentroidRisesAtHalfTheNoseSpeedOfAGrowingJetBubble) {
  // A sharp void (eps = 1) on the jet, 6 cells wide, from the bottom face up to a top that rises two cells per
  // sample: its centroid is half its height and rises h per sample, its nose (the threshold crossing a constant
  // fraction of a cell above the top centre) 2 h per sample. Both slopes are exact up to round-off.
  const Grid<2> g = Grid<2>::uniform({0.6, 1.0}, {60, 100});  // 1 cm cells
  BubbleTracker tracker(fine_config(g, 0.3));
  const Field<2> zero(cell_field(g, 0.0));
  const double dt = 0.01;
  BubbleSample s;
  for (int n = 0; n < 4; ++n) {
    Field<2> f(cell_field(g, eps_bed));
    for (int j = 0; j < 10 + 2 * n; ++j)
      for (int i = 27; i < 33; ++i) f(i, j) = 1.0;
    s = observe_2d(tracker, n * dt, g, f, zero);
  }
  ASSERT_TRUE(s.rise_velocity && s.centroid_rise_velocity && s.centroid_y);
  const double u_c = g.h[1] / dt;
  std::printf("growing jet bubble: centroid exact %g computed %.15g; nose exact %g computed %.15g\n", u_c,
              *s.centroid_rise_velocity, 2.0 * u_c, *s.rise_velocity);
  EXPECT_NEAR(*s.centroid_rise_velocity, u_c, 1e-9 * u_c);
  EXPECT_NEAR(*s.rise_velocity, 2.0 * u_c, 1e-9 * u_c);
  EXPECT_NEAR(*s.centroid_y, 0.5 * 16 * g.h[1], 1e-12);
  EXPECT_TRUE(*s.attached);
  // The optional trailing columns: every earlier column is unchanged.
  const std::string base = bubble_csv_row(s), with = bubble_csv_row(s, true);
  EXPECT_EQ(with.rfind(base + ",", 0), 0u);
  EXPECT_EQ(bubble_csv_header(2, true), bubble_csv_header(2) + ",centroid_y_m,centroid_rise_velocity_m_s");
  EXPECT_EQ(bubble_csv_header(3, true), bubble_csv_header(3) + ",centroid_y_m,centroid_rise_velocity_m_s");
  EXPECT_EQ(bubble_csv_values(s, true).size(), bubble_csv_values(s).size() + 2);
  EXPECT_DOUBLE_EQ(*bubble_csv_values(s, true).back(), *s.centroid_rise_velocity);
  // A restored state without centroid history (an older checkpoint) gives the velocity again after two samples.
  BubbleTracker::State st = tracker.state();
  st.centroid_h.clear();
  BubbleTracker restored(fine_config(g, 0.3));
  restored.restore(st);
  Field<2> f(cell_field(g, eps_bed));
  for (int j = 0; j < 18; ++j)
    for (int i = 27; i < 33; ++i) f(i, j) = 1.0;
  EXPECT_FALSE(observe_2d(restored, 4 * dt, g, f, zero).centroid_rise_velocity);
  for (int j = 0; j < 20; ++j)
    for (int i = 27; i < 33; ++i) f(i, j) = 1.0;
  const BubbleSample r = observe_2d(restored, 5 * dt, g, f, zero);
  ASSERT_TRUE(r.centroid_rise_velocity);
  EXPECT_NEAR(*r.centroid_rise_velocity, u_c, 1e-9 * u_c);
}

TEST(BubbleTracker, CsvColumns) {
  const std::string h = bubble_csv_header();
  EXPECT_EQ(h.rfind("time_s,nose_height_m,rise_velocity_m_s,nose_gas_velocity_m_s,throughflow_ratio,bubble_area_m2,"
                    "attached",
                    0),
            0u);
  BubbleSample s;
  s.time = 0.25;
  s.nose_height = 0.125;
  s.attached = true;
  const std::string row = bubble_csv_row(s);
  EXPECT_EQ(std::count(row.begin(), row.end(), ','), std::count(h.begin(), h.end(), ','));
  EXPECT_EQ(row.rfind("0.25,0.125,,,,,1,", 0), 0u);
}

TEST(RiseVelocity2d, ScalesWithRootOfDiameter) {
  EXPECT_DOUBLE_EQ(bubble_rise_velocity_2d(0.1, 9.81), rise_constant_2d * std::sqrt(9.81 * 0.1));
  EXPECT_NEAR(bubble_rise_velocity_2d(0.4, 9.81) / bubble_rise_velocity_2d(0.1, 9.81), 2.0, 1e-14);
}

}  // namespace
}  // namespace fluidbed
