// SIMPLE ended on the coupling bound (GasConfig::coupling_tolerance): the gas of a step, started from the same
// state with the same inputs, against the same step converged to the fixed tolerances. The bound promises that
// the iteration's remaining error is a small fraction kappa of the step's change of the mass flux, and the
// tightened last correction that the gas mass is still conserved to mass_tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "closures/drag.hpp"
#include "fluid/gas_solver.hpp"

namespace fluidbed {
namespace {

// A bed of 0.42 with a bubble of voidage 0.9 and radius 0.06 m rising at 0.8 m/s through it, the particles
// around it moving up at 0.3 m/s: voidage, drag and solids velocity all change from step to step.
double bed_eps(const Grid<2>& g, int i, int j, double t) {
  const double r = std::hypot(g.centre(0, i) - 0.15, g.centre(1, j) - (0.1 + 0.8 * t));
  return 0.42 + 0.48 * 0.5 * (1.0 - std::tanh((r - 0.06) / 0.01));
}

// Sum over the faces of rho_g eps_f A |u - w|, eps_f the mean of the two cells (a copy at the sides).
double flux_distance(const Grid<2>& g, const GasConfig& c, const Field<2>& eps, const GasFields<2>& u,
                     const GasFields<2>& w) {
  double s = 0.0;
  for (int a = 0; a < 2; ++a) {
    const IndexBox<2> faces = g.domain.faces(a);
    for_each(faces, [&](const Index<2>& f) {
      Index<2> lo = shifted<2>(f, a, -1), hi = f;
      lo[a] = std::max(lo[a], g.domain.lo[a]);
      hi[a] = std::min(hi[a], g.domain.hi[a] - 1);
      const double e = 0.5 * (eps[lo] + eps[hi]);
      s += c.rho_g * e * g.h[1 - a] * std::abs(u.u[a][f] - w.u[a][f]);
    });
  }
  return s;
}

struct Study {
  int steps = 0, stopped = 0, iterations_fixed = 0, iterations_coupled = 0;
  double worst = 0.0;        // the largest distance of the two answers over kappa x the step's change
  double contraction = 0.0;  // the largest contraction SIMPLE showed on a step that ended on the bound
  double understated = 0.0;  // the largest distance to the converged answer over the last move alone
};

// 250 steps of the bed above, each from the converged state, converged to the fixed tolerances and ended on the bound.
Study study(double relax_velocity) {
  const int nx = 15, ny = 30;
  const Grid<2> grid = Grid<2>::uniform({0.3, 0.6}, {nx, ny});
  GasConfig fixed_cfg;
  fixed_cfg.boundary.inlet_velocity = 1.8;
  fixed_cfg.boundary.jets = {InletJet{0.15, 0.02, 20.0, 0.01, 0.04}};
  fixed_cfg.relax_velocity = relax_velocity;
  GasConfig coupled_cfg = fixed_cfg;
  coupled_cfg.coupling_tolerance = 0.01;
  EXPECT_EQ(fixed_cfg.coupling_tolerance, 0.0);  // the struct's default: a gas alone converges every step
  GasSolver<2> fixed(grid, fixed_cfg), coupled(grid, coupled_cfg);
  Field<2> eps_old(cell_field(grid)), eps_new(cell_field(grid)), beta(cell_field(grid));
  Field<2> us(cell_field(grid, 0.0)), vs(cell_field(grid));
  const double dt = 2e-4, d = 0.004;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) eps_old(i, j) = bed_eps(grid, i, j, 0.0);
  Study r;
  for (int step = 1; step <= 250; ++step, ++r.steps) {
    const double t = step * dt;
    CellVector<2> ug;
    fixed.cell_velocity(ug);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        eps_new(i, j) = bed_eps(grid, i, j, t);
        vs(i, j) = 0.3 * (1.0 - eps_new(i, j)) / 0.58;
        const double slip = std::hypot(ug[0](i, j), ug[1](i, j) - vs(i, j));
        beta(i, j) = beta_ergun_wen_yu({eps_new(i, j), d, fixed_cfg.rho_g, fixed_cfg.mu_g, slip});
      }
    const GasFields<2> before = fixed.fields();
    coupled.fields() = before;
    const GasStepReport rf = fixed.advance(t, dt, eps_old, eps_new, beta, {us, vs});
    const GasStepReport rc = coupled.advance(t, dt, eps_old, eps_new, beta, {us, vs});
    r.iterations_fixed += rf.simple_iterations;
    r.iterations_coupled += rc.simple_iterations;
    EXPECT_FALSE(rf.stopped_on_coupling);
    EXPECT_LE(rc.simple_iterations, rf.simple_iterations) << "step " << step;
    // Continuity of the answer as tight as the fixed tolerance leaves it, whichever way SIMPLE ended.
    EXPECT_LT(rc.mass_balance_relative, coupled_cfg.mass_tolerance) << "step " << step;
    if (rc.stopped_on_coupling) {
      ++r.stopped;
      const double q = rc.contraction;
      EXPECT_LT(q, 1.0) << "step " << step;
      EXPECT_LT(rc.iterate_change * std::max(1.0, q / (1.0 - q)), coupled_cfg.coupling_tolerance * rc.flux_change)
          << "step " << step;
      r.contraction = std::max(r.contraction, q);
      // What the early stop left: the distance to the converged answer against the step's own change.
      const double change = flux_distance(grid, fixed_cfg, eps_new, fixed.fields(), before);
      const double distance = flux_distance(grid, fixed_cfg, eps_new, coupled.fields(), fixed.fields());
      r.worst = std::max(r.worst, distance / (coupled_cfg.coupling_tolerance * change));
      r.understated = std::max(r.understated, distance / (rc.iterate_change * rc.reference_mass_flow));
    }
    eps_old = eps_new;
  }
  std::printf("[ coupling ] relax_velocity %.2f, %d steps: SIMPLE iterations %.2f a step converged, %.2f on the "
              "bound (%d steps ended on it, contraction up to %.2f); largest distance to the converged answer %.3f "
              "x kappa x the step's change, %.2f x the last move\n",
              relax_velocity, r.steps, double(r.iterations_fixed) / r.steps, double(r.iterations_coupled) / r.steps,
              r.stopped, r.contraction, r.worst, r.understated);
  return r;
}

TEST(SimpleCouplingCriterion, EndsWithinItsBoundAndKeepsTheGasMass) {
  const Study r = study(0.8);
  // The bound must be what ends most steps, and save iterations, or the test checks nothing.
  EXPECT_GT(r.stopped, r.steps / 2);
  EXPECT_LT(r.iterations_coupled, r.iterations_fixed * 2 / 3);
  // SIMPLE contracts by about 4 an iteration here (docs/model-gas.md), so what remains after the last move d is
  // at most d (1/4) / (1 - 1/4) = d / 3, and d < kappa x change.
  EXPECT_LT(r.contraction, 0.5);
  EXPECT_LT(r.worst, 1.0 / 3.0);
}

// Heavy momentum under-relaxation slows SIMPLE's contraction to about 0.8, where the last move alone understates
// what remains by r / (1 - r), about 4: the bound then scales the move by it and must still hold. (Reading r from
// one ratio, at the third iteration, left 1.29 x kappa x change on the step the jet opens; ending on the move
// alone, 4.1.)
TEST(SimpleCouplingCriterion, SlowContractionStillEndsWithinItsBound) {
  const Study r = study(0.2);
  EXPECT_GT(r.stopped, r.steps / 2);
  EXPECT_GT(r.contraction, 0.5);   // the scaled form was what ended such steps ...
  EXPECT_GT(r.understated, 3.0);   // ... and the move alone would have promised too much
  EXPECT_LT(r.worst, 1.0);
}

}  // namespace
}  // namespace fluidbed
