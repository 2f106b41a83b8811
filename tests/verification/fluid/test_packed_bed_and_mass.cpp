// Gas through a frozen packed bed against the Ergun equation, and the gas mass balance with a moving, breathing
// low-voidage blob and a jet switching on and off.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <cstdio>

#include "closures/drag.hpp"
#include "fluid/gas_solver.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.004;  // Table 1: 4 mm particles

// beta of Eq. 13 per cell from the current gas velocity, the solids being at rest.
void update_beta(const GasSolver<2>& gas, const Field<2>& eps, Field<2>& beta) {
  CellVector<2> u;
  gas.cell_velocity(u);
  const Field<2>& ug = u[0];
  const Field<2>& vg = u[1];
  const GasConfig& c = gas.config();
  for (std::size_t k = 0; k < eps.data().size(); ++k) {
    const double slip = std::hypot(ug.data()[k], vg.data()[k]);
    beta.data()[k] = beta_ergun_wen_yu({eps.data()[k], kD, c.rho_g, c.mu_g, slip});
  }
}

TEST(PackedBed, PressureDropFollowsErgun) {
  // Uniform eps = 0.4, gas through the whole bottom. For uniform flow the discrete momentum balance is
  // eps dP/dy = -beta v + eps rho g exactly, so the only deviations from Ergun come from the SIMPLE tolerance
  // (1e-8) and the lagged beta, converged here to 1e-10: a relative tolerance of 1e-6 is ample (brief: 2%).
  const int nx = 5;
  const int ny = 25;
  const Grid<2> grid = Grid<2>::uniform({0.1, 0.5}, {nx, ny});
  const double eps_bed = 0.4;
  for (double u_sup : {0.5, 1.0, 1.8, 3.0}) {
    GasConfig cfg;
    cfg.boundary.jets.clear();
    cfg.boundary.inlet_velocity = u_sup;
    GasSolver<2> gas(grid, cfg);
    const Field<2> eps(cell_field(grid, eps_bed));
    const Field<2> zero(cell_field(grid, 0.0));
    Field<2> beta(cell_field(grid, 0.0));
    double dp_prev = 0.0;
    bool steady = false;
    for (int step = 1; step <= 200 && !steady; ++step) {
      update_beta(gas, eps, beta);
      const GasStepReport rep = gas.advance(step * 0.01, 0.01, eps, eps, beta, {zero, zero});
      ASSERT_LT(rep.mass_residual, cfg.mass_tolerance);
      steady = std::abs(gas.pressure_drop() - dp_prev) < 1e-10 * std::abs(gas.pressure_drop());
      dp_prev = gas.pressure_drop();
    }
    ASSERT_TRUE(steady);
    const double height = (ny - 1) * grid.h[1];  // between the bottom and top cell centres
    const double measured = gas.pressure_drop() / height - cfg.rho_g * std::abs(cfg.gravity.y);
    const double ergun = ergun_pressure_gradient(eps_bed, kD, cfg.rho_g, cfg.mu_g, u_sup);
    std::printf("[ ergun    ] U = %.2f m/s: dP/dy (frictional) computed %.4f Pa/m, Ergun %.4f Pa/m, rel. error %.2e\n",
                u_sup, measured, ergun, std::abs(measured / ergun - 1.0));
    EXPECT_NEAR(measured / ergun, 1.0, 1e-6);
    // The interstitial velocity is the superficial one over eps everywhere.
    for (int j = 0; j <= ny; ++j) EXPECT_NEAR(gas.fields().u[1](2, j), u_sup / eps_bed, 1e-9 * u_sup);
  }
}

// Voidage: bed of 0.45 with a disc of radius 0.05 m whose centre rises at 1 m/s and whose voidage breathes,
// so the total gas volume changes in time (a non-zero accumulation term).
double blob_eps(const Grid<2>& g, int i, int j, double t) {
  const double xc = 0.15;
  const double yc = 0.12 + 1.0 * t;
  const double r = std::hypot(g.centre(0, i) - xc, g.centre(1, j) - yc);
  const double inside = 0.5 * (1.0 - std::tanh((r - 0.05) / 0.01));
  return 0.45 + (0.25 + 0.2 * std::sin(60.0 * t)) * inside;
}

TEST(GasMassBalance, ClosedEveryStepWithMovingBlobAndJet) {
  const int nx = 15;
  const int ny = 30;
  const Grid<2> grid = Grid<2>::uniform({0.3, 0.6}, {nx, ny});
  GasConfig cfg;
  cfg.boundary.inlet_velocity = 1.8;
  cfg.boundary.jets = {InletJet{0.15, 0.02, 30.0, 0.01, 0.05}};
  GasSolver<2> gas(grid, cfg);
  Field<2> eps_old(cell_field(grid)), eps_new(cell_field(grid)), beta(cell_field(grid)), zero(cell_field(grid, 0.0));
  const double dt = 1e-3;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) eps_old(i, j) = blob_eps(grid, i, j, 0.0);
  double max_balance = 0.0;
  double max_accumulation = 0.0;
  double min_in = 1e300;
  double max_in = 0.0;
  int max_iterations = 0;
  for (int step = 1; step <= 80; ++step) {
    const double t = step * dt;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) eps_new(i, j) = blob_eps(grid, i, j, t);
    update_beta(gas, eps_new, beta);
    const GasStepReport rep = gas.advance(t, dt, eps_old, eps_new, beta, {zero, zero});
    // Independent bookkeeping from the fields: inflow and outflow through the faces, change of gas volume.
    const GasFields<2>& f = gas.fields();
    double in = 0.0;
    double out = 0.0;
    double acc = 0.0;
    for (int i = 0; i < nx; ++i) {
      in += cfg.rho_g * eps_new(i, 0) * f.u[1](i, 0) * grid.h[0];
      out += cfg.rho_g * eps_new(i, ny - 1) * f.u[1](i, ny) * grid.h[0];
    }
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) acc += cfg.rho_g * (eps_new(i, j) - eps_old(i, j)) * grid.h[0] * grid.h[1] / dt;
    const double balance = std::abs(out - in + acc) / rep.reference_mass_flow;
    // The report and the independent sum agree, and both close to the solver tolerance.
    EXPECT_NEAR(rep.mass_in, in, 1e-12 * rep.reference_mass_flow);
    EXPECT_NEAR(rep.mass_out, out, 1e-12 * rep.reference_mass_flow);
    EXPECT_LT(balance, cfg.mass_tolerance) << "step " << step;
    EXPECT_LT(rep.mass_balance_relative, cfg.mass_tolerance) << "step " << step;
    EXPECT_LT(rep.mass_residual, cfg.mass_tolerance) << "step " << step;
    max_balance = std::max(max_balance, balance);
    max_accumulation = std::max(max_accumulation, std::abs(acc) / rep.reference_mass_flow);
    min_in = std::min(min_in, in);
    max_in = std::max(max_in, in);
    max_iterations = std::max(max_iterations, rep.simple_iterations);
    eps_old = eps_new;
  }
  std::printf("[ mass     ] 80 steps: max |out - in + accumulation| / reference = %.2e, max |accumulation| / "
              "reference = %.2e, inflow %.4f..%.4f kg/s/m, max SIMPLE iterations %d\n",
              max_balance, max_accumulation, min_in, max_in, max_iterations);
  // The test is only meaningful if the accumulation term and the jet switching actually happened.
  EXPECT_GT(max_accumulation, 1e-2);
  EXPECT_NEAR(max_in, cfg.rho_g * (1.8 * 0.28 + 30.0 * 0.02), 1e-9);
  EXPECT_NEAR(min_in, cfg.rho_g * 1.8 * 0.3, 1e-9);
}

/// Two gas steps of the blob and a jet on an nx x ny grid of the 0.3 x 0.6 m box with the given OpenMP threads.
GasFields<2> blob_steps_with_threads(int nx, int ny, int threads, ViscousStress viscous = ViscousStress::Off) {
  const Grid<2> grid = Grid<2>::uniform({0.3, 0.6}, {nx, ny});
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  GasConfig cfg;
  cfg.viscous = viscous;
  cfg.boundary.jets = {InletJet{0.15, 0.02, 30.0, 0.0, 1.0}};
  GasSolver<2> gas(grid, cfg);
  Field<2> eps_old(cell_field(grid)), eps_new(cell_field(grid)), beta(cell_field(grid)), zero(cell_field(grid, 0.0));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) eps_old(i, j) = blob_eps(grid, i, j, 0.0);
  for (int step = 1; step <= 2; ++step) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) eps_new(i, j) = blob_eps(grid, i, j, step * 1e-4);
    update_beta(gas, eps_new, beta);
    const GasStepReport rep = gas.advance(step * 1e-4, 1e-4, eps_old, eps_new, beta, {zero, zero});
    std::printf("[ threads  ] %d x %d, %d thread(s), step %d: %d SIMPLE iterations\n", nx, ny, threads, step,
                rep.simple_iterations);
    eps_old = eps_new;
  }
  omp_set_num_threads(saved);
  return gas.fields();
}

TEST(GasSolverThreads, ResultsIndependentOfThreadCount) {
  // A grid above the OpenMP threshold (16,384 cells): the face loops threaded; bitwise equal fields.
  const GasFields<2> one = blob_steps_with_threads(120, 140, 1);
  const GasFields<2> two = blob_steps_with_threads(120, 140, 2);
  EXPECT_EQ(one.u[0].data(), two.u[0].data());
  EXPECT_EQ(one.u[1].data(), two.u[1].data());
  EXPECT_EQ(one.p.data(), two.p.data());
}

TEST(GasSolverThreads, ComponentsSolvedConcurrentlyGiveTheSerialResult) {
  // The paper's cell size (0.02 m), below the threshold: u and v are assembled and solved on two threads at once
  // (viscous stress off), or one after the other (full stress, where v reads the new u). Bitwise equal fields.
  for (ViscousStress viscous : {ViscousStress::Off, ViscousStress::Full}) {
    const GasFields<2> one = blob_steps_with_threads(15, 30, 1, viscous);
    const GasFields<2> two = blob_steps_with_threads(15, 30, 2, viscous);
    const GasFields<2> three = blob_steps_with_threads(15, 30, 3, viscous);
    EXPECT_EQ(one.u[0].data(), two.u[0].data());
    EXPECT_EQ(one.u[1].data(), two.u[1].data());
    EXPECT_EQ(one.p.data(), two.p.data());
    EXPECT_EQ(one.u[0].data(), three.u[0].data());
    EXPECT_EQ(one.p.data(), three.p.data());
  }
}

}  // namespace
}  // namespace fluidbed
