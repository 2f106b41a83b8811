#include "coupling/cfd_dem.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "coupling/voidage.hpp"
#include "fluid/drag.hpp"

namespace fluidbed {

CfdDemSimulation::CfdDemSimulation(DemSolver dem, std::optional<GasSolver<2>> gas, CouplingConfig coupling)
    : dem_(std::move(dem)), gas_(std::move(gas)), coupling_(coupling) {
  depth_ = coupling_.depth > 0.0 ? coupling_.depth : dem_.config().species[0].diameter;
  if (gas_) {
    const Grid2& g = gas_->grid2();
    for (Field2* f : {&eps_, &eps_gas_old_, &eps_gas_, &beta_, &us_, &vs_, &us_gas_, &vs_gas_, &ug_, &vg_}) *f = Field2(g.nx, g.ny);
  }
}

void CfdDemSimulation::clip_voidage() {
  for (std::size_t c = 0; c < eps_.v.size(); ++c) eps_gas_.v[c] = std::clamp(eps_.v[c], coupling_.eps_min, 1.0);
}

void CfdDemSimulation::deposit() {
  const Grid2& g = gas_->grid2();
  // One set of kernel weights per gas step serves the deposition here and the interpolation to the particles in
  // update_particle_forces (the particles do not move in between).
  particle_cell_weights(dem_.particles(), g, coupling_.voidage, weights_);
  compute_voidage(dem_.particles(), weights_, g, depth_, eps_);
  clip_voidage();
  cell_solids_velocity(dem_.particles(), weights_, g, us_, vs_);

  // Interphase coefficient of each cell as the gas sees it: the particles' drag coefficients K_p = V_p beta /
  // (1 - eps) summed with the deposition kernel, per unit cell volume (Eq. 12's beta), and the K-weighted mean
  // particle velocity, so that the gas receives what the particles feel (Newton's third law).
  const ParticleStore& p = dem_.particles();
  std::vector<double> k_sum(g.cells(), 0.0), ku(g.cells(), 0.0), kv(g.cells(), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const CellWeights& cw = weights_[i];
    for (int k = 0; k < cw.count; ++k) {
      const std::size_t c = cw.cell[static_cast<std::size_t>(k)];
      const double w = cw.w[static_cast<std::size_t>(k)] * p.drag_k[i];
      k_sum[c] += w;
      ku[c] += w * p.vx[i];
      kv[c] += w * p.vy[i];
    }
  }
  const double vcell = g.dx * g.dy * depth_;
  for (std::size_t c = 0; c < g.cells(); ++c) {
    beta_.v[c] = k_sum[c] / vcell;
    us_gas_.v[c] = k_sum[c] > 0.0 ? ku[c] / k_sum[c] : us_.v[c];
    vs_gas_.v[c] = k_sum[c] > 0.0 ? kv[c] / k_sum[c] : vs_.v[c];
  }
}

void CfdDemSimulation::update_particle_forces() {
  const Grid2& g = gas_->grid2();
  const GasConfig& gc = gas_->config();
  ParticleStore& p = dem_.particles();
  const auto n = static_cast<std::ptrdiff_t>(p.size());
  const bool pressure_force = coupling_.pressure_gradient_force;
  if (weights_.size() != p.size()) particle_cell_weights(p, g, coupling_.voidage, weights_);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const CellWeights& cw = weights_[i];
    const double eps = std::min(gather(eps_gas_, cw), 1.0 - 1e-9);
    const Vec2 ug = gas_->velocity_at({p.x[i], p.y[i]});
    const double r = p.radius[i];
    const double vp = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    const double slip = norm(ug - p.vel(i));
    const double beta = beta_ergun_wen_yu(DragInput{eps, 2.0 * r, gc.rho_g, gc.mu_g, slip}, coupling_.drag_switch);
    // Eq. 12's beta is per unit mixture volume; one particle's share is V_p / (1 - eps).
    p.drag_k[i] = vp * beta / (1.0 - eps);
    p.ugx[i] = ug.x;
    p.ugy[i] = ug.y;
    if (pressure_force) {
      const Vec2 gp = gas_->pressure_gradient_at({p.x[i], p.y[i]});
      p.fx_ext[i] = -vp * gp.x;
      p.fy_ext[i] = -vp * gp.y;
    } else {
      p.fx_ext[i] = 0.0;
      p.fy_ext[i] = 0.0;
    }
  }
  gas_->cell_velocity(ug_, vg_);
}

void CfdDemSimulation::initialize() {
  if (!gas_) return;
  deposit();
  eps_gas_old_ = eps_gas_;
  // One quasi-steady gas solve for the bed at rest (particles have no drag coefficient yet: do it twice, the
  // second time with the drag of the first).
  for (int pass = 0; pass < 2; ++pass) {
    report_ = gas_->advance(time(), macro_dt(), eps_gas_old_, eps_gas_, beta_, us_gas_, vs_gas_);
    update_particle_forces();
    deposit();
  }
  eps_gas_old_ = eps_gas_;
}

void CfdDemSimulation::advance(double h) {
  const bool full = h == macro_dt();
  if (!gas_) {
    if (full) {
      dem_.step();
    } else {
      dem_.step(h);
    }
    return;
  }
  for (int k = 0; k < coupling_.dem_substeps; ++k) {
    if (full) {
      dem_.step();
    } else {
      dem_.step(h / coupling_.dem_substeps);
    }
  }
  eps_gas_old_ = eps_gas_;
  deposit();
  report_ = gas_->advance(time(), h, eps_gas_old_, eps_gas_, beta_, us_gas_, vs_gas_);
  ++gas_steps_;
  update_particle_forces();
}

double CfdDemSimulation::min_voidage() const {
  return eps_.v.empty() ? 1.0 : *std::min_element(eps_.v.begin(), eps_.v.end());
}

Vec2 CfdDemSimulation::total_fluid_force() const {
  const ParticleStore& p = dem_.particles();
  Vec2 f{};
  for (std::size_t i = 0; i < p.size(); ++i) {
    f.x += p.fx_ext[i] + p.drag_k[i] * (p.ugx[i] - p.vx[i]);
    f.y += p.fy_ext[i] + p.drag_k[i] * (p.ugy[i] - p.vy[i]);
  }
  return f;
}

Vec2 CfdDemSimulation::total_gas_reaction() const {
  if (!gas_) return {};
  const Grid2& g = gas_->grid2();
  const double vcell = g.dx * g.dy * depth_;
  Vec2 f{};
  for (std::size_t c = 0; c < g.cells(); ++c) {
    f.x += beta_.v[c] * (ug_.v[c] - us_gas_.v[c]) * vcell;
    f.y += beta_.v[c] * (vg_.v[c] - vs_gas_.v[c]) * vcell;
  }
  return f;
}

void CfdDemSimulation::restore(Field2 eps, std::uint64_t gas_steps) {
  gas_steps_ = gas_steps;
  if (!gas_) return;
  eps_ = std::move(eps);
  const Grid2& g = gas_->grid2();
  clip_voidage();
  particle_cell_weights(dem_.particles(), g, coupling_.voidage, weights_);  // of the restored particles
  cell_solids_velocity(dem_.particles(), weights_, g, us_, vs_);
  gas_->cell_velocity(ug_, vg_);
}

}  // namespace fluidbed
