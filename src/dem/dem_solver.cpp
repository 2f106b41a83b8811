#include "dem/dem_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <fmt/format.h>

#include "core/error.hpp"

namespace fluidbed {

std::vector<ContactParams> make_pair_params(const DemConfig& c) {
  const std::size_t ns = c.n_species();
  std::vector<ContactParams> t(ns * ns);
  for (std::size_t a = 0; a < ns; ++a) {
    for (std::size_t b = 0; b < ns; ++b) {
      const InteractionParams& ip = c.pair_params(static_cast<int>(a), static_cast<int>(b));
      const double m_eff = reduced_mass(c.species[a].mass(), c.species[b].mass());
      ContactParams& p = t[a * ns + b];
      p.k_n = c.stiffness;
      p.k_t = c.stiffness * c.tangential_stiffness_ratio;
      p.eta_n = damping_from_restitution(m_eff, p.k_n, ip.restitution);  // Eq. 8, reduced mass
      p.eta_t = p.eta_n;  // the paper's single dashpot eta for both directions (Eqs. 2-3)
      p.mu = ip.friction;
    }
  }
  return t;
}

std::vector<ContactParams> make_wall_params(const DemConfig& c) {
  std::vector<ContactParams> t(c.n_species());
  for (std::size_t a = 0; a < c.n_species(); ++a) {
    ContactParams& p = t[a];
    p.k_n = c.stiffness;
    p.k_t = c.stiffness * c.tangential_stiffness_ratio;
    p.eta_n = damping_from_restitution(c.species[a].mass(), p.k_n, c.wall[a].restitution);  // Eq. 8, wall fixed
    p.eta_t = p.eta_n;
    p.mu = c.wall[a].friction;
  }
  return t;
}

DemSolver::DemSolver(DemConfig config, ParticleStore particles)
    : config_(std::move(config)), p_(std::move(particles)) {
  pair_params_ = make_pair_params(config_);
  wall_params_ = make_wall_params(config_);
  double d_max = 0.0;
  for (const Species& s : config_.species) d_max = std::max(d_max, s.diameter);
  cell_size_ = d_max + config_.skin;
  p_.sort_by_id();
  for (std::size_t i = 1; i < p_.size(); ++i) {
    if (p_.id[i] == p_.id[i - 1]) {
      throw_input_error(fmt::format("particle id {} is given twice: every particle needs its own id", p_.id[i]));
    }
  }
  wall_xi_.assign(p_.size(), {});
}

void DemSolver::rebuild() {
  const std::size_t n = p_.size();
  // The old list in its old storage slots; its buffers are reused by the next rebuild.
  const bool have_old = nbr_.offset.size() == n + 1;
  if (have_old) {
    old_offset_.swap(nbr_.offset);
    old_partner_.swap(nbr_.partner);
    old_history_.swap(nbr_.history);
  }

  // Re-sort by cell only every few rebuilds: the list itself does not need sorted storage, and particles
  // drift from their cells slowly, so memory locality is kept at a fraction of the permutation cost.
  const bool sorted = rebuilds_ % kSortEvery == 0;
  std::vector<std::size_t> order, new_slot;
  if (sorted) {
    order = sort_by_cell(p_, cell_size_);
    p_.permute(order);
    std::vector<std::array<Vec2, 4>> w(n);
    new_slot.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      w[k] = wall_xi_[order[k]];
      new_slot[order[k]] = k;
    }
    wall_xi_.swap(w);
  }
  build_neighbor_list(p_, cell_size_, config_.skin, nbr_);

  if (have_old) {
    // Carry each stretched spring over to the new entry of the same pair; released springs (zero) need no
    // search, and a pair that left the list had released its spring already (it was beyond contact).
    const auto sn = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const std::size_t o = sorted ? order[i] : i;
      for (std::size_t q = old_offset_[o]; q < old_offset_[o + 1]; ++q) {
        const Vec2 h = old_history_[q];
        if (h.x == 0.0 && h.y == 0.0) continue;
        const std::size_t j = sorted ? new_slot[old_partner_[q]] : old_partner_[q];
        for (std::size_t k = nbr_.offset[i]; k < nbr_.offset[i + 1]; ++k) {
          if (nbr_.partner[k] == j) {
            nbr_.history[k] = h;
            break;
          }
        }
      }
    }
  }
  link_mirrors();
  x_build_ = p_.x;
  y_build_ = p_.y;
  need_rebuild_ = false;
  ++rebuilds_;
}

void DemSolver::link_mirrors() {
  const std::size_t n = p_.size();
  if (nbr_.entries() > std::numeric_limits<std::uint32_t>::max()) {
    throw_simulation_error("neighbour list too long for 32-bit entry links");
  }
  mirror_.resize(nbr_.entries());
  int missing = 0;
  const auto sn = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static) reduction(max : missing)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    for (std::size_t k = nbr_.offset[i]; k < nbr_.offset[i + 1]; ++k) {
      const std::size_t j = nbr_.partner[k];
      bool found = false;
      for (std::size_t q = nbr_.offset[j]; q < nbr_.offset[j + 1]; ++q) {
        if (nbr_.partner[q] == i) {
          mirror_[k] = static_cast<std::uint32_t>(q);
          found = true;
          break;
        }
      }
      if (!found) missing = 1;
    }
  }
  if (missing != 0) throw_simulation_error("neighbour list is not symmetric (internal error)");
  // A new list: no entry has a force yet (compute_forces relies on zeros in the entries not in contact).
  entry_force_.assign(nbr_.entries(), Vec2{});
  entry_torque_.assign(nbr_.entries(), 0.0);
}

double DemSolver::compute_forces(double dt) {
  // With one species every contact has the same diameter: the largest overlap fraction is the largest overlap over
  // it, taken once after the loops; only a mixture pays for a division per contact (5% of the force loop).
  return config_.n_species() > 1 ? compute_forces_of<true>(dt) : compute_forces_of<false>(dt);
}

template <bool Mixed>
double DemSolver::compute_forces_of(double dt) {
  const std::size_t n = p_.size();
  const double W = config_.width;
  const double H = config_.height;
  const WallConfig walls = config_.walls;
  const std::size_t ns = config_.n_species();
  if (mirror_.size() != nbr_.entries()) link_mirrors();  // a restored list
  double max_ov = 0.0;
  double max_frac = 0.0;  // overlap over the contact's own diameter (the dem.max_overlap_fraction test)
  const auto sn = static_cast<std::ptrdiff_t>(n);
  // Pass 1: every pair once, from its lower slot. The law is antisymmetric bit for bit, so writing -f and -xi to
  // the partner's entry gives exactly what the partner would have computed itself; no two pairs share an entry,
  // so threads never write the same memory.
#pragma omp parallel for schedule(static) reduction(max : max_ov, max_frac)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const double xi = p_.x[i], yi = p_.y[i], ri = p_.radius[i], wi = p_.omega[i];
    const Vec2 vi{p_.vx[i], p_.vy[i]};
    const std::size_t si = static_cast<std::size_t>(p_.species[i]);
    for (std::size_t k = nbr_.offset[i]; k < nbr_.offset[i + 1]; ++k) {
      const std::size_t j = nbr_.partner[k];
      if (j < i) continue;  // evaluated by j
      const std::size_t km = mirror_[k];
      const double dx = p_.x[j] - xi;
      const double dy = p_.y[j] - yi;
      const double d2 = dx * dx + dy * dy;
      const double rsum = ri + p_.radius[j];
      if (d2 >= rsum * rsum) {
        // Not touching: entries hold zeros unless this contact just ended (spring released, force cleared);
        // testing first spares the scattered writes to the partner's entry for the many pairs that only pass by.
        const Vec2 fk = entry_force_[k], hk = nbr_.history[k];
        if (fk.x != 0.0 || fk.y != 0.0 || hk.x != 0.0 || hk.y != 0.0) {
          nbr_.history[k] = Vec2{};
          nbr_.history[km] = Vec2{};
          entry_force_[k] = Vec2{};
          entry_force_[km] = Vec2{};
          entry_torque_[k] = 0.0;
          entry_torque_[km] = 0.0;
        }
        continue;
      }
      const double d = std::sqrt(d2);
      const double inv_d = 1.0 / d;
      const Vec2 nrm{dx * inv_d, dy * inv_d};
      const double overlap = rsum - d;
      // Velocity of i's contact point relative to j's; symmetric in (i, j) up to the sign, bit for bit.
      const Vec2 v_rel = (vi - p_.vel(j)) + cross(wi * ri + p_.omega[j] * p_.radius[j], nrm);
      const ContactForce cf = linear_spring_dashpot(pair_params_[si * ns + static_cast<std::size_t>(p_.species[j])],
                                                    ContactKinematics{nrm, overlap, v_rel}, dt, nbr_.history[k]);
      nbr_.history[km] = -nbr_.history[k];
      entry_force_[k] = cf.f;
      entry_force_[km] = -cf.f;
      // Eq. 9: the torque of the tangential force, r (n x f_t), equal for both partners ((-n) x (-f_t) = n x f_t).
      const double tq = cross(nrm, cf.f_t);
      entry_torque_[k] = tq;
      entry_torque_[km] = tq;
      max_ov = std::max(max_ov, overlap);
      // Judged against the smaller partner: its diameter sets how deep the pair can sink before the contact is
      // no longer a small perturbation of two touching spheres.
      if constexpr (Mixed) max_frac = std::max(max_frac, overlap / (2.0 * std::min(ri, p_.radius[j])));
    }
  }
  // Pass 2: each particle sums its own entries in list order (independent of the thread count), then its walls.
#pragma omp parallel for schedule(static) reduction(max : max_ov, max_frac)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const double xi = p_.x[i], yi = p_.y[i], ri = p_.radius[i], wi = p_.omega[i];
    const Vec2 vi{p_.vx[i], p_.vy[i]};
    const std::size_t si = static_cast<std::size_t>(p_.species[i]);
    Vec2 f{};
    double torque = 0.0;
    for (std::size_t k = nbr_.offset[i]; k < nbr_.offset[i + 1]; ++k) {
      f += entry_force_[k];
      torque += ri * entry_torque_[k];
    }
    // Plane walls: the same law against a fixed body of infinite mass.
    const ContactParams& wp = wall_params_[si];
    auto wall = [&](Wall w, bool enabled, double overlap, Vec2 nrm) {
      Vec2& xi_w = wall_xi_[i][static_cast<int>(w)];
      if (!enabled || overlap <= 0.0) {
        xi_w = Vec2{};
        return;
      }
      const Vec2 v_rel = vi + cross(wi * ri, nrm);
      const ContactForce cf = linear_spring_dashpot(wp, ContactKinematics{nrm, overlap, v_rel}, dt, xi_w);
      f += cf.f;
      torque += ri * cross(nrm, cf.f_t);
      max_ov = std::max(max_ov, overlap);
      if constexpr (Mixed) max_frac = std::max(max_frac, overlap / (2.0 * ri));
    };
    wall(Wall::Left, walls.left, ri - xi, {-1.0, 0.0});
    wall(Wall::Right, walls.right, ri - (W - xi), {1.0, 0.0});
    wall(Wall::Bottom, walls.bottom, ri - yi, {0.0, -1.0});
    wall(Wall::Top, walls.top, ri - (H - yi), {0.0, 1.0});
    p_.fx[i] = f.x;
    p_.fy[i] = f.y;
    p_.torque[i] = torque;
  }
  max_overlap_ = max_ov;
  max_overlap_fraction_ = Mixed || n == 0 ? max_frac : max_ov / (2.0 * p_.radius[0]);
  return max_ov;
}

DemStepInfo DemSolver::step() {
  DemStepInfo info = advance(config_.dt);
  // Whole steps from the clock origin: n dt carries one rounding, a running sum of dt one per step.
  time_ = time_origin_ + static_cast<double>(steps_ - steps_origin_) * config_.dt;
  return info;
}

DemStepInfo DemSolver::step(double h) {
  if (h == config_.dt) return step();
  DemStepInfo info = advance(h);
  time_ += h;
  time_origin_ = time_;
  steps_origin_ = steps_;
  return info;
}

DemStepInfo DemSolver::advance(double dt) {
  DemStepInfo info;
  if (need_rebuild_) {
    rebuild();
    info.rebuilt = true;
  }
  info.max_overlap = compute_forces(dt);

  // Eq. 10: explicit update, new velocity first, then position with the new velocity. The drag
  // drag_k (ug - v) is taken implicitly in v so that light or fine particles do not limit the time step;
  // with drag_k = 0 this is exactly Eq. 10.
  const std::size_t n = p_.size();
  const Vec2 g = config_.gravity;
  const double half_skin2 = 0.25 * config_.skin * config_.skin;
  const double H = config_.height;
  const DomainTest in_domain = domain_test();
  int moved_far = 0;
  int bad = 0;
  int escaped = 0;
  const auto sn = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static) reduction(max : moved_far, bad, escaped)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const double k = p_.drag_k[i];
    const double relax = 1.0 / (1.0 + dt * k * p_.inv_mass[i]);
    p_.vx[i] = (p_.vx[i] + ((p_.fx[i] + p_.fx_ext[i] + k * p_.ugx[i]) * p_.inv_mass[i] + g.x) * dt) * relax;
    p_.vy[i] = (p_.vy[i] + ((p_.fy[i] + p_.fy_ext[i] + k * p_.ugy[i]) * p_.inv_mass[i] + g.y) * dt) * relax;
    p_.x[i] += p_.vx[i] * dt;
    p_.y[i] += p_.vy[i] * dt;
    p_.omega[i] += p_.torque[i] * p_.inv_inertia[i] * dt;  // Eq. 9
    const double ddx = p_.x[i] - x_build_[i];
    const double ddy = p_.y[i] - y_build_[i];
    if (ddx * ddx + ddy * ddy >= half_skin2) moved_far = 1;
    if (!in_domain(p_, i)) bad = 1;
    if (in_domain.outflow && p_.y[i] > H) escaped = 1;
  }
  need_rebuild_ = moved_far != 0;
  ++steps_;
  if (bad != 0) check_particles();
  if (escaped != 0) info.removed = remove_escaped();
  return info;
}

std::size_t DemSolver::remove_escaped() {
  const std::size_t n = p_.size();
  const double H = config_.height;
  constexpr auto kGone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> keep, new_slot(n, kGone);
  keep.reserve(n);
  std::size_t removed = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (p_.y[i] > H) {
      ++removed;
      removed_mass_ += p_.mass[i];
    } else {
      new_slot[i] = keep.size();
      keep.push_back(i);
    }
  }
  removed_count_ += removed;
  // The neighbour list of the particles that stay, in the same order, with their springs: the remaining pairs
  // are still within reach of their last build, so the list stays valid without a rebuild.
  NeighborList list;
  list.offset.assign(keep.size() + 1, 0);
  list.partner.reserve(nbr_.partner.size());
  list.history.reserve(nbr_.history.size());
  if (nbr_.offset.size() == n + 1) {
    for (std::size_t k = 0; k < keep.size(); ++k) {
      const std::size_t i = keep[k];
      for (std::size_t q = nbr_.offset[i]; q < nbr_.offset[i + 1]; ++q) {
        const std::size_t j = new_slot[nbr_.partner[q]];
        if (j == kGone) continue;
        list.partner.push_back(static_cast<std::uint32_t>(j));
        list.history.push_back(nbr_.history[q]);
      }
      list.offset[k + 1] = list.partner.size();
    }
    nbr_ = std::move(list);
  } else {
    need_rebuild_ = true;
  }
  p_.permute(keep);
  std::vector<std::array<Vec2, 4>> w(keep.size());
  std::vector<double> xb(keep.size()), yb(keep.size());
  for (std::size_t k = 0; k < keep.size(); ++k) {
    w[k] = wall_xi_[keep[k]];
    xb[k] = x_build_.empty() ? p_.x[k] : x_build_[keep[k]];
    yb[k] = y_build_.empty() ? p_.y[k] : y_build_[keep[k]];
  }
  wall_xi_.swap(w);
  x_build_.swap(xb);
  y_build_.swap(yb);
  if (!need_rebuild_) link_mirrors();
  return removed;
}

void DemSolver::check_particles() const {
  const std::size_t n = p_.size();
  const double W = config_.width;
  const double H = config_.height;
  // Report the offending particle with the smallest id, so the message does not depend on threads.
  const DomainTest in_domain = domain_test();
  std::size_t worst = n;
  for (std::size_t i = 0; i < n; ++i) {
    if (!in_domain(p_, i) && (worst == n || p_.id[i] < p_.id[worst])) worst = i;
  }
  if (worst == n) return;
  const bool finite = std::isfinite(p_.x[worst]) && std::isfinite(p_.y[worst]) && std::isfinite(p_.vx[worst]) &&
                      std::isfinite(p_.vy[worst]) && std::isfinite(p_.omega[worst]);
  if (finite && p_.y[worst] > H && p_.x[worst] >= 0.0 && p_.x[worst] <= W) {
    throw_simulation_error(fmt::format(
        "t = {:.6g} s: particle {} left through the open top of the domain (y = {:.6g} m > {} m, velocity "
        "({:.6g}, {:.6g}) m/s). The top is open to the gas but particles may not leave: likely cause, the gas lifts "
        "the bed (a plug or a burst at the surface); remedy: domain.particle_top = \"outflow\" removes and counts "
        "the particles that leave (monitor.csv particles_lost, mass_lost_kg), domain.particle_top = \"wall\" keeps "
        "them in, or make the domain taller or ramp the inlet up (inlet.ramp_time).",
        time_, p_.id[worst], p_.y[worst], H, p_.vx[worst], p_.vy[worst]));
  }
  throw_simulation_error(fmt::format(
      "t = {:.6g} s: particle {} left the domain [0, {}] x [0, {}] m or its state is not finite: position "
      "({:.6g}, {:.6g}) m, velocity ({:.6g}, {:.6g}) m/s. Likely cause: the time step is too large for the "
      "stiffness (check `fluidbed check`); remedy: reduce dem.time_step.",
      time_, p_.id[worst], W, H, p_.x[worst], p_.y[worst], p_.vx[worst], p_.vy[worst]));
}

double DemSolver::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    e += 0.5 * p_.mass[i] * (p_.vx[i] * p_.vx[i] + p_.vy[i] * p_.vy[i]) +
         0.5 * p_.omega[i] * p_.omega[i] / p_.inv_inertia[i];
  }
  return e;
}

DemSolver::State DemSolver::state() const {
  return State{p_,           nbr_,          wall_xi_,       x_build_,      y_build_,
               time_,        steps_,        rebuilds_,      need_rebuild_, time_origin_,
               steps_origin_, removed_count_, removed_mass_};
}

void DemSolver::restore(State s) {
  p_ = std::move(s.particles);
  nbr_ = std::move(s.neighbors);
  wall_xi_ = std::move(s.wall_xi);
  x_build_ = std::move(s.x_build);
  y_build_ = std::move(s.y_build);
  time_ = s.time;
  steps_ = s.steps;
  rebuilds_ = s.rebuilds;
  time_origin_ = s.time_origin;
  steps_origin_ = s.steps_origin;
  removed_count_ = s.removed_count;
  removed_mass_ = s.removed_mass;
  need_rebuild_ = s.need_rebuild || nbr_.offset.size() != p_.size() + 1;
  mirror_.clear();  // linked again at the next force evaluation
  if (wall_xi_.size() != p_.size()) wall_xi_.assign(p_.size(), {});
}

}  // namespace fluidbed
