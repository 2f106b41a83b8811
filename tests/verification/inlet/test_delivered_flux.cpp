// A time-dependent inlet delivers the volume of gas its schedule asks for (issue 14, acceptance): short gas-only
// runs (eps = 1, no particles) in 2D and 3D, the bottom mass flow of every step integrated over time against
// rho_g times the integral of U(t) over the inlet regions.
//
// Tolerance. The gas solver sets the inflow of a step from the schedule at the step's midpoint (GasSolver::advance),
// so the delivered volume is the midpoint rule of the integral. The rule is exact for a function linear over each
// step: the table, the ramp and the square wave switch only at multiples of dt (dt = 1/512 s, exact in binary),
// so for them only rounding remains (1e-12 relative allowed: N steps of sums over the faces). The sine's error is
// at most T dt^2 A (2 pi f)^2 / 24 per unit of its width (the midpoint rule's bound), which is added. Through the
// top the same volume leaves, within each step's converged SIMPLE mass imbalance (at most mass_tolerance of the
// reference mass flow per step, summed as sum_k dt m_ref,k / rho_g), so that every path from the schedule to the
// outflow is checked.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "fluid/gas_boundary.hpp"
#include "fluid/gas_solver.hpp"

namespace fluidbed {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDt = 1.0 / 512.0;

// Integral of a table schedule over [a, b]: trapezoids between the breakpoints and the window's ends (exact for the
// piecewise-linear function).
double table_integral(const InletSchedule& s, double a, double b) {
  std::vector<double> t{a};
  for (double x : s.times)
    if (x > a && x < b) t.push_back(x);
  t.push_back(b);
  double sum = 0.0;
  for (std::size_t k = 0; k + 1 < t.size(); ++k)
    sum += 0.5 * (t[k + 1] - t[k]) * (schedule_velocity(s, 0.0, t[k]) + schedule_velocity(s, 0.0, t[k + 1]));
  return sum;
}

// Integral of U0 + A sin(2 pi f t + phi) over [a, b].
double sine_integral(double u0, const InletSchedule& s, double a, double b) {
  const double w = 2.0 * kPi * s.frequency;
  return u0 * (b - a) + s.amplitude / w * (std::cos(w * a + s.phase) - std::cos(w * b + s.phase));
}

struct Delivered {
  double in = 0.0;       // volume through the bottom [m^3, or m^2 per metre of depth in 2D]
  double out = 0.0;      // through the top
  double out_tol = 0.0;  // sum_k dt mass_tolerance m_ref,k / rho_g
};

template <int Dim>
Delivered run(const Grid<Dim>& grid, const GasConfig& cfg, int steps) {
  GasSolver<Dim> gas(grid, cfg);
  const Field<Dim> one(grid.domain, 0, 1.0);
  const Field<Dim> zero(grid.domain, 0, 0.0);
  CellVector<Dim> us;
  for (int a = 0; a < Dim; ++a) us[a] = zero;
  Delivered d;
  for (int k = 1; k <= steps; ++k) {
    const GasStepReport r = gas.advance(k * kDt, kDt, one, one, zero, us);
    d.in += r.mass_in * kDt / cfg.rho_g;
    d.out += r.mass_out * kDt / cfg.rho_g;
    d.out_tol += cfg.mass_tolerance * r.reference_mass_flow * kDt / cfg.rho_g;
  }
  return d;
}

GasConfig gas_only() {
  GasConfig cfg;
  cfg.gravity = {0.0, 0.0, 0.0};
  cfg.boundary.jets.clear();
  return cfg;
}

void report(const char* what, double exact, double computed, double tol) {
  std::printf("%-40s exact %.12e computed %.12e error %.3e (tolerance %.3e)\n", what, exact, computed,
              computed - exact, tol);
}

TEST(InletDelivers, TableBackgroundSineAndSquareJets2D) {
  const int steps = 48;
  const double t_end = steps * kDt;
  GasConfig cfg = gas_only();
  GasBoundaryConfig& bc = cfg.boundary;
  bc.inlet_velocity = 1.0;  // unused by the table
  bc.inlet_noise = 0.2;  // moves flow between the background faces, never the total
  bc.schedule.kind = ScheduleKind::Table;
  bc.schedule.times = {0.0, 10 * kDt, 25 * kDt, 40 * kDt};
  bc.schedule.velocities = {0.5, 2.0, 1.0, 1.5};
  InletJet sine{0.03, 0.02, 5.0, 8 * kDt, 40 * kDt};
  sine.schedule.kind = ScheduleKind::Sine;
  sine.schedule.amplitude = 3.0;
  sine.schedule.frequency = 8.0;
  sine.schedule.phase = 0.4;
  InletJet square{0.07, 0.02, 1.0, 0.0, 1.0};
  square.schedule.kind = ScheduleKind::Square;
  square.schedule.amplitude = 6.0;
  square.schedule.frequency = 16.0;  // 32 steps a period, on for the first 8
  square.schedule.duty = 0.25;
  bc.jets = {sine, square};
  const Grid<2> grid = Grid<2>::uniform({0.1, 0.2}, {10, 20});
  const Delivered d = run(grid, cfg, steps);

  const InletSchedule& tab = bc.schedule;
  const double ta = sine.t_start, tb = sine.t_end;
  const double v_bg = 0.1 * table_integral(tab, 0.0, t_end);
  const double v_sine = 0.02 * (sine_integral(5.0, sine.schedule, ta, tb) - table_integral(tab, ta, tb));
  const double on = 16 * kDt;  // [0, 8 dt) and [32 dt, 40 dt)
  const double v_square = 0.02 * (1.0 * t_end + 6.0 * on - table_integral(tab, 0.0, t_end));
  const double exact = v_bg + v_sine + v_square;
  const double w = 2.0 * kPi * 8.0;
  const double midpoint = 0.02 * (tb - ta) * kDt * kDt * 3.0 * w * w / 24.0;
  const double tol_in = midpoint + 1e-12 * exact;
  report("2D volume in through the bottom [m^2]", exact, d.in, tol_in);
  report("2D volume out through the top [m^2]", exact, d.out, tol_in + d.out_tol);
  EXPECT_NEAR(d.in, exact, tol_in);
  EXPECT_NEAR(d.out, exact, tol_in + d.out_tol);
  // Sharper: with the sine's integral replaced by its midpoint sum, the piecewise-linear parts stay exact and
  // only rounding remains.
  double sine_midpoint = 0.0;
  for (int k = 8; k < 40; ++k) {
    const double tm = (k + 0.5) * kDt;
    sine_midpoint += kDt * (5.0 + 3.0 * std::sin(2.0 * kPi * 8.0 * tm + 0.4));
  }
  const double as_stepped = v_bg + v_square + 0.02 * (sine_midpoint - table_integral(tab, ta, tb));
  report("2D volume in, sine as midpoint sum [m^2]", as_stepped, d.in, 1e-12 * exact);
  EXPECT_NEAR(d.in, as_stepped, 1e-12 * exact);
}

TEST(InletDelivers, RampedBackgroundAndPulsedPerforatedPlate3D) {
  const int steps = 32;
  const double t_end = steps * kDt;
  GasConfig cfg = gas_only();
  GasBoundaryConfig& bc = cfg.boundary;
  bc.inlet_velocity = 1.2;
  bc.inlet_noise = 0.3;
  bc.schedule.kind = ScheduleKind::Ramp;
  bc.schedule.ramp_from = 0.2;
  bc.schedule.ramp_start = 4 * kDt;
  bc.schedule.ramp_time = 16 * kDt;
  PerforatedPlate plate;
  plate.n_x = 2;
  plate.n_z = 2;
  plate.hole = 0.012;
  plate.pitch = 0.024;
  plate.x_centre = 0.03;
  plate.z_centre = 0.03;
  plate.velocity = 0.0;  // on/off: 0 m/s off, 7 m/s on
  plate.schedule.kind = ScheduleKind::Square;
  plate.schedule.amplitude = 7.0;
  plate.schedule.frequency = 32.0;  // 16 steps a period, on for the first 8
  plate.schedule.duty = 0.5;
  bc.jets = perforated_plate_holes(plate, 3);
  const Grid<3> grid = Grid<3>::uniform({0.06, 0.08, 0.06}, {6, 8, 6});
  const Delivered d = run(grid, cfg, steps);

  const double area = 0.06 * 0.06;
  const double open = 4 * kPi * 0.25 * 0.012 * 0.012;
  // Ramp: 0.2 until 4 dt, linear to 1.2 at 20 dt, then 1.2.
  const double bg = 0.2 * 4 * kDt + 0.5 * (0.2 + 1.2) * 16 * kDt + 1.2 * (t_end - 20 * kDt);
  const double holes = 7.0 * 16 * kDt;  // on for [0, 8 dt) and [16 dt, 24 dt)
  const double exact = area * bg + open * (holes - bg);
  const double tol_in = 1e-12 * exact;
  report("3D volume in through the bottom [m^3]", exact, d.in, tol_in);
  report("3D volume out through the top [m^3]", exact, d.out, tol_in + d.out_tol);
  EXPECT_NEAR(d.in, exact, tol_in);
  EXPECT_NEAR(d.out, exact, tol_in + d.out_tol);
}

}  // namespace
}  // namespace fluidbed
