// The two-fluid model takes its inflow from the same inlet functions as the CFD-DEM gas (issue 14): a short run of
// a small TFM bed under a table schedule delivers, through its distributor faces, the volume the schedule asks for.
//
// Tolerance. The TFM sets the inflow of a step [t_k, t_k+1] from the schedule at the step's midpoint, as the
// CFD-DEM gas does, so the delivered volume is the midpoint sum W sum_k dt_k U((t_k + t_k+1) / 2) (adaptive dt_k).
// Against that sum, computed here from the step times, only rounding remains (1e-12 relative). Against the integral
// of U the midpoint rule is exact on every step over which U is linear; a step holding a corner of the table, where
// the slope changes by dm, errs by at most |dm| dt^2 / 8, which with the two corners bounds the second comparison.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fluid/gas_boundary.hpp"
#include "tfm/tfm_solver.hpp"

namespace fluidbed {
namespace {

TEST(InletDelivers, TfmBedUnderATableSchedule) {
  tfm::TfmConfig c;
  c.domain.width = 0.06;
  c.domain.height = 0.7;
  const double width = c.domain.width;
  c.packed_height = 0.54;
  c.boundary.jets.clear();
  c.boundary.inlet_velocity = 0.0;  // unused by the table
  c.boundary.schedule.kind = ScheduleKind::Table;
  c.boundary.schedule.times = {0.0, 0.02, 0.05};
  c.boundary.schedule.velocities = {1.0, 2.0, 1.5};
  const InletSchedule& s = c.boundary.schedule;
  tfm::TfmSolver<2> solver(c);
  const double t_end = 0.08;
  double in = 0.0, mid = 0.0, dt_max = 0.0;
  while (solver.time() < t_end - 1e-12) {
    const double dt = solver.step(t_end);
    dt_max = std::max(dt_max, dt);
    const tfm::TfmState<2>& st = solver.state();
    const int nx = solver.grid().n(0);
    double q = 0.0;
    for (int i = 0; i < nx; ++i) q += st.ug[1](i, 0) * (width / nx);
    in += q * dt;
    mid += width * dt * schedule_velocity(s, 0.0, solver.time() - 0.5 * dt);
  }
  // Integral of the table over [0, 0.08]: 0.02 * 1.5 + 0.03 * 1.75 + 0.03 * 1.5.
  const double exact = width * (0.02 * 1.5 + 0.03 * 1.75 + 0.03 * 1.5);
  // Corners at 0.02 s (slope 50 -> -50/3 m/s^2) and at 0.05 s (-50/3 -> 0).
  const double kinks = (50.0 + 50.0 / 3.0) + 50.0 / 3.0;
  const double tol = width * kinks * dt_max * dt_max / 8.0 + 1e-12 * exact;
  std::printf("TFM volume in, midpoint sum [m^2]         exact %.12e computed %.12e error %.3e (tolerance %.3e)\n",
              mid, in, in - mid, 1e-12 * mid);
  std::printf("TFM volume in, integral of U [m^2]        exact %.12e computed %.12e error %.3e (tolerance %.3e, "
              "max dt %.3g s)\n", exact, in, in - exact, tol, dt_max);
  EXPECT_NEAR(in, mid, 1e-12 * mid);
  EXPECT_NEAR(in, exact, tol);
}

}  // namespace
}  // namespace fluidbed
