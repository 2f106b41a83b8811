// Bubble tracker in 3D on synthetic voxel fields whose volume, connectivity, nose, speed and attachment are known
// in closed form or by brute force. The tolerances are derived in each test's first comment.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "analysis/bed_surface.hpp"
#include "analysis/bubble_tracker.hpp"
#include "analysis/rise_velocity.hpp"
#include "core/error.hpp"
#include "run/analysis_csv.hpp"

namespace fluidbed {
namespace {

constexpr double eps_bed = 0.43;
constexpr double thr = 0.8;

// A voxel field with its own storage; view() hands it to the tracker.
struct Voxels {
  CellGeometry<3> g;
  std::vector<double> v;
  Voxels(const Index<3>& n, const std::array<double, 3>& h, double value) : g{n, h, {0.0, 0.0, 0.0}} {
    v.assign(g.cells(), value);
  }
  template <class F>
  void set(F&& eps_at) {
    for (std::size_t k = 0; k < v.size(); ++k) {
      const Index<3> c = g.cell_of(k);
      v[k] = eps_at(g.centre(0, c[0]), g.centre(1, c[1]), g.centre(2, c[2]));
    }
  }
  CellView<3> view() const { return {g, v.data()}; }
};

// eps = 1 inside radius r_in, falling linearly to the bed value at r_out (a smoothly bounded sphere).
struct RampSphere {
  double xc, yc, zc, r_in, r_out;
  double eps(double x, double y, double z) const {
    const double r = std::sqrt((x - xc) * (x - xc) + (y - yc) * (y - yc) + (z - zc) * (z - zc));
    const double s = std::clamp((r_out - r) / (r_out - r_in), 0.0, 1.0);
    return eps_bed + (1.0 - eps_bed) * s;
  }
  // Height of the eps = thr contour on the vertical line through the centre.
  double nose() const { return yc + r_out - (thr - eps_bed) / (1.0 - eps_bed) * (r_out - r_in); }
};

BubbleConfig config_3d(const CellGeometry<3>& g, double jet_x, double jet_z) {
  BubbleConfig c;
  c.jet_x = jet_x;
  c.jet_z = jet_z;
  c.jet_width = 0.02;
  c.cells = {0, 0, g.n[2]};
  c.min_volume = 4.0 * g.cell_measure();
  return c;
}

TEST(BubbleTracker3d, SphereVolumeWithinTheSurfaceVoxels) {
  // A sharp sphere (eps = 1 where the cell centre is inside) of radius R on anisotropic cells. A cell the sphere
  // surface does not cut is wholly inside or outside and is counted right, so |N h^3 - 4/3 pi R^3| is at most the
  // measure of the cut cells; a cut cell has its centre within the half diagonal delta of the surface, so the
  // tolerance is (cells with | |c - centre| - R | < delta) x cell volume. The centroid: sum_cells c h^3 is the
  // integral of x over the voxel set and the integral over the ball vanishes (about its centre), so their
  // difference, over the symmetric difference (inside that shell), bounds |centroid - centre| by
  // tol (R + delta) / V_voxels. The diameter (6 V / pi)^(1/3) moves by a third of the relative volume error.
  Voxels f({40, 36, 44}, {0.01, 0.0125, 0.008}, eps_bed);
  const double R = 0.1, xc = 0.2031, yc = 0.2217, zc = 0.1779;
  const auto dist = [&](double x, double y, double z) {
    return std::sqrt((x - xc) * (x - xc) + (y - yc) * (y - yc) + (z - zc) * (z - zc));
  };
  f.set([&](double x, double y, double z) { return dist(x, y, z) < R ? 1.0 : eps_bed; });
  const double delta = 0.5 * std::sqrt(0.01 * 0.01 + 0.0125 * 0.0125 + 0.008 * 0.008);
  std::size_t cut = 0, inside = 0;
  for (std::size_t k = 0; k < f.v.size(); ++k) {
    const Index<3> c = f.g.cell_of(k);
    const double r = dist(f.g.centre(0, c[0]), f.g.centre(1, c[1]), f.g.centre(2, c[2]));
    if (std::abs(r - R) < delta) ++cut;
    if (r < R) ++inside;
  }
  const double tol = static_cast<double>(cut) * f.g.cell_measure();
  BubbleTracker tracker(config_3d(f.g, xc, zc));
  const Voxels zero({40, 36, 44}, {0.01, 0.0125, 0.008}, 0.0);
  const BubbleSample s = tracker.observe<3>(0.0, f.view(), zero.view());
  ASSERT_TRUE(s.volume.has_value());
  EXPECT_FALSE(s.area.has_value());
  const double exact = 4.0 / 3.0 * std::numbers::pi * R * R * R;
  std::printf("sphere volume: exact %.6e computed %.6e error %.3e (bound %.3e, %zu cut cells)\n", exact, *s.volume,
              *s.volume - exact, tol, cut);
  EXPECT_NEAR(*s.volume, exact, tol);
  // The measure itself: every voxel of the (6-connected, convex) sphere counted once, each h_x h_y h_z.
  EXPECT_NEAR(*s.volume, static_cast<double>(inside) * 0.01 * 0.0125 * 0.008, 1e-15);
  const double d_exact = 2.0 * R;
  std::printf("sphere diameter: exact %.6f computed %.6f error %.3e (bound %.3e)\n", d_exact,
              *s.equivalent_diameter, *s.equivalent_diameter - d_exact, d_exact * tol / exact / 3.0 * 1.01);
  EXPECT_NEAR(*s.equivalent_diameter, std::cbrt(6.0 * *s.volume / std::numbers::pi), 1e-15);
  // First order in the relative volume error, 1% margin for the second-order term.
  EXPECT_NEAR(*s.equivalent_diameter, d_exact, d_exact * tol / exact / 3.0 * 1.01);
  const double c_tol = tol * (R + delta) / *s.volume;
  EXPECT_NEAR(*s.centroid_x, xc, c_tol);
  EXPECT_NEAR(*s.centroid_y, yc, c_tol);
  EXPECT_NEAR(*s.centroid_z, zc, c_tol);
  std::printf("centroid error: (%.2e, %.2e, %.2e) (bound %.2e)\n", *s.centroid_x - xc, *s.centroid_y - yc,
              *s.centroid_z - zc, c_tol);
  EXPECT_EQ(s.dimension, 3);
  // The theory value of a 3D bed: Davidson and Harrison's 0.711 sqrt(g d_e).
  ASSERT_TRUE(s.theory_rise_velocity.has_value());
  EXPECT_DOUBLE_EQ(*s.theory_rise_velocity, 0.711 * std::sqrt(9.81 * *s.equivalent_diameter));
}

// Ball of radius R (in cells) about an integer cell, as a set of storage indices.
std::vector<std::size_t> index_ball(const CellGeometry<3>& g, const Index<3>& centre, int R) {
  std::vector<std::size_t> out;
  for (int k = -R; k <= R; ++k)
    for (int j = -R; j <= R; ++j)
      for (int i = -R; i <= R; ++i)
        if (i * i + j * j + k * k <= R * R) out.push_back(g.index({centre[0] + i, centre[1] + j, centre[2] + k}));
  return out;
}

TEST(BubbleTracker3d, SixConnectivity) {
  // Two voxel balls of radius 4 cells about (10,10,10) and (15,15,15): by brute force below they share no cell
  // and no face, but touch at corners, so they are two bubbles under face (6-) connectivity (they would be one
  // under 26-connectivity). Moved to (19,10,10) they share faces: one bubble of both volumes.
  const CellGeometry<3> g{{30, 30, 30}, {0.01, 0.01, 0.01}, {0.0, 0.0, 0.0}};
  const auto mask_of = [&](const std::vector<std::size_t>& a, const std::vector<std::size_t>& b) {
    std::vector<std::uint8_t> m(g.cells(), 0);
    for (std::size_t k : a) m[k] = 1;
    for (std::size_t k : b) m[k] = 1;
    return m;
  };
  const auto a = index_ball(g, {10, 10, 10}, 4);
  const auto b = index_ball(g, {15, 15, 15}, 4);
  std::vector<std::uint8_t> in_a(g.cells(), 0), in_b(g.cells(), 0);
  for (std::size_t k : a) in_a[k] = 1;
  for (std::size_t k : b) in_b[k] = 1;
  int shared = 0, faces = 0, corners = 0;
  for (std::size_t k : a) {
    shared += in_b[k];
    const Index<3> c = g.cell_of(k);
    for (int ax = 0; ax < 3; ++ax)
      for (int s : {-1, 1}) {
        Index<3> d = c;
        d[ax] += s;
        faces += in_b[g.index(d)];
      }
    corners += in_b[g.index({c[0] + 1, c[1] + 1, c[2] + 1})];
  }
  ASSERT_EQ(shared, 0);
  ASSERT_EQ(faces, 0);
  ASSERT_GT(corners, 0);
  std::vector<int> label;
  EXPECT_EQ(label_regions<3>(g.n, mask_of(a, b), label), 2);
  EXPECT_NE(label[a.front()], label[b.front()]);

  const auto b_face = index_ball(g, {19, 10, 10}, 4);
  EXPECT_EQ(label_regions<3>(g.n, mask_of(a, b_face), label), 1);

  // The tracker: two separate bubbles, it takes one ball (the first met, same size); joined, both balls' volume.
  const auto field_of = [&](const std::vector<std::uint8_t>& m) {
    std::vector<double> v(g.cells(), eps_bed);
    for (std::size_t k = 0; k < v.size(); ++k)
      if (m[k]) v[k] = 1.0;
    return v;
  };
  const std::vector<double> zero(g.cells(), 0.0);
  const double cell = g.cell_measure();
  {
    BubbleTracker tracker(config_3d(g, 0.1, 0.1));
    const auto v = field_of(mask_of(a, b));
    const BubbleSample s = tracker.observe<3>(0.0, {g, v.data()}, {g, zero.data()});
    ASSERT_TRUE(s.volume.has_value());
    EXPECT_NEAR(*s.volume, static_cast<double>(a.size()) * cell, 1e-15);
  }
  {
    BubbleTracker tracker(config_3d(g, 0.1, 0.1));
    const auto v = field_of(mask_of(a, b_face));
    const BubbleSample s = tracker.observe<3>(0.0, {g, v.data()}, {g, zero.data()});
    ASSERT_TRUE(s.volume.has_value());
    EXPECT_NEAR(*s.volume, static_cast<double>(a.size() + b_face.size()) * cell, 1e-15);
  }
}

TEST(BubbleTracker3d, RiseVelocityOfMovingSphere) {
  // 0.3 x 0.6 x 0.3 m at 5 mm; the nose line through a column of cell centres (x and z weights zero) and the
  // ramp 20 mm = 4 cells wide: the two cell centres bracketing the threshold lie inside the ramp, where eps is
  // linear along the line, so the nose is exact and so is the least-squares speed: round-off only.
  Voxels f({60, 120, 60}, {0.005, 0.005, 0.005}, eps_bed);
  const Voxels zero({60, 120, 60}, {0.005, 0.005, 0.005}, 0.0);
  const double xl = f.g.centre(0, 30), zl = f.g.centre(2, 27);
  BubbleTracker tracker(config_3d(f.g, xl, zl));
  const double u_b = 0.7, dt = 0.0137;
  for (int n = 0; n < 15; ++n) {
    const double t = n * dt;
    const RampSphere d{xl, 0.15 + u_b * t, zl, 0.04, 0.06};
    f.set([&](double x, double y, double z) { return d.eps(x, y, z); });
    const BubbleSample s = tracker.observe<3>(t, f.view(), zero.view());
    ASSERT_TRUE(s.nose_height.has_value());
    EXPECT_NEAR(*s.nose_height, d.nose(), 1e-12);
    EXPECT_DOUBLE_EQ(*s.nose_x, xl);
    EXPECT_DOUBLE_EQ(*s.nose_z, zl);
    EXPECT_EQ(s.bubble_id, 0);
    EXPECT_FALSE(*s.attached);
    if (n == 0) {
      EXPECT_FALSE(s.rise_velocity.has_value());
      continue;
    }
    ASSERT_TRUE(s.rise_velocity.has_value());
    if (n == 14) std::printf("rise velocity: exact %.15f computed %.15f error %.2e\n", u_b, *s.rise_velocity,
                             *s.rise_velocity - u_b);
    EXPECT_NEAR(*s.rise_velocity, u_b, 1e-9);
  }
}

TEST(BubbleTracker3d, NoseAndGasVelocityExactForLinearFields) {
  // eps = a - b y + c x + e z and vg linear in x, y, z: the bilinear (x, z) interpolation of eps on the nose line
  // and the trilinear interpolation of vg are exact for linear fields, so the nose is y* = (a + c x + e z - thr)/b
  // off the cell centres in x and z, and the gas velocity half a cell above it is exact: round-off only.
  Voxels eps({30, 50, 20}, {0.02, 0.02, 0.02}, 0.0), vg({30, 50, 20}, {0.02, 0.02, 0.02}, 0.0);
  const double a = 1.0, b = 0.57, c = 0.05, e = -0.08;
  eps.set([&](double x, double y, double z) { return a - b * y + c * x + e * z; });
  const auto v_exact = [](double x, double y, double z) { return 2.5 + 0.7 * x + 3.1 * y - 1.3 * z; };
  vg.set(v_exact);
  for (const auto& [jx, jz] : {std::array<double, 2>{0.3, 0.2}, {0.311, 0.127}, {0.0437, 0.3}}) {
    BubbleTracker tracker(config_3d(eps.g, jx, jz));
    const BubbleSample s = tracker.observe<3>(0.0, eps.view(), vg.view());
    ASSERT_TRUE(s.nose_height.has_value());
    const double nose = (a + c * jx + e * jz - thr) / b;
    EXPECT_NEAR(*s.nose_height, nose, 1e-12) << jx << " " << jz;
    EXPECT_NEAR(*s.nose_gas_velocity, v_exact(jx, nose + 0.01, jz), 1e-12);
    EXPECT_TRUE(*s.attached);
  }
}

TEST(BubbleTracker3d, DetachmentFromADiscJetAtTheExactSample) {
  // A sharp sphere starting over a disc jet of diameter 4 cm and rising: it is attached while a bottom-layer cell
  // whose face overlaps the disc (brute force below: the face's point nearest the disc centre is inside it) has
  // its centre inside the sphere; the detachment sample follows.
  Voxels f({30, 50, 30}, {0.01, 0.01, 0.01}, eps_bed);
  const Voxels zero({30, 50, 30}, {0.01, 0.01, 0.01}, 0.0);
  const double jx = 0.153, jz = 0.147, jet_d = 0.04;
  BubbleConfig cfg = config_3d(f.g, jx, jz);
  cfg.jet_shape = InletShape::Disc;
  cfg.jet_width = jet_d;
  BubbleTracker tracker(cfg);
  const double radius = 0.05, u_b = 0.8, dt = 0.004;
  int expected = -1, detected = -1;
  for (int n = 0; n < 40; ++n) {
    const double yd = 0.03 + u_b * n * dt;
    const auto inside = [&](double x, double y, double z) {
      return std::sqrt((x - jx) * (x - jx) + (y - yd) * (y - yd) + (z - jz) * (z - jz)) < radius;
    };
    f.set([&](double x, double y, double z) { return inside(x, y, z) ? 1.0 : eps_bed; });
    bool touches = false;
    for (int k = 0; k < f.g.n[2]; ++k)
      for (int i = 0; i < f.g.n[0]; ++i) {
        const double px = std::clamp(jx, f.g.face(0, i), f.g.face(0, i + 1));
        const double pz = std::clamp(jz, f.g.face(2, k), f.g.face(2, k + 1));
        const bool over_jet = std::hypot(px - jx, pz - jz) < 0.5 * jet_d;
        if (over_jet && inside(f.g.centre(0, i), f.g.centre(1, 0), f.g.centre(2, k))) touches = true;
      }
    if (!touches && expected < 0) expected = n;
    const BubbleSample s = tracker.observe<3>(n * dt, f.view(), zero.view());
    ASSERT_TRUE(s.attached.has_value()) << n;
    EXPECT_EQ(*s.attached, touches) << "sample " << n;
    if (s.detached && detected < 0) detected = n;
  }
  ASSERT_GT(expected, 0);
  EXPECT_EQ(detected, expected);
  EXPECT_DOUBLE_EQ(*tracker.detachment_time(), expected * dt);
}

TEST(BubbleTracker3d, EruptionAtTheBedSurfaceThenNextBubble) {
  // Bed up to 0.4 m, freeboard above: the sphere's void joins the freeboard once the centre of the top bed slab
  // (every cell of it borders the freeboard) lies inside the eps = thr contour on the nose line, as in 2D.
  Voxels f({30, 60, 30}, {0.01, 0.01, 0.01}, eps_bed);
  const Voxels zero({30, 60, 30}, {0.01, 0.01, 0.01}, 0.0);
  const double xl = f.g.centre(0, 15), zl = f.g.centre(2, 14), bed_top = 0.4, dt = 0.01, u_b = 1.0;
  BubbleTracker tracker(config_3d(f.g, xl, zl));
  int erupted_at = -1;
  for (int n = 0; n < 40 && erupted_at < 0; ++n) {
    const RampSphere d{xl, 0.15 + u_b * n * dt, zl, 0.04, 0.06};
    f.set([&](double x, double y, double z) { return y < bed_top ? d.eps(x, y, z) : 1.0; });
    const BubbleSample s = tracker.observe<3>(n * dt, f.view(), zero.view());
    const bool joined = d.nose() > bed_top - 0.5 * f.g.h[1];
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
  const RampSphere next{xl, 0.03, zl, 0.04, 0.06};
  f.set([&](double x, double y, double z) { return y < bed_top ? next.eps(x, y, z) : 1.0; });
  const BubbleSample s = tracker.observe<3>(1.0, f.view(), zero.view());
  ASSERT_TRUE(s.nose_height.has_value());
  EXPECT_EQ(s.bubble_id, 1);
  EXPECT_TRUE(*s.attached);
}

TEST(BubbleTracker3d, RectangleFootprintAndItsCorners) {
  // A Rectangle jet 2 cm x 4 cm centred on a cell corner covers exactly 2 x 4 bottom cells; a one-cell void in a
  // bottom cell is attached only inside that footprint (corner cells included, the next ones out not).
  const CellGeometry<3> g{{20, 10, 20}, {0.01, 0.01, 0.01}, {0.0, 0.0, 0.0}};
  BubbleConfig cfg = config_3d(g, 0.1, 0.1);
  cfg.jet_shape = InletShape::Rectangle;
  cfg.jet_width = 0.02;
  cfg.jet_depth = 0.04;
  cfg.min_volume = 0.5 * g.cell_measure();
  const std::vector<double> zero(g.cells(), 0.0);
  for (int k = 6; k < 14; ++k)
    for (int i = 7; i < 13; ++i) {
      BubbleTracker tracker(cfg);
      std::vector<double> v(g.cells(), eps_bed);
      v[g.index({i, 0, k})] = 1.0;
      const BubbleSample s = tracker.observe<3>(0.0, {g, v.data()}, {g, zero.data()});
      ASSERT_TRUE(s.attached.has_value());
      const bool inside = i >= 9 && i < 11 && k >= 8 && k < 12;
      EXPECT_EQ(*s.attached, inside) << i << " " << k;
    }
}

TEST(BubbleTracker3d, OneCellDeepSlabIsThe2dTracker) {
  // A 3D field one cell deep holding a 2D field: the nose line at mid-depth has zero z weight, so nose, rise
  // velocity, attachment, detachment and bed height are bit for bit those of the 2D tracker; the measure is the
  // area times the depth.
  const Grid<2> g2 = Grid<2>::uniform({0.6, 1.0}, {60, 100});
  const CellGeometry<3> g3{{60, 100, 1}, {g2.h[0], g2.h[1], 0.004}, {0.0, 0.0, 0.0}};
  BubbleConfig c2;
  c2.cells = {g2.n(0), g2.n(1), 0};
  c2.jet_x = 0.3;
  c2.min_area = 4.0 * g2.h[0] * g2.h[1];
  BubbleConfig c3 = c2;
  c3.min_volume = c2.min_area * 0.004;
  BubbleTracker t2(c2), t3(c3);
  const Field<2> zero(cell_field(g2, 0.0));
  for (int n = 0; n < 30; ++n) {
    Field<2> eps(cell_field(g2, eps_bed));
    const double yd = 0.03 + 0.9 * n * 0.01;
    for (int j = 0; j < g2.n(1); ++j)
      for (int i = 0; i < g2.n(0); ++i) {
        const double r = std::hypot(g2.centre(0, i) - 0.3, g2.centre(1, j) - yd);
        eps(i, j) = j > 80 ? 1.0 : eps_bed + (1.0 - eps_bed) * std::clamp((0.06 - r) / 0.02, 0.0, 1.0);
      }
    const BubbleSample s2 = t2.observe<2>(n * 0.01, cell_view(g2, eps, "eps"), cell_view(g2, zero, "vg"));
    const BubbleSample s3 = t3.observe<3>(n * 0.01, {g3, eps.data().data()}, {g3, zero.data().data()});
    EXPECT_EQ(s2.nose_height, s3.nose_height) << n;
    EXPECT_EQ(s2.rise_velocity, s3.rise_velocity) << n;
    EXPECT_EQ(s2.attached, s3.attached) << n;
    EXPECT_EQ(s2.detached, s3.detached) << n;
    EXPECT_EQ(s2.erupted, s3.erupted) << n;
    EXPECT_EQ(s2.bed_height, s3.bed_height) << n;
    EXPECT_EQ(s2.centroid_y, s3.centroid_y) << n;
    if (s2.area) {
      EXPECT_NEAR(*s3.volume, *s2.area * 0.004, 1e-15);
    }
  }
  EXPECT_TRUE(t2.detachment_time().has_value());
  EXPECT_EQ(t2.detachment_time(), t3.detachment_time());
  EXPECT_EQ(t2.eruption_time(), t3.eruption_time());
}

TEST(BubbleTracker3d, BedSurfaceIsTheSlabMean) {
  // The surface is the highest y slab whose mean voidage over x and z is below surface_eps: a slab half bed
  // (0.43) and half gas (1.0) averages 0.715 > 0.7, so it is freeboard; one two thirds bed (0.62) is bed.
  Voxels f({10, 20, 12}, {0.02, 0.02, 0.02}, 1.0);
  f.set([](double, double y, double z) {
    if (y < 0.2) return eps_bed;
    if (y < 0.24) return z < 0.16 ? eps_bed : 1.0;   // slabs 10, 11: two thirds bed
    if (y < 0.26) return z < 0.12 ? eps_bed : 1.0;   // slab 12: half bed
    return 1.0;
  });
  EXPECT_EQ(bed_surface_row<3>(f.view()), 11);
  EXPECT_NEAR(*bed_surface_height<3>(f.view()), 0.24, 1e-15);
}

TEST(BubbleTracker3d, CsvColumns) {
  BubbleSample s;
  s.dimension = 3;
  s.time = 0.5;
  s.volume = 2e-4;
  s.nose_z = 0.125;
  const std::string h = bubble_csv_header(3);
  EXPECT_NE(h.find(",bubble_volume_m3,"), std::string::npos);
  EXPECT_EQ(h.find("area"), std::string::npos);
  const std::string row = bubble_csv_row(s);
  EXPECT_EQ(std::count(row.begin(), row.end(), ','), std::count(h.begin(), h.end(), ','));
  EXPECT_EQ(bubble_csv_values(s).size(), static_cast<std::size_t>(std::count(h.begin(), h.end(), ',') + 1));
  EXPECT_EQ(row, "0.5,,,,,0.0002,,,,0,,,0.125,");
}

TEST(RiseVelocity3d, DavidsonHarrisonConstant) {
  // Davidson and Harrison (1963): U_b = 0.711 sqrt(g d_e) for a 3D bubble of sphere-equivalent diameter d_e.
  EXPECT_DOUBLE_EQ(rise_constant_3d, 0.711);
  EXPECT_DOUBLE_EQ(rise_constant<3>(), 0.711);
  EXPECT_DOUBLE_EQ(rise_constant<2>(), rise_constant_2d);
  EXPECT_DOUBLE_EQ(bubble_rise_velocity_3d(0.1, 9.81), 0.711 * std::sqrt(9.81 * 0.1));
  EXPECT_DOUBLE_EQ(bubble_rise_velocity(3, 0.1, 9.81), bubble_rise_velocity_3d(0.1, 9.81));
  EXPECT_DOUBLE_EQ(bubble_rise_velocity(2, 0.1, 9.81), bubble_rise_velocity_2d(0.1, 9.81));
  EXPECT_NEAR(bubble_rise_velocity_3d(0.4) / bubble_rise_velocity_3d(0.1), 2.0, 1e-14);
  EXPECT_THROW(bubble_rise_velocity(4, 0.1), Error);
}

}  // namespace
}  // namespace fluidbed
