// Inlet schedules (ScheduleKind) against their closed forms, and perforated plates against their exact open area
// and volume flux. Every expected value is computed from the formula of gas_config.hpp by hand-written arithmetic
// independent of the code's; the tolerances are a few ulps of the values (the formulas are evaluated directly,
// only their rounding differs) or, for the sums of face overlaps, n_faces ulps of the total.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/error.hpp"
#include "core/grid.hpp"
#include "core/grid.hpp"
#include "fluid/gas_boundary.hpp"

namespace fluidbed {
namespace {

constexpr double kPi = std::numbers::pi;

void report(const char* what, double exact, double computed) {
  std::printf("%-44s exact %.17g computed %.17g error %.3g\n", what, exact, computed, computed - exact);
}

TEST(InletSchedule, RampTableSineSquareClosedForms) {
  InletSchedule ramp;
  ramp.kind = ScheduleKind::Ramp;
  ramp.ramp_from = 1.0;
  ramp.ramp_start = 0.2;
  ramp.ramp_time = 0.4;
  EXPECT_EQ(schedule_velocity(ramp, 3.0, 0.0), 1.0);
  EXPECT_EQ(schedule_velocity(ramp, 3.0, 0.2), 1.0);
  EXPECT_NEAR(schedule_velocity(ramp, 3.0, 0.3), 1.5, 4e-16);  // 1 + 2 (0.1 / 0.4)
  EXPECT_EQ(schedule_velocity(ramp, 3.0, 0.6), 3.0);
  EXPECT_EQ(schedule_velocity(ramp, 3.0, 9.0), 3.0);

  InletSchedule table;
  table.kind = ScheduleKind::Table;
  table.times = {0.0, 0.1, 0.3};
  table.velocities = {2.0, 4.0, 1.0};
  EXPECT_EQ(schedule_velocity(table, 99.0, -1.0), 2.0);  // held before the first point; U0 unused
  EXPECT_EQ(schedule_velocity(table, 99.0, 0.1), 4.0);
  EXPECT_NEAR(schedule_velocity(table, 99.0, 0.05), 3.0, 4e-16);
  EXPECT_NEAR(schedule_velocity(table, 99.0, 0.2), 2.5, 9e-16);
  EXPECT_EQ(schedule_velocity(table, 99.0, 5.0), 1.0);

  InletSchedule sine;
  sine.kind = ScheduleKind::Sine;
  sine.amplitude = 0.5;
  sine.frequency = 4.0;
  sine.phase = 0.3;
  for (double t : {0.0, 0.01, 0.0625, 0.2, 1.37}) {
    const double exact = 2.0 + 0.5 * std::sin(2.0 * kPi * 4.0 * t + 0.3);
    EXPECT_NEAR(schedule_velocity(sine, 2.0, t), exact, 1e-15) << "t = " << t;
  }

  // On for the first 30% of each 0.1 s period, shifted a quarter period later by phase = -pi/2.
  InletSchedule square;
  square.kind = ScheduleKind::Square;
  square.amplitude = 5.0;
  square.frequency = 10.0;
  square.duty = 0.3;
  square.phase = -0.5 * kPi;
  for (int k = 0; k < 400; ++k) {
    const double t = 0.0013 + k * 0.0025;
    double pos = std::fmod(t - 0.025, 0.1);
    if (pos < 0.0) pos += 0.1;
    // Away from the switching instants the state is unambiguous.
    if (std::abs(pos) < 1e-9 || std::abs(pos - 0.03) < 1e-9) continue;
    EXPECT_EQ(schedule_velocity(square, 1.0, t), pos < 0.03 ? 6.0 : 1.0) << "t = " << t;
  }
}

TEST(InletSchedule, OncePerStepValuesMatchTheFaces) {
  // The region velocities of inlet_velocities are what each face carries: a face fully inside a jet has the jet's
  // scheduled velocity, a face outside every jet the background's.
  GasBoundaryConfig bc;
  bc.inlet_velocity = 1.5;
  bc.schedule.kind = ScheduleKind::Sine;
  bc.schedule.amplitude = 0.5;
  bc.schedule.frequency = 2.0;
  InletJet jet{0.05, 0.02, 10.0, 0.0, 1.0};
  jet.schedule.kind = ScheduleKind::Ramp;
  jet.schedule.ramp_time = 0.5;
  bc.jets = {jet};
  const Grid<2> g = Grid<2>::uniform({0.1, 0.1}, {10, 10});
  const double t = 0.2;
  const InletVelocities v = inlet_velocities(bc, t);
  std::vector<double> u;
  inlet_superficial_profile(bc, g, t, u);
  report("background at t = 0.2 s", 1.5 + 0.5 * std::sin(2.0 * kPi * 2.0 * t), v.background);
  report("ramped jet at t = 0.2 s", 10.0 * 0.2 / 0.5, v.jet[0]);
  EXPECT_NEAR(v.background, 1.5 + 0.5 * std::sin(2.0 * kPi * 2.0 * t), 1e-15);
  EXPECT_NEAR(v.jet[0], 4.0, 1e-15);
  EXPECT_EQ(u[0], v.background);
  EXPECT_NEAR(u[4], v.jet[0], 1e-14);
  EXPECT_NEAR(u[5], v.jet[0], 1e-14);
  EXPECT_DOUBLE_EQ(inlet_peak_velocity(bc), 10.0);
}

TEST(PerforatedPlate, SlotsIn2DHaveTheExactOpenWidthAndFlux) {
  PerforatedPlate plate;
  plate.n_x = 7;
  plate.hole = 0.0013;  // narrower than a cell: the overlap still carries each slot's flux exactly
  plate.pitch = 0.011;
  plate.x_centre = 0.05;
  plate.velocity = 12.0;
  GasBoundaryConfig bc;
  bc.inlet_velocity = 0.4;
  bc.jets = perforated_plate_holes(plate, 2);
  ASSERT_EQ(bc.jets.size(), 7u);
  EXPECT_NEAR(bc.jets[3].x_centre, 0.05, 1e-17);
  EXPECT_NEAR(bc.jets[1].x_centre - bc.jets[0].x_centre, 0.011, 1e-17);
  const Grid<2> g = Grid<2>::uniform({0.1, 0.1}, {20, 10});
  std::vector<double> u;
  inlet_superficial_profile(bc, g, 0.5, u);
  double flux = 0.0;
  for (double x : u) flux += x * g.h[0];
  const double open = 7 * 0.0013;
  const double exact = 12.0 * open + 0.4 * (0.1 - open);
  report("2D plate volume flux per depth [m^2/s]", exact, flux);
  EXPECT_NEAR(flux, exact, 20 * 4e-16 * exact);
}

double disc_area_sum(const std::vector<InletJet>& holes, const Grid<3>& g) {
  double a = 0.0;
  for (const InletJet& h : holes)
    for (int k = 0; k < g.n(2); ++k)
      for (int i = 0; i < g.n(0); ++i)
        a += jet_overlap_area(h, i * g.h[0], (i + 1) * g.h[0], k * g.h[2], (k + 1) * g.h[2]);
  return a;
}

TEST(PerforatedPlate, DiscsOnSquareAndTriangularPitchIn3D) {
  const Grid<3> g = Grid<3>::uniform({0.06, 0.1, 0.06}, {12, 10, 12});
  for (const HolePitch layout : {HolePitch::Square, HolePitch::Triangular}) {
    PerforatedPlate plate;
    plate.n_x = 5;
    plate.n_z = 4;
    plate.hole = 0.003;
    plate.pitch = 0.009;
    plate.layout = layout;
    plate.x_centre = 0.03;
    plate.z_centre = 0.03;
    plate.velocity = 8.0;
    const std::vector<InletJet> holes = perforated_plate_holes(plate, 3);
    ASSERT_EQ(holes.size(), 20u);
    // Every hole's nearest neighbour is one pitch away (square and equilateral triangles alike).
    double nearest = 1e9;
    double cx = 0.0, cz = 0.0;
    for (std::size_t a = 0; a < holes.size(); ++a) {
      cx += holes[a].x_centre / 20.0;
      cz += holes[a].z_centre / 20.0;
      for (std::size_t b = a + 1; b < holes.size(); ++b)
        nearest = std::min(nearest, std::hypot(holes[a].x_centre - holes[b].x_centre, holes[a].z_centre - holes[b].z_centre));
    }
    EXPECT_NEAR(nearest, 0.009, 1e-15);
    // The block is centred: triangular rows alternate their half-pitch shift, so the centroid sits a quarter pitch
    // off only for an odd row count; with 4 rows it is centred.
    EXPECT_NEAR(cx, 0.03, 1e-15);
    EXPECT_NEAR(cz, 0.03, 1e-15);
    const double open_exact = 20 * kPi * 0.25 * 0.003 * 0.003;
    const double open = disc_area_sum(holes, g);
    report(layout == HolePitch::Square ? "square plate open area [m^2]" : "triangular plate open area [m^2]",
           open_exact, open);
    EXPECT_NEAR(open, open_exact, 1e-15 * open_exact * 100);
    GasBoundaryConfig bc;
    bc.inlet_velocity = 0.2;
    bc.jets = holes;
    std::vector<double> u;
    inlet_superficial_profile(bc, g, 0.1, u);
    double flux = 0.0;
    for (double x : u) flux += x * g.h[0] * g.h[2];
    const double exact = 8.0 * open_exact + 0.2 * (0.06 * 0.06 - open_exact);
    report("3D plate volume flux [m^3/s]", exact, flux);
    EXPECT_NEAR(flux, exact, 144 * 4e-16 * exact);
    EXPECT_NEAR(inlet_mean_velocity(bc, g, 0.1), exact / (0.06 * 0.06), 1e-13);
  }
}

TEST(InletSchedule, BadSchedulesAreRejected) {
  GasConfig c;
  c.boundary.schedule.kind = ScheduleKind::Sine;
  EXPECT_THROW(validate(c), Error);  // frequency 0
  c.boundary.schedule.frequency = 1.0;
  EXPECT_NO_THROW(validate(c));
  c.boundary.jets[0].schedule.kind = ScheduleKind::Table;
  c.boundary.jets[0].schedule.times = {0.0, 0.0};
  c.boundary.jets[0].schedule.velocities = {1.0, 2.0};
  EXPECT_THROW(validate(c), Error);
  c.boundary.jets[0].schedule.times = {0.0, 0.1};
  EXPECT_NO_THROW(validate(c));
  c.boundary.jets[0].schedule.kind = ScheduleKind::Square;
  c.boundary.jets[0].schedule.frequency = 1.0;
  c.boundary.jets[0].schedule.duty = 1.0;
  EXPECT_THROW(validate(c), Error);
}

}  // namespace
}  // namespace fluidbed
