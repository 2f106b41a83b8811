// Verification of the two-fluid model with periodic lateral axes (issue 30, item 1): a periodic axis has no walls,
// so a run shifted by whole cells along it is the shifted run (to the rounding of the linear solves); a column at
// minimum fluidisation stays at rest and laterally uniform; a jet bed conserves its solids and keeps the packing
// bound while solids cross the periodic plane; restarts are bit-identical; what cannot work is refused by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "closures/drag.hpp"
#include "core/error.hpp"
#include "tfm/tfm_solver.hpp"

namespace fluidbed::tfm {
namespace {

// A 2D bed, 10 x 20 cells, periodic in x, with one jet of 0.04 m (two cells) centred at x_jet.
TfmConfig periodic_jet_bed_2d(double x_jet) {
  TfmConfig c;
  c.domain.width = 0.2;
  c.domain.height = 0.4;
  c.domain.periodic = {true, false, false};
  c.packed_height = 0.2;
  c.boundary.jets = {InletJet{x_jet, 0.04, 20.0, 0.0, 1.0}};
  return c;
}

// The largest difference between run a's field and run b's read `shift` cells further along axis 0 (wrapped).
template <int Dim>
double shifted_difference(const Field<Dim>& a, const Field<Dim>& b, int shift, int n) {
  double m = 0.0;
  for_each(a.box(), [&](const Index<Dim>& c) {
    Index<Dim> s = c;
    s[0] = (c[0] + shift) % n;
    m = std::max(m, std::abs(a[c] - b[s]));
  });
  return m;
}

TEST(TfmPeriodic, JetShiftedAlongThePeriodicAxisGivesTheShiftedRun) {
  // Jet A straddles the periodic plane's neighbourhood (cells 1-2), jet B is the same jet 4 cells over (cells 5-6):
  // without walls the two runs are one run seen from two origins, so every face and cell of the step must wrap
  // exactly. What differs is only the rounding of the pressure and continuity solves (their rows are numbered
  // from a different origin), which the first steps of a bubble amplify little: 1e-9 is far below the 1e-3 a
  // wrong wrap gives within a few steps.
  const int shift = 4;
  TfmSolver<2> a(periodic_jet_bed_2d(0.04));
  TfmSolver<2> b(periodic_jet_bed_2d(0.04 + shift * 0.02));
  a.advance_to(0.03);
  b.advance_to(0.03);
  const int n = a.grid().n(0);
  const double d_eps = shifted_difference<2>(a.state().eps, b.state().eps, shift, n);
  // Face velocities normal to x: the faces of a cell's column (same index rule); along x: faces 0 .. n - 1.
  const double d_vy = shifted_difference<2>(a.state().us[1], b.state().us[1], shift, n);
  double d_vx = 0.0;
  for_each(a.state().us[0].box(), [&](const Index<2>& f) {
    if (f[0] == n) return;  // face n is face 0
    d_vx = std::max(d_vx, std::abs(a.state().us[0][f] - b.state().us[0][Index<2>{(f[0] + shift) % n, f[1]}]));
  });
  std::printf("periodic jet shifted by %d cells: %ld steps, max |v_s| %.3f m/s; largest difference eps %.2e, solids "
              "v_x %.2e m/s, v_y %.2e m/s\n",
              shift, a.state().steps, a.max_solids_speed(), d_eps, d_vx, d_vy);
  EXPECT_EQ(a.state().steps, b.state().steps);
  EXPECT_GT(a.max_solids_speed(), 1e-2);  // the jet has set the bed moving
  EXPECT_LT(d_eps, 1e-9);
  EXPECT_LT(d_vx, 1e-9);
  EXPECT_LT(d_vy, 1e-9);
}

// The 3D column of test_tfm_3d.cpp (3 x 35 x 3 cells at the Ergun U_mf), periodic in x and z: no wall anywhere
// along the horizontal, so every column is the same column.
TfmConfig periodic_column_at_rest() {
  TfmConfig c;
  c.domain.dimension = 3;
  c.domain.width = 0.06;
  c.domain.depth = 0.06;
  c.domain.height = 0.7;
  c.domain.gravity = {0.0, -9.81, 0.0};
  c.domain.periodic = {true, false, true};
  c.packed_height = 0.54;
  c.boundary.jets.clear();
  c.boundary.inlet_velocity = ergun_minimum_fluidisation_velocity(c.eps_initial, c.d_p, c.rho_s, c.rho_g, c.mu_g);
  return c;
}

TEST(TfmPeriodic, ColumnAtMinimumFluidisationStaysAtRestAndUniform) {
  TfmSolver<3> solver(periodic_column_at_rest());
  const double m0 = solver.solids_mass();
  solver.advance_to(0.5);
  const double dp = solver.pressure_drop(), w = solver.contents_weight_per_area();
  double spread = 0.0;  // largest difference of a cell from the cell of column (0, 0) at its height
  const Field<3>& eps = solver.state().eps;
  for_each(eps.box(), [&](const Index<3>& c) { spread = std::max(spread, std::abs(eps[c] - eps[Index<3>{0, c[1], 0}])); });
  std::printf("periodic column: %ld steps, max |v_s| %.3e m/s; pressure drop exact (weight/area) %.2f Pa, computed "
              "%.2f Pa; mass drift %.2e; lateral spread of eps %.2e\n",
              solver.state().steps, solver.max_solids_speed(), w, dp, solver.solids_mass() / m0 - 1.0, spread);
  EXPECT_LT(solver.max_solids_speed(), 1e-3);
  EXPECT_NEAR(dp / w, 1.0, 0.01);  // the discrete bed surface's share, as in the walled column
  EXPECT_NEAR(solver.solids_mass() / m0, 1.0, 1e-10);
  EXPECT_LT(spread, 1e-12);  // only the rounding of the solves tells the columns apart
}

// A 3D bed, 10 x 20 x 4 cells, periodic in x and z, with a square jet in the corner at the periodic planes: the
// bubble and the solids it moves cross both planes.
TfmConfig periodic_corner_jet_3d() {
  TfmConfig c;
  c.domain.dimension = 3;
  c.domain.width = 0.2;
  c.domain.depth = 0.08;
  c.domain.height = 0.4;
  c.domain.gravity = {0.0, -9.81, 0.0};
  c.domain.periodic = {true, false, true};
  c.packed_height = 0.2;
  InletJet jet{0.03, 0.04, 20.0, 0.0, 1.0};
  jet.shape = InletShape::Rectangle;
  jet.z_centre = 0.03;
  jet.depth = 0.04;
  c.boundary.jets = {jet};
  return c;
}

TEST(TfmPeriodic, CornerJetConservesSolidsAcrossThePeriodicPlanes) {
  const TfmConfig c = periodic_corner_jet_3d();
  TfmSolver<3> solver(c);
  const double m0 = solver.solids_mass();
  const double bound = c.eps_star - packing_allowance(c);
  double eps_min = 1.0, residual = 0.0, crossing = 0.0;
  while (solver.time() < 0.06 - 1e-12) {
    const double dt = solver.step(0.06);
    eps_min = std::min(eps_min, solver.min_voidage());
    // The residual is V d(eps)/dt against the fluxes: a step clipped short to land on the end time divides the
    // rounding of eps by its small dt (4e-11 here for the last step), so only full steps are held to round-off.
    if (dt >= 0.5 * solver.state().dt) residual = std::max(residual, solver.gas_volume_residual());
    // Solids speed through the periodic planes x = 0 and z = 0 (face 0 of each axis; face n is the same face).
    for (int a : {0, 2}) {
      IndexBox<3> plane = solver.grid().domain.faces(a);
      plane.hi[a] = plane.lo[a] + 1;
      for_each(plane, [&](const Index<3>& f) {
        Index<3> last = f;
        last[a] = solver.grid().domain.hi[a];
        EXPECT_EQ(solver.state().us[a][f], solver.state().us[a][last]) << "face n is not face 0 on axis " << a;
        crossing = std::max(crossing, std::abs(solver.state().us[a][f]));
      });
    }
  }
  const double drift = solver.solids_mass() / m0 - 1.0;
  std::printf("periodic corner jet: %ld steps, max |v_s| %.3f m/s, through the periodic planes %.3f m/s; mass drift "
              "%.2e; eps_min %.5f (bound %.4f); largest gas continuity residual %.2e\n",
              solver.state().steps, solver.max_solids_speed(), crossing, drift, eps_min, bound, residual);
  EXPECT_GT(crossing, 1e-2);  // the planes are crossed, not walls in disguise
  EXPECT_NEAR(drift, 0.0, 1e-10);  // conservative fluxes: face n carries out what face 0 brings in
  EXPECT_GE(eps_min, bound - 1e-12);
  EXPECT_LT(residual, 1e-12);
}

TEST(TfmPeriodic, RestartIsBitIdentical) {
  const TfmConfig c = periodic_corner_jet_3d();
  TfmSolver<3> a(c);
  a.advance_to(0.02);
  const std::vector<NamedArray> saved = a.save_state();
  a.advance_to(0.03);
  TfmSolver<3> b(c);
  b.restore_state(saved);
  b.advance_to(0.03);
  const std::vector<NamedArray> sa = a.save_state(), sb = b.save_state();
  ASSERT_EQ(sa.size(), sb.size());
  for (std::size_t k = 0; k < sa.size(); ++k) {
    EXPECT_EQ(sa[k].name, sb[k].name);
    EXPECT_TRUE(sa[k].values == sb[k].values) << "array " << sa[k].name << " differs after restart";
  }
}

std::string refusal(const TfmConfig& c) {
  try {
    TfmSolver<3> s(c);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(TfmPeriodic, RefusesWhatCannotWorkByName) {
  TfmConfig narrow = periodic_corner_jet_3d();
  narrow.domain.depth = 0.04;  // 2 cells: face 0 would join a cell to the same neighbour twice
  EXPECT_NE(refusal(narrow).find("at least 3 cells"), std::string::npos) << refusal(narrow);
  TfmConfig hypre = periodic_corner_jet_3d();
  hypre.pressure_solver = PressureBackend::HyprePfmg;
  EXPECT_NE(refusal(hypre).find("hypre-pfmg"), std::string::npos) << refusal(hypre);
  TfmConfig vertical = periodic_corner_jet_3d();
  vertical.domain.periodic = {false, true, false};
  EXPECT_NE(refusal(vertical).find("vertical"), std::string::npos) << refusal(vertical);
}

}  // namespace
}  // namespace fluidbed::tfm
