#pragma once
// Structure-of-arrays particle store (AMReX/MFiX-Exa SoA layout): one vector per attribute, so kernels stream
// through memory and a later MPI/GPU port moves whole arrays. Storage order is free (re-sorted by cell);
// the global id is the identity of a particle, and every per-particle attribute is here, so that it travels with
// the particle through re-sorting and, later, migration. (The springs against the walls, which few particles hold,
// are kept apart by the solver: dem/wall_springs.hpp.)
//
// The attributes are listed once, in for_each_array; reserve, add, permute, clear and the checkpoint's save and
// load all go through it, so adding an attribute is one edit. Names per dimension:
//   2D: x, y; vx, vy; omega (spin about z); fx, fy; torque (about z); fx_ext, fy_ext; ugx, ugy.
//   3D: x, y, z; vx, vy, vz; omega_x, omega_y, omega_z; fx, fy, fz; torque_x, torque_y, torque_z; fx_ext, fy_ext,
//       fz_ext; ugx, ugy, ugz.
// Axis-generic kernels use coord(a), velocity(a), force(a), force_ext(a), gas_velocity(a) and, per spin
// component c (one in 2D, three in 3D), spin_component(c) and torque_component(c).
#include <array>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/vec.hpp"
#include "dem/size_distribution.hpp"

namespace fluidbed {

/// Particle species: mass and inertia are those of a sphere (the paper's 2D bed of spheres). A species may place
/// its particles with a size distribution (`size`); each particle then keeps its own diameter, and `diameter` is
/// the distribution's number mean, the species' representative size.
struct Species {
  double diameter = 0.004;  ///< m
  double density = 2700.0;  ///< kg/m^3
  /// Sizes of the randomly placed particles; law Fixed (the default): all `diameter`.
  SizeDistribution size{};

  double radius() const { return 0.5 * diameter; }
  double volume() const { return std::numbers::pi * diameter * diameter * diameter / 6.0; }
  double mass() const { return density * volume(); }
  /// Solid sphere: I = (2/5) m r^2.
  double inertia() const { return 0.4 * mass() * radius() * radius(); }

  bool sized() const { return size.law != SizeLaw::Fixed; }
  /// Smallest and largest diameter a particle of this species can have, m.
  double d_min() const { return sized() ? size.d_min : diameter; }
  double d_max() const { return sized() ? size.d_max : diameter; }
  /// The distribution of the placed sizes (a fixed one at `diameter` for law Fixed).
  SizeDistribution distribution() const { return sized() ? size : fixed_size(diameter); }
  /// The same material at diameter d (a fixed size): what one particle of the species is.
  Species of_diameter(double d) const {
    Species s = *this;
    s.diameter = d;
    s.size = SizeDistribution{};
    return s;
  }
};

/// Number of spin components: one (about z) in 2D, three in 3D.
template <int Dim>
inline constexpr int kSpinComponents = Dim == 2 ? 1 : 3;

/// The per-dimension named arrays of a ParticleStore (see the file comment for the names).
template <int Dim>
struct ParticleAxes;

template <>
struct ParticleAxes<2> {
  std::vector<double> x, y;            ///< centre, m
  std::vector<double> vx, vy;          ///< velocity, m/s
  std::vector<double> omega;           ///< spin about z, rad/s
  std::vector<double> fx, fy;          ///< contact force of the current step, N
  std::vector<double> torque;          ///< contact torque of the current step, N m
  std::vector<double> fx_ext, fy_ext;  ///< fluid force other than drag (pressure gradient), N; held between gas steps
  std::vector<double> ugx, ugy;        ///< gas velocity at the particle, m/s; drag = drag_k (ug - v)

 protected:
  std::vector<double>* coord_(int a) { return a == 0 ? &x : &y; }
  std::vector<double>* vel_(int a) { return a == 0 ? &vx : &vy; }
  std::vector<double>* force_(int a) { return a == 0 ? &fx : &fy; }
  std::vector<double>* force_ext_(int a) { return a == 0 ? &fx_ext : &fy_ext; }
  std::vector<double>* ug_(int a) { return a == 0 ? &ugx : &ugy; }
  std::vector<double>* spin_(int) { return &omega; }
  std::vector<double>* torque_(int) { return &torque; }
  static constexpr const char* kSpinName[1] = {"omega"};
  static constexpr const char* kTorqueName[1] = {"torque"};
};

template <>
struct ParticleAxes<3> {
  std::vector<double> x, y, z;                   ///< centre, m
  std::vector<double> vx, vy, vz;                ///< velocity, m/s
  std::vector<double> omega_x, omega_y, omega_z; ///< spin vector, rad/s
  std::vector<double> fx, fy, fz;                ///< contact force of the current step, N
  std::vector<double> torque_x, torque_y, torque_z;  ///< contact torque of the current step, N m
  std::vector<double> fx_ext, fy_ext, fz_ext;    ///< fluid force other than drag, N; held between gas steps
  std::vector<double> ugx, ugy, ugz;             ///< gas velocity at the particle, m/s

 protected:
  std::vector<double>* coord_(int a) { return a == 0 ? &x : (a == 1 ? &y : &z); }
  std::vector<double>* vel_(int a) { return a == 0 ? &vx : (a == 1 ? &vy : &vz); }
  std::vector<double>* force_(int a) { return a == 0 ? &fx : (a == 1 ? &fy : &fz); }
  std::vector<double>* force_ext_(int a) { return a == 0 ? &fx_ext : (a == 1 ? &fy_ext : &fz_ext); }
  std::vector<double>* ug_(int a) { return a == 0 ? &ugx : (a == 1 ? &ugy : &ugz); }
  std::vector<double>* spin_(int c) { return c == 0 ? &omega_x : (c == 1 ? &omega_y : &omega_z); }
  std::vector<double>* torque_(int c) { return c == 0 ? &torque_x : (c == 1 ? &torque_y : &torque_z); }
  static constexpr const char* kSpinName[3] = {"omega_x", "omega_y", "omega_z"};
  static constexpr const char* kTorqueName[3] = {"torque_x", "torque_y", "torque_z"};
};

/// What an attribute is for a checkpoint: state a restart needs, or a value recomputed every step.
enum class ArrayRole { State, Derived };

template <int Dim>
struct ParticleStore : ParticleAxes<Dim> {
  static constexpr int dim = Dim;
  static constexpr int kWalls = 2 * Dim;  ///< plane walls: low and high side of each axis (Wall<Dim> order)

  std::vector<std::int64_t> id;
  std::vector<std::int32_t> species;
  std::vector<std::int32_t> layer;  ///< initial horizontal layer (colouring of the paper's Fig. 4a)
  /// The cell of a global lattice the particle was in at the last sorting rebuild of the neighbour list: with the
  /// id, its place in the order every per-cell sum over particles takes (DemSolver::canonical_order), which is the
  /// storage order after such a rebuild, and the same on every rank.
  std::vector<std::int64_t> order_key;
  std::vector<double> radius;       ///< m
  std::vector<double> mass;         ///< kg
  std::vector<double> inv_mass;     ///< 1/kg
  std::vector<double> inv_inertia;  ///< 1/(kg m^2)
  std::vector<double> drag_k;       ///< drag coefficient V_p beta / (1 - eps) of the particle, kg/s

  std::size_t size() const { return id.size(); }

  std::vector<double>& coord(int a) { return *this->coord_(a); }
  const std::vector<double>& coord(int a) const { return *const_cast<ParticleStore*>(this)->coord_(a); }
  std::vector<double>& velocity(int a) { return *this->vel_(a); }
  const std::vector<double>& velocity(int a) const { return *const_cast<ParticleStore*>(this)->vel_(a); }
  std::vector<double>& force(int a) { return *this->force_(a); }
  const std::vector<double>& force(int a) const { return *const_cast<ParticleStore*>(this)->force_(a); }
  std::vector<double>& force_ext(int a) { return *this->force_ext_(a); }
  const std::vector<double>& force_ext(int a) const { return *const_cast<ParticleStore*>(this)->force_ext_(a); }
  std::vector<double>& gas_velocity(int a) { return *this->ug_(a); }
  const std::vector<double>& gas_velocity(int a) const { return *const_cast<ParticleStore*>(this)->ug_(a); }
  std::vector<double>& spin_component(int c) { return *this->spin_(c); }
  const std::vector<double>& spin_component(int c) const { return *const_cast<ParticleStore*>(this)->spin_(c); }
  std::vector<double>& torque_component(int c) { return *this->torque_(c); }
  const std::vector<double>& torque_component(int c) const {
    return *const_cast<ParticleStore*>(this)->torque_(c);
  }

  /// Every attribute with its name and role: f(name, vector&, role) for the id, species and layer arrays
  /// (int64, int32) and every double array, in a fixed order. The one list of the attributes.
  template <class F>
  void for_each_array(F&& f) {
    static constexpr const char* kAxis[3] = {"x", "y", "z"};
    f(std::string("id"), id, ArrayRole::State);
    f(std::string("species"), species, ArrayRole::State);
    f(std::string("layer"), layer, ArrayRole::State);
    f(std::string("order_key"), order_key, ArrayRole::State);
    for (int a = 0; a < Dim; ++a) f(std::string(kAxis[a]), coord(a), ArrayRole::State);
    for (int a = 0; a < Dim; ++a) f(std::string("v") + kAxis[a], velocity(a), ArrayRole::State);
    for (int c = 0; c < kSpinComponents<Dim>; ++c) f(std::string(this->kSpinName[c]), spin_component(c), ArrayRole::State);
    f(std::string("radius"), radius, ArrayRole::Derived);
    f(std::string("mass"), mass, ArrayRole::Derived);
    f(std::string("inv_mass"), inv_mass, ArrayRole::Derived);
    f(std::string("inv_inertia"), inv_inertia, ArrayRole::Derived);
    for (int a = 0; a < Dim; ++a) f(std::string("f") + kAxis[a], force(a), ArrayRole::Derived);
    for (int c = 0; c < kSpinComponents<Dim>; ++c) {
      f(std::string(this->kTorqueName[c]), torque_component(c), ArrayRole::Derived);
    }
    if (fluid_arrays_) for_each_fluid_array(f);
  }
  /// The arrays only a run with gas uses (for_each_array's last), with their names and roles.
  template <class F>
  void for_each_fluid_array(F&& f) {
    static constexpr const char* kAxis[3] = {"x", "y", "z"};
    for (int a = 0; a < Dim; ++a) f(std::string("f") + kAxis[a] + "_ext", force_ext(a), ArrayRole::State);
    f(std::string("drag_k"), drag_k, ArrayRole::State);
    for (int a = 0; a < Dim; ++a) f(std::string("ug") + kAxis[a], gas_velocity(a), ArrayRole::State);
  }
  /// Whether the store holds the fluid's arrays (force_ext, drag_k, gas_velocity). A run without gas leaves them
  /// out: nothing writes them, and they are 56 of a 3D particle's 232 bytes. for_each_array lists them only when
  /// held, so every copy, permutation, message and checkpoint follows.
  bool holds_fluid_arrays() const { return fluid_arrays_; }
  /// Gives the fluid's arrays up (emptied, their memory freed) or takes them (zero for every particle).
  void hold_fluid_arrays(bool on) {
    if (on == fluid_arrays_) return;
    const std::size_t n = size();
    for_each_fluid_array([&](const std::string&, std::vector<double>& a, ArrayRole) {
      if (on) {
        a.assign(n, 0.0);
      } else {
        std::vector<double>().swap(a);
      }
    });
    fluid_arrays_ = on;
  }
  template <class F>
  void for_each_array(F&& f) const {
    const_cast<ParticleStore*>(this)->for_each_array(
        [&](const std::string& name, auto& a, ArrayRole role) { f(name, std::as_const(a), role); });
  }
  /// Bytes of one particle over all its arrays (the fluid's included).
  static std::size_t bytes_per_particle() {
    std::size_t b = 0;
    ParticleStore p;
    p.for_each_array([&](const std::string&, auto& a, ArrayRole) { b += sizeof(typename std::decay_t<decltype(a)>::value_type); });
    return b;
  }

  /// Room for n particles in every array (a placement that knows its count avoids push_back's slack).
  void reserve(std::size_t n) {
    for_each_array([n](const std::string&, auto& a, ArrayRole) { a.reserve(n); });
  }

  /// Append a particle of species s at its diameter s.diameter (`of_diameter` gives a particle its own size): at
  /// rest by default, forces and drag zero.
  void add(std::int64_t id_, std::int32_t species_, const Species& s, Vec<Dim> pos, Vec<Dim> vel = {},
           Spin<Dim> w = {}, std::int32_t layer_ = 0) {
    for_each_array([](const std::string&, auto& a, ArrayRole) { a.emplace_back(); });
    const std::size_t i = size() - 1;
    id[i] = id_;
    species[i] = species_;
    layer[i] = layer_;
    for (int a = 0; a < Dim; ++a) {
      coord(a)[i] = pos[a];
      velocity(a)[i] = vel[a];
    }
    set_spin(i, w);
    set_size(i, s);
  }
  /// Radius, mass and inertia of particle i: a sphere of s.diameter and s.density.
  void set_size(std::size_t i, const Species& s) {
    radius[i] = s.radius();
    mass[i] = s.mass();
    inv_mass[i] = 1.0 / s.mass();
    inv_inertia[i] = 1.0 / s.inertia();
  }
  /// Largest particle diameter in the store (0 when empty), m.
  double max_diameter() const {
    double r = 0.0;
    for (double x : radius) r = r > x ? r : x;
    return 2.0 * r;
  }
  /// Whether any particle's size differs from its species' `diameter` (a distribution, or sizes read from a file):
  /// then the sizes are state that files and checkpoints must carry.
  bool has_own_sizes(const std::vector<Species>& s) const {
    for (std::size_t i = 0; i < size(); ++i) {
      if (2.0 * radius[i] != s[static_cast<std::size_t>(species[i])].diameter) return true;
    }
    return false;
  }

  Vec<Dim> pos(std::size_t i) const {
    Vec<Dim> v;
    for (int a = 0; a < Dim; ++a) v[a] = coord(a)[i];
    return v;
  }
  Vec<Dim> vel(std::size_t i) const {
    Vec<Dim> v;
    for (int a = 0; a < Dim; ++a) v[a] = velocity(a)[i];
    return v;
  }
  Spin<Dim> spin(std::size_t i) const {
    if constexpr (Dim == 2) {
      return this->omega[i];
    } else {
      return {this->omega_x[i], this->omega_y[i], this->omega_z[i]};
    }
  }
  void set_spin(std::size_t i, Spin<Dim> w) {
    if constexpr (Dim == 2) {
      this->omega[i] = w;
    } else {
      this->omega_x[i] = w.x;
      this->omega_y[i] = w.y;
      this->omega_z[i] = w.z;
    }
  }

  /// Reorder every attribute so that new slot k holds old slot order[k]; slots that `order` does not name are
  /// dropped (a selection, e.g. the particles that stay after some left the domain).
  void permute(const std::vector<std::size_t>& order);
  /// Ascending id: the canonical storage order a solver starts from, so that a run depends on the particles and
  /// not on how they were stored when handed over (settled in memory, read from a CSV in any row order).
  void sort_by_id();
  /// The slots in ascending id (one pass when the ids are dense, as a bed numbered from 0 and its feed are).
  std::vector<std::uint32_t> slots_in_id_order() const;
  void clear() {
    for_each_array([](const std::string&, auto& a, ArrayRole) { a.clear(); });
  }

 private:
  bool fluid_arrays_ = true;
};

extern template struct ParticleStore<2>;
extern template struct ParticleStore<3>;

}  // namespace fluidbed
