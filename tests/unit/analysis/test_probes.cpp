// Probes on synthetic fields, 2D and 3D: every field is affine in x, y (and z), f = a + b x + c y + d z. Bi- and
// trilinear interpolation between cell centres and the cross-section mean of the linear height interpolation are
// exact for affine fields, so point values, plane means and the pressure drop are compared with the closed form to
// rounding (1e-12 of the field's scale). A hydrostatic bed p = p0 - rho g y gives the pressure drop rho g (y2 - y1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "analysis/probes.hpp"

namespace fluidbed {
namespace {

constexpr double h = 0.02;
constexpr int nx = 10, ny = 20, nz = 4;

template <int Dim>
struct Affine {
  double a, b, c, d;
  double at(const std::array<double, 3>& x) const { return a + b * x[0] + c * x[1] + (Dim == 3 ? d * x[2] : 0.0); }
};

template <int Dim>
struct Fields {
  CellGeometry<Dim> g;
  std::vector<std::vector<double>> v;  // p, eps, ug..., us...
  std::vector<Affine<Dim>> law;
  Fields() {
    g.n[0] = nx;
    g.n[1] = ny;
    if constexpr (Dim == 3) g.n[2] = nz;
    g.h.fill(h);
    g.origin.fill(0.0);
    // p: hydrostatic, 1500 kg/m^3 of bed weight under g = 9.81 (rho g = 14715 Pa/m), tilted a little in x and z.
    law = {{8000.0, 10.0, -14715.0, 5.0}, {0.4, 0.1, 0.5, 0.2}};
    for (int k = 0; k < 2 * Dim; ++k) law.push_back({0.1 * k, 0.3, -0.2 * k, 0.05});
    for (const Affine<Dim>& f : law) {
      std::vector<double> values(g.cells());
      for (std::size_t q = 0; q < values.size(); ++q) {
        const Index<Dim> c = g.cell_of(q);
        std::array<double, 3> x{};
        for (int a = 0; a < Dim; ++a) x[a] = g.centre(a, c[a]);
        values[q] = f.at(x);
      }
      v.push_back(values);
    }
  }
  ProbeFields<Dim> view() const {
    ProbeFields<Dim> f;
    f.geometry = g;
    f.p = v[0].data();
    f.eps = v[1].data();
    for (int a = 0; a < Dim; ++a) {
      f.ug[a] = v[2 + a].data();
      f.us[a] = v[2 + Dim + a].data();
    }
    return f;
  }
};

template <int Dim>
void check_probes() {
  const Fields<Dim> fields;
  const double width = nx * h, depth = nz * h;
  ProbeSpec point{ProbeKind::Point, "pt", {0.073, 0.211, 0.031}, 0.0, 0.0};
  ProbeSpec plane{ProbeKind::Plane, "pl", {}, 0.137, 0.0};
  ProbeSpec drop{ProbeKind::PressureDrop, "dp", {}, 0.05, 0.31};
  const std::vector<ProbeSpec> probes{point, plane, drop};
  const std::vector<std::string> cols = probe_columns(probes, Dim, true);
  const std::vector<double> row = sample_probes<Dim>(probes, fields.view());
  ASSERT_EQ(cols.size(), row.size());
  ASSERT_EQ(cols.size(), static_cast<std::size_t>(2 * (2 + 2 * Dim) + 1));
  EXPECT_EQ(cols[0], "pt_p_Pa");
  EXPECT_EQ(cols[2], "pt_ug_x_m_s");
  EXPECT_EQ(cols.back(), "dp_dp_Pa");
  // The mean of an affine field over the cross-section at y: the field at the centre of the cross-section.
  const std::array<double, 3> mid{0.5 * width, plane.height, 0.5 * depth};
  std::size_t c = 0;
  for (const std::array<double, 3>& x : {point.position, mid}) {
    for (const Affine<Dim>& f : fields.law) {
      const double exact = f.at(x), tol = 1e-12 * (std::abs(f.a) + 1.0);
      std::printf("%dD %-12s exact %.15g computed %.15g error %.3g\n", Dim, cols[c].c_str(), exact, row[c],
                  row[c] - exact);
      EXPECT_NEAR(row[c], exact, tol) << cols[c];
      ++c;
    }
  }
  // Hydrostatic: the lower tap reads rho g (y2 - y1) more than the upper one.
  const double exact = 14715.0 * (drop.height_top - drop.height);
  std::printf("%dD dp exact %.15g computed %.15g error %.3g\n", Dim, exact, row.back(), row.back() - exact);
  EXPECT_NEAR(row.back(), exact, 1e-9 * exact);
}

TEST(Probes, AffineFields2D) { check_probes<2>(); }
TEST(Probes, AffineFields3D) { check_probes<3>(); }

TEST(Probes, NoSolidsVelocityLeavesItsColumnsOut) {
  Fields<2> fields;
  ProbeFields<2> f = fields.view();
  f.us = {};
  const std::vector<ProbeSpec> probes{{ProbeKind::Point, "a", {0.1, 0.1, 0.0}, 0.0, 0.0}};
  EXPECT_EQ(sample_probes<2>(probes, f).size(), probe_columns(probes, 2, false).size());
  EXPECT_EQ(probe_columns(probes, 2, false).size(), 4u);
}

// Bed height on a synthetic bed: packed (eps = 0.4) below y = 0.2 m, a surface zone where eps rises linearly to 1
// at y = 0.3 m, freeboard above; a bubble row (eps = 0.9) at y = 0.09 m lies inside the bed; eps varies across x
// (and z) with zero cross-section mean. The mean solids fraction 1 - eps is linear between the cell centres that
// bracket a threshold in the surface zone, so the linear interpolation is exact: for threshold s the height is
// 0.2 + 0.1 (0.6 - s) / 0.6, to rounding (1e-12 m).
template <int Dim>
void check_bed_height() {
  CellGeometry<Dim> g;
  g.n[0] = nx;
  g.n[1] = ny;
  if constexpr (Dim == 3) g.n[2] = nz;
  g.h.fill(h);
  g.origin.fill(0.0);
  const auto mean_eps = [](double y) {
    if (std::abs(y - 0.09) < 0.5 * h) return 0.9;
    return y < 0.2 ? 0.4 : y > 0.3 ? 1.0 : 0.4 + 0.6 * (y - 0.2) / 0.1;
  };
  std::vector<double> eps(g.cells());
  for (std::size_t q = 0; q < eps.size(); ++q) {
    const Index<Dim> c = g.cell_of(q);
    double across = 0.02 * (g.centre(0, c[0]) - 0.5 * g.length(0));
    if constexpr (Dim == 3) across += 0.01 * (g.centre(2, c[2]) - 0.5 * g.length(2));
    eps[q] = mean_eps(g.centre(1, c[1])) + across;
  }
  const CellView<Dim> view{g, eps.data()};
  for (const double s : {0.5, 0.3, 0.2, 0.1}) {
    const double exact = 0.2 + 0.1 * (0.6 - s) / 0.6, computed = bed_height<Dim>(view, s);
    std::printf("%dD bed height at solids fraction %.2f: exact %.15g computed %.15g error %.3g\n", Dim, s, exact,
                computed, computed - exact);
    EXPECT_NEAR(computed, exact, 1e-12) << s;
  }
  // Denser than any row: no bed; a column full to the top: its top.
  EXPECT_EQ(bed_height<Dim>(view, 0.7), 0.0);
  std::vector<double> full(g.cells(), 0.4);
  EXPECT_DOUBLE_EQ(bed_height<Dim>(CellView<Dim>{g, full.data()}, 0.3), ny * h);
  // Through sample_probes: one column, the same value.
  ProbeFields<Dim> f;
  f.geometry = g;
  f.eps = eps.data();
  f.p = eps.data();
  for (int a = 0; a < Dim; ++a) f.ug[a] = eps.data();
  ProbeSpec bed{ProbeKind::BedHeight, "bed", {}, 0.0, 0.0, 0.3};
  const std::vector<ProbeSpec> probes{bed};
  ASSERT_EQ(probe_columns(probes, Dim, false), std::vector<std::string>{"bed_bed_height_m"});
  const std::vector<double> row = sample_probes<Dim>(probes, f);
  ASSERT_EQ(row.size(), 1u);
  EXPECT_NEAR(row[0], 0.2 + 0.1 * 0.3 / 0.6, 1e-12);
}

TEST(Probes, BedHeight2D) { check_bed_height<2>(); }
TEST(Probes, BedHeight3D) { check_bed_height<3>(); }

// The percentile of Hyndman and Fan's definition 7: on 1, 2, ..., 101 the p-th percentile is 1 + p exactly; on
// five values the ranks fall between order statistics (p = 90: rank 3.6, 4 + 0.6 (5 - 4)); any order of the same
// values gives the same bits; the ends are the minimum and the maximum; no values give 0.
TEST(Probes, PercentileOfValuesInAnyOrder) {
  std::vector<double> v(101);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<double>((i * 37) % 101 + 1);  // a permutation
  for (const double p : {0.0, 5.0, 50.0, 95.0, 99.0, 100.0}) EXPECT_EQ(percentile(v, p), 1.0 + p) << p;
  const std::vector<double> five{5.0, 1.0, 4.0, 2.0, 3.0};
  EXPECT_DOUBLE_EQ(percentile(five, 90.0), 4.6);
  EXPECT_DOUBLE_EQ(percentile(five, 12.5), 1.5);
  std::vector<double> tops(2000);
  for (std::size_t i = 0; i < tops.size(); ++i) tops[i] = 0.1 + 1e-3 * std::sin(0.37 * static_cast<double>(i));
  const double forward = percentile(tops, 99.5);
  std::vector<double> backward(tops.rbegin(), tops.rend());
  EXPECT_EQ(percentile(backward, 99.5), forward);
  EXPECT_EQ(percentile(five, 0.0), 1.0);
  EXPECT_EQ(percentile(five, 100.0), 5.0);
  EXPECT_EQ(percentile(std::vector<double>{}, 50.0), 0.0);
  EXPECT_EQ(percentile(std::vector<double>{0.25}, 99.0), 0.25);
}

// A particle_top probe reads the particles' tops it is given, in its own column among the field probes.
TEST(Probes, ParticleTopReadsTheParticlesTops) {
  Fields<3> fields;
  ProbeFields<3> f = fields.view();
  std::vector<double> tops{0.30, 0.10, 0.20, 0.40, 0.05};
  f.particle_tops = tops;
  ProbeSpec top{ProbeKind::ParticleTop, "top", {}, 0.0, 0.0, 0.3, 75.0};
  ProbeSpec drop{ProbeKind::PressureDrop, "dp", {}, 0.1, 0.3};
  const std::vector<ProbeSpec> probes{drop, top};
  ASSERT_EQ(probe_columns(probes, 3, true), (std::vector<std::string>{"dp_dp_Pa", "top_top_m"}));
  const std::vector<double> row = sample_probes<3>(probes, f);
  ASSERT_EQ(row.size(), 2u);
  EXPECT_DOUBLE_EQ(row[1], 0.30);  // rank 3 of 0.05, 0.10, 0.20, 0.30, 0.40
  f.particle_tops = {};
  EXPECT_EQ(sample_probes<3>(probes, f)[1], 0.0);  // no particles
}

}  // namespace
}  // namespace fluidbed
