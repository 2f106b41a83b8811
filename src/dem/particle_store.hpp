#pragma once
// Structure-of-arrays particle store (AMReX/MFiX-Exa SoA layout): one vector per attribute, so kernels stream
// through memory and a later MPI/GPU port moves whole arrays. Storage order is free (re-sorted by cell);
// the global id is the identity of a particle.
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "core/vec2.hpp"

namespace fluidbed {

/// Particle species: mass and inertia are those of a sphere (the paper's 2D bed of spheres).
struct Species {
  double diameter = 0.004;  ///< m
  double density = 2700.0;  ///< kg/m^3

  double radius() const { return 0.5 * diameter; }
  double volume() const { return std::numbers::pi * diameter * diameter * diameter / 6.0; }
  double mass() const { return density * volume(); }
  /// Solid sphere: I = (2/5) m r^2.
  double inertia() const { return 0.4 * mass() * radius() * radius(); }
};

struct ParticleStore {
  std::vector<std::int64_t> id;
  std::vector<std::int32_t> species;
  std::vector<std::int32_t> layer;  ///< initial horizontal layer (colouring of the paper's Fig. 4a)
  std::vector<double> x, y;         ///< centre, m
  std::vector<double> vx, vy;       ///< velocity, m/s
  std::vector<double> omega;        ///< spin about z, rad/s
  std::vector<double> radius;       ///< m
  std::vector<double> mass;         ///< kg
  std::vector<double> inv_mass;     ///< 1/kg
  std::vector<double> inv_inertia;  ///< 1/(kg m^2)
  std::vector<double> fx, fy;       ///< contact force of the current step, N
  std::vector<double> torque;       ///< contact torque of the current step, N m
  std::vector<double> fx_ext, fy_ext;  ///< fluid force other than drag (pressure gradient), N; held between gas steps
  std::vector<double> drag_k;          ///< drag coefficient V_p beta / (1 - eps) of the particle, kg/s
  std::vector<double> ugx, ugy;        ///< gas velocity at the particle, m/s; drag = drag_k (ug - v)

  std::size_t size() const { return id.size(); }

  /// Room for n particles in every array (a placement that knows its count avoids push_back's slack).
  void reserve(std::size_t n) {
    id.reserve(n);
    species.reserve(n);
    layer.reserve(n);
    for (std::vector<double>* a : {&x, &y, &vx, &vy, &omega, &radius, &mass, &inv_mass, &inv_inertia, &fx, &fy, &torque,
                                   &fx_ext, &fy_ext, &drag_k, &ugx, &ugy}) {
      a->reserve(n);
    }
  }

  void add(std::int64_t id_, std::int32_t species_, const Species& s, Vec2 pos, Vec2 vel = {}, double w = 0.0,
           std::int32_t layer_ = 0) {
    id.push_back(id_);
    species.push_back(species_);
    layer.push_back(layer_);
    x.push_back(pos.x);
    y.push_back(pos.y);
    vx.push_back(vel.x);
    vy.push_back(vel.y);
    omega.push_back(w);
    radius.push_back(s.radius());
    mass.push_back(s.mass());
    inv_mass.push_back(1.0 / s.mass());
    inv_inertia.push_back(1.0 / s.inertia());
    fx.push_back(0.0);
    fy.push_back(0.0);
    torque.push_back(0.0);
    fx_ext.push_back(0.0);
    fy_ext.push_back(0.0);
    drag_k.push_back(0.0);
    ugx.push_back(0.0);
    ugy.push_back(0.0);
  }

  Vec2 pos(std::size_t i) const { return {x[i], y[i]}; }
  Vec2 vel(std::size_t i) const { return {vx[i], vy[i]}; }

  /// Reorder every attribute so that new slot k holds old slot order[k]; slots that `order` does not name are
  /// dropped (a selection, e.g. the particles that stay after some left the domain).
  void permute(const std::vector<std::size_t>& order);
  /// Ascending id: the canonical storage order a solver starts from, so that a run depends on the particles and
  /// not on how they were stored when handed over (settled in memory, read from a CSV in any row order).
  void sort_by_id();
  void clear();
};

}  // namespace fluidbed
