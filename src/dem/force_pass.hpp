#pragma once
// The force pass of DemSolver (Eqs. 1-9 over the neighbour list and the walls), included by the units that compile
// it for one dimension and one kind of box each (forces_*.cpp), so that the build shares its many instantiations
// among its cores.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <type_traits>

#include <omp.h>

#include "core/error.hpp"
#include "core/team.hpp"
#include "dem/dem_solver.hpp"
#include "dem/growth.hpp"
#include "dem/kernel_support.hpp"

namespace fluidbed {

using dem_kernel::AxisPtrs;
using dem_kernel::axis_ptrs;

template <int Dim>
template <bool Periodic>
double DemSolver<Dim>::compute_forces_on(double dt) {
  // The contact law is chosen here, once per evaluation; the loops below are compiled for it.
  // With one species every contact has the same diameter: the largest overlap fraction is the largest overlap over
  // it, taken once after the loops; only a mixture pays for a division per contact (5% of the force loop).
  // Particles of their own sizes take the mixed loop (overlap per contact) with the dashpot per pair.
  const bool mixed = config_.n_species() > 1;
  const bool sized = sized_;
  return with_contact_law(config_.contact, [&]<class Law>(Law) {
    if (sized) return compute_forces_of<Law, true, Periodic, true>(dt);
    return mixed ? compute_forces_of<Law, true, Periodic, false>(dt) : compute_forces_of<Law, false, Periodic, false>(dt);
  });
}

// One force evaluation's constants and raw pointers, hoisted out of the loops once, with the pointwise functions
// (the release of one ended pair, one pair contact, one wall contact) and the per-block and per-particle loops that
// apply them; compute_forces_of runs those loops in its parallel regions. All are forced inline: left to itself GCC
// calls the pair and the wall contact out of line (they pass its size limits), a call per contact and per wall
// that the loops written in one function did not pay.
template <int Dim>
template <class Law, bool Mixed, bool Periodic, bool Sized>
struct DemSolver<Dim>::ForcePass {
  static constexpr int NS = kSpinComponents<Dim>;
  // Only the paper's constant dashpot depends on the species' mass; the other dampings read m_eff per contact.
  static constexpr bool kSizedDashpot = Sized && std::is_same_v<typename Law::DampingPart, PaperDamping>;
  static constexpr double kSide[2] = {1.0, -1.0};

  DemSolver& s;
  double dt;
  std::size_t ns;
  Vec<Dim> L;
  std::array<bool, 2 * Dim> wall_on{};
  AxisPtrs<Dim> X, V, F;
  AxisPtrs<NS> W, T;
  const double* R;
  const double* M;
  const double* IINV;
  const std::uint32_t* partner;
  const std::uint32_t* upper;
  // The springs by record: of the last evaluation (read), of this one (written).
  const Vec<Dim>* spring_in = nullptr;
  const Spin<Dim>* roll_in = nullptr;
  Vec<Dim>* spring_out = nullptr;
  Spin<Dim>* roll_out = nullptr;
  // The contacts' records, for pass 2: set once pass 1 has sized them.
  const Vec<Dim>* cforce = nullptr;
  const Spin<Dim>* ctorque = nullptr;

  ForcePass(DemSolver& solver, double h)
      : s(solver),
        dt(h),
        ns(solver.config_.n_species()),
        L(solver.config_.domain.template extent<Dim>()),
        X(axis_ptrs<Dim>([&](int a) -> auto& { return solver.p_.coord(a); }, Dim)),
        V(axis_ptrs<Dim>([&](int a) -> auto& { return solver.p_.velocity(a); }, Dim)),
        F(axis_ptrs<Dim>([&](int a) -> auto& { return solver.p_.force(a); }, Dim)),
        W(axis_ptrs<NS>([&](int c) -> auto& { return solver.p_.spin_component(c); }, NS)),
        T(axis_ptrs<NS>([&](int c) -> auto& { return solver.p_.torque_component(c); }, NS)),
        R(solver.p_.radius.data()),
        M(solver.p_.mass.data()),
        IINV(solver.p_.inv_inertia.data()),
        partner(solver.nbr_.partner.data()),
        upper(solver.upper_offset_.data()) {
    const WallConfig& walls = solver.config_.walls;
    for (int w = 0; w < 2 * Dim; ++w) wall_on[static_cast<std::size_t>(w)] = walls.enabled(w / 2, w % 2);
  }

  [[gnu::always_inline]] Vec<Dim> pos(std::size_t i) const {
    Vec<Dim> v;
    for (int a = 0; a < Dim; ++a) v[a] = X[a][i];
    return v;
  }
  [[gnu::always_inline]] Vec<Dim> vel(std::size_t i) const {
    Vec<Dim> v;
    for (int a = 0; a < Dim; ++a) v[a] = V[a][i];
    return v;
  }
  [[gnu::always_inline]] Spin<Dim> spin(std::size_t i) const {
    if constexpr (Dim == 2) {
      return W[0][i];
    } else {
      return Vec3{W[0][i], W[1][i], W[2][i]};
    }
  }
  // Ai et al. 2011 Eq. 17: the rolling inertia of one partner, I + m r^2.
  [[gnu::always_inline]] double roll_inertia(std::size_t i) const { return 1.0 / IINV[i] + M[i] * R[i] * R[i]; }
  [[gnu::always_inline]] Vec<Dim> separation(const Vec<Dim>& xi, std::size_t j) const {
    Vec<Dim> dx = pos(j) - xi;
    if constexpr (Periodic) dx = s.periodic_.min_image(dx);  // the partner's nearest image
    return dx;
  }

  /// Pass 1, first part, for block b (particles lo .. hi): the touching pairs of particles lo .. hi into the block's
  /// compact array, each with the record that holds its spring (the last evaluation's, or those a new list was
  /// given), and the pairs apart whose springs are held released.
  [[gnu::always_inline]] void gather_touching(std::size_t b, std::size_t lo, std::size_t hi) const {
    std::vector<Contact>& found = s.contacts_[b];
    Contact* out = found.data();
    std::size_t used = 0;
    std::uint32_t sink = 0;  // where a touching pair's release goes
    for (std::size_t i = lo; i < hi; ++i) {
      // Room for every entry of i (the writes below are unconditional); grown by an eighth (dem/growth.hpp).
      if (found.size() < used + (upper[i + 1] - upper[i])) {
        resize_with_room(found, used + (upper[i + 1] - upper[i]) + 64);
        out = found.data();
      }
      const Vec<Dim> xi = pos(i);
      const double ri = R[i];
      // The end read once: the stores below could alias it for all the compiler knows.
      for (std::size_t u = upper[i], u_end = upper[i + 1]; u < u_end; ++u) {
        const std::size_t k = s.upper_entry_[u];
        const std::size_t j = partner[k];
        const Vec<Dim> dx = separation(xi, j);
        const double rsum = ri + R[j];
        const bool touching = !(dot(dx, dx) >= rsum * rsum);
        // The entry of the lower slot is the record's side 0: its record is e / 2.
        const std::uint32_t e = s.entry_contact_[k];
        out[used] = Contact{static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(u), e >> 1};
        used += static_cast<std::size_t>(touching);
        // A pair apart releases its record (both entries zeroed; a no-op where it held none) without a branch:
        // in a fluidized bed, where contacts begin and end all the time, a branch on either test is taken at
        // random, and GCC turns a select of the two entries back into one. The mask goes through an empty asm,
        // so the compiler cannot tell that it is all ones or zero: the store reaches the partner's entry when
        // the pair is apart and a local word when it touches.
        std::uintptr_t apart = 0 - static_cast<std::uintptr_t>(!touching);
        asm("" : "+r"(apart));
        s.entry_contact_[k] = e & ~static_cast<std::uint32_t>(apart);
        const auto here = reinterpret_cast<std::uintptr_t>(&sink);
        const auto there = reinterpret_cast<std::uintptr_t>(&s.entry_contact_[s.upper_mirror_[u]]);
        *reinterpret_cast<std::uint32_t*>(here ^ ((here ^ there) & apart)) = 0u;
      }
    }
    s.contact_count_[b] = used;
  }

  // Pass 1, second part, a block of touching pairs at a time: their kinematics gathered into lanes (structure of
  // arrays), the law over the lanes in one loop with no branch (contact_law.hpp writes its cases as selects), which
  // the compiler turns into vector code, then the results scattered to the pair's records. Each lane
  // computes what the pair's own evaluation would, operation for operation, so the bits do not depend on the
  // block or the lane a pair lands in.
  static constexpr std::size_t kBlock = 32;
  // Per-lane contact parameters only where they differ between pairs (several species, or the paper's dashpot on
  // particles of their own sizes); otherwise every lane reads the one entry.
  static constexpr bool kLaneParams = Mixed || kSizedDashpot;
  // The rolling inertia (Ai et al. 2011 Eq. 17) is read by the rolling spring's dashpot only.
  static constexpr bool kRollInertia = Law::kRollingHistory;
  static constexpr int kParamFields = sizeof(ContactParams) / sizeof(double);
  static_assert(sizeof(ContactParams) == kParamFields * sizeof(double), "ContactParams holds doubles only");
  using ParamWords = std::array<double, kParamFields>;
  struct Lanes {
    double dx[Dim][kBlock], dv[Dim][kBlock], wi[NS][kBlock], wj[NS][kBlock];
    double ri[kBlock], rj[kBlock], mi[kBlock], mj[kBlock], ii[kBlock], ij[kBlock];
    double xi[Dim][kBlock], roll[NS][kBlock];  // the springs, in and out
    double f[Dim][kBlock], tq_i[NS][kBlock], tq_j[NS][kBlock], overlap[kBlock];
    // The parameters by field, as the other lanes (an array of the structs keeps GCC from vectorising the loop).
    double params[kLaneParams ? kParamFields : 1][kBlock];
  };

  template <class V, int N>
  [[gnu::always_inline]] static V lane(const double (&a)[N][kBlock], std::size_t c) {
    if constexpr (std::is_same_v<V, double>) {
      return a[0][c];
    } else if constexpr (V::dim == 2) {
      return V{a[0][c], a[1][c]};
    } else {
      return V{a[0][c], a[1][c], a[2][c]};
    }
  }
  template <class V, int N>
  [[gnu::always_inline]] static void set_lane(double (&a)[N][kBlock], std::size_t c, const V& v) {
    if constexpr (std::is_same_v<V, double>) {
      a[0][c] = v;
    } else {
      a[0][c] = v.x;
      a[1][c] = v.y;
      if constexpr (V::dim == 3) a[2][c] = v.z;
    }
  }

  /// The pairs ct[0 .. n) into the lanes: separation, relative velocity, spins, sizes, springs (and parameters).
  [[gnu::always_inline]] void gather_pairs(const Contact* ct, std::size_t n, Lanes& L) const {
    for (std::size_t c = 0; c < n; ++c) {
      const std::size_t i = ct[c].i, k = s.upper_entry_[ct[c].u];
      const std::size_t j = partner[k];
      set_lane(L.dx, c, separation(pos(i), j));
      set_lane(L.dv, c, vel(i) - vel(j));
      set_lane(L.wi, c, spin(i));
      set_lane(L.wj, c, spin(j));
      L.ri[c] = R[i];
      L.rj[c] = R[j];
      if constexpr (Law::kNeedsPairSize) {
        L.mi[c] = M[i];
        L.mj[c] = M[j];
      }
      if constexpr (kRollInertia) {
        L.ii[c] = roll_inertia(i);
        L.ij[c] = roll_inertia(j);
      }
      // The spring in the pair's record (record 0: +0, a new contact).
      set_lane(L.xi, c, spring_in[ct[c].record]);
      if constexpr (Law::kRollingHistory) set_lane(L.roll, c, roll_in[ct[c].record]);
      if constexpr (kLaneParams) {
        const std::size_t pair =
            Mixed ? static_cast<std::size_t>(s.p_.species[i]) * ns + static_cast<std::size_t>(s.p_.species[j]) : 0;
        ContactParams pp = s.pair_params_[pair];
        if constexpr (kSizedDashpot) {
          // Eq. 8 on this pair's reduced mass: the restitution of the input for every pair of sizes.
          pp.eta_n = s.pair_damping_per_root_mass_[pair] * std::sqrt(reduced_mass(M[i], M[j]));
          pp.eta_t = pp.eta_n;
        }
        const ParamWords words = std::bit_cast<ParamWords>(pp);
        for (int f = 0; f < kParamFields; ++f) L.params[f][c] = words[static_cast<std::size_t>(f)];
      }
    }
  }

  /// Eqs. 2-9 (and the rolling torque) over lanes 0 .. n: the force on the lower slot, both torques, the springs.
  [[gnu::always_inline]] void pair_law(Lanes& L, std::size_t n) const {
    const ContactParams& common = s.pair_params_[0];
    for (std::size_t c = 0; c < n; ++c) {
      if constexpr (kLaneParams) {
        ParamWords words;
        for (int f = 0; f < kParamFields; ++f) words[static_cast<std::size_t>(f)] = L.params[f][c];
        pair_lane(std::bit_cast<ContactParams>(words), L, c);
      } else {
        pair_lane(common, L, c);
      }
    }
  }

  /// Lane c of pair_law, with the pair's parameters p.
  [[gnu::always_inline]] void pair_lane(const ContactParams& p, Lanes& L, std::size_t c) const {
    const double h = dt;
    const Vec<Dim> dx = lane<Vec<Dim>>(L.dx, c);
    const double ri = L.ri[c], rj = L.rj[c];
    const double d2 = dot(dx, dx);
    const double rsum = ri + rj;
    const double d = std::sqrt(d2);
    const double inv_d = 1.0 / d;
    const Vec<Dim> nrm = inv_d * dx;
    const double overlap = rsum - d;
    // Lever arms to the contact point x_i + (r_i - overlap / 2) n, the same point seen from j: with them the
    // pair's torques balance the moment of its forces and an isolated pair keeps its angular momentum, spin
    // included (the full radii would change it in proportion to the overlap).
    const double ai = ri - 0.5 * overlap, aj = rj - 0.5 * overlap;
    const Spin<Dim> wi = lane<Spin<Dim>>(L.wi, c), wj = lane<Spin<Dim>>(L.wj, c);
    // Velocity of i's contact point relative to j's; symmetric in (i, j) up to the sign, bit for bit.
    const Vec<Dim> v_rel = lane<Vec<Dim>>(L.dv, c) + cross(wi * ai + wj * aj, nrm);
    ContactKinematics<Dim> kin{nrm, overlap, v_rel};
    if constexpr (Law::kNeedsPairSize) {
      kin.r_eff = ri * rj / rsum;
      kin.m_eff = L.mi[c] * L.mj[c] / (L.mi[c] + L.mj[c]);
      if constexpr (kRollInertia) kin.i_roll = 1.0 / (1.0 / L.ii[c] + 1.0 / L.ij[c]);
    }
    Vec<Dim> xi = lane<Vec<Dim>>(L.xi, c);
    const ContactForce<Dim> cf = Law::template force<Dim>(p, kin, h, xi);
    set_lane(L.xi, c, xi);
    set_lane(L.f, c, cf.f);
    // Eq. 9: the torque of the tangential force about each centre, a (n x f_t) with the partner's own lever
    // arm; n x f_t is the same for both partners ((-n) x (-f_t) = n x f_t).
    const Spin<Dim> tq = cross(nrm, cf.f_t);
    Spin<Dim> tq_i = ai * tq, tq_j = aj * tq;
    if constexpr (Law::kRolling) {
      // The rolling torque acts on i and, reversed, on j (Ai et al. 2011 Eq. 11: w_r = omega_i - omega_j).
      Spin<Dim> m_k = Law::kRollingHistory ? lane<Spin<Dim>>(L.roll, c) : Spin<Dim>{};
      const Spin<Dim> tr = Law::template rolling_torque<Dim>(p, kin, cf, wi - wj, h, m_k);
      if constexpr (Law::kRollingHistory) set_lane(L.roll, c, m_k);
      tq_i += tr;
      tq_j -= tr;
    }
    set_lane(L.tq_i, c, tq_i);
    set_lane(L.tq_j, c, tq_j);
    L.overlap[c] = overlap;
  }

  /// The lanes back: pair c of the block into record g0 + c (force, torques, springs), named by both its entries.
  [[gnu::always_inline]] void scatter_pairs(const Contact* ct, std::size_t n, std::size_t g0, const Lanes& L,
                                            double& max_ov, double& max_frac) const {
    for (std::size_t c = 0; c < n; ++c) {
      const std::size_t k = s.upper_entry_[ct[c].u];
      const std::size_t km = s.upper_mirror_[ct[c].u];
      const std::size_t g = g0 + c;
      spring_out[g] = lane<Vec<Dim>>(L.xi, c);
      if constexpr (Law::kRollingHistory) roll_out[g] = lane<Spin<Dim>>(L.roll, c);
      s.entry_contact_[k] = static_cast<std::uint32_t>(2 * g);
      s.entry_contact_[km] = static_cast<std::uint32_t>(2 * g + 1);
      // Component by component: a whole-vector copy lets GCC spill the sum to the stack in 8-byte halves and read
      // it back 16 bytes at once, a load that no store can forward (a stall of the pass's every contact).
      Vec<Dim>& rec = s.contact_force_[g];
      for (int a = 0; a < Dim; ++a) rec[a] = L.f[a][c];
      s.contact_torque_[2 * g] = lane<Spin<Dim>>(L.tq_i, c);
      s.contact_torque_[2 * g + 1] = lane<Spin<Dim>>(L.tq_j, c);
      const double overlap = L.overlap[c];
      max_ov = std::max(max_ov, overlap);
      // Judged against the smaller partner: its diameter sets how deep the pair can sink before the contact is
      // no longer a small perturbation of two touching spheres.
      if constexpr (Mixed) max_frac = std::max(max_frac, overlap / (2.0 * std::min(L.ri[c], L.rj[c])));
    }
  }

  /// Pass 1, second part: the touching pairs ct[0 .. n) into records g0, g0 + 1, ..., a block at a time.
  void pair_contacts(const Contact* ct, std::size_t n, std::size_t g0, double& max_ov, double& max_frac) const {
    Lanes L;
    for (std::size_t c0 = 0; c0 < n; c0 += kBlock) {
      const std::size_t m = std::min(kBlock, n - c0);
      gather_pairs(ct + c0, m, L);
      pair_law(L, m);
      scatter_pairs(ct + c0, m, g0 + c0, L, max_ov, max_frac);
    }
  }

  /// Pass 2: particle i (at xi, radius ri, its wall springs or null) against plane wall w = 2 axis + side, added
  /// to its force f and torque.
  template <int w>
  [[gnu::always_inline]] void wall_contact(std::size_t i, const Vec<Dim>& xi, double ri, Vec<Dim>* springs, Vec<Dim>& f, Spin<Dim>& torque,
                    double& max_ov, double& max_frac) const {
    constexpr int a = w / 2;
    constexpr bool high = w % 2 == 1;
    if (!wall_on[static_cast<std::size_t>(w)]) return;
    const double overlap = high ? ri - (L[a] - xi[a]) : ri - xi[a];
    if (overlap <= 0.0) {
      if (springs) {
        Vec<Dim>& sp = springs[w];
        bool held = false;
        for (int c = 0; c < Dim; ++c) held = held || sp[c] != 0.0;
        if (held) sp = Vec<Dim>{};
      }
      if constexpr (Law::kRollingHistory) s.wall_roll_[i * (2 * Dim) + w] = Spin<Dim>{};
      return;
    }
    Vec<Dim> nrm{};
    nrm[a] = high ? 1.0 : -1.0;
    Vec<Dim> xi_w = springs ? springs[w] : Vec<Dim>{};
    const double lever = ri - overlap;  // to the contact point on the wall plane
    // Velocity, spin and species are read only here, by the few particles touching a wall.
    const Vec<Dim> v_rel = vel(i) + cross(spin(i) * lever, nrm);
    const std::size_t sw = Mixed ? static_cast<std::size_t>(s.p_.species[i]) : 0;
    ContactKinematics<Dim> kin{nrm, overlap, v_rel};
    if constexpr (Law::kNeedsPairSize) {
      kin.r_eff = ri;
      kin.m_eff = M[i];
      if constexpr (Law::kRolling) kin.i_roll = roll_inertia(i);
    }
    const ContactForce<Dim> cf = [&] {
      if constexpr (kSizedDashpot) {
        ContactParams wp = s.wall_params_[sw];
        wp.eta_n = s.wall_damping_per_root_mass_[sw] * std::sqrt(M[i]);  // Eq. 8, the wall fixed
        wp.eta_t = wp.eta_n;
        return Law::template force<Dim>(wp, kin, dt, xi_w);
      } else {
        return Law::template force<Dim>(s.wall_params_[sw], kin, dt, xi_w);
      }
    }();
    if (springs) {
      springs[w] = xi_w;
    } else if (!WallSprings<Dim>::is_plus_zero(xi_w)) {
      s.new_wall_springs_[team_slot().index].push_back({i, w, xi_w});
    }
    f += cf.f;
    torque += lever * cross(nrm, cf.f_t);
    if constexpr (Law::kRolling) {
      Spin<Dim> unused{};
      Spin<Dim>& m_k = Law::kRollingHistory ? s.wall_roll_[i * (2 * Dim) + w] : unused;
      torque += Law::template rolling_torque<Dim>(s.wall_params_[sw], kin, cf, spin(i), dt, m_k);
    }
    max_ov = std::max(max_ov, overlap);
    if constexpr (Mixed) max_frac = std::max(max_frac, overlap / (2.0 * ri));
  }

  /// Pass 2 for particle i: the sum of its own entries in list order (independent of the thread count), then its
  /// walls, into its force and torque.
  [[gnu::always_inline]] void sum_particle(std::size_t i, double& max_ov, double& max_frac) const {
    const Vec<Dim> xi = pos(i);
    const std::int32_t rec = s.walls_.record(i);
    Vec<Dim>* const springs = rec >= 0 ? s.walls_.springs(rec).data() : nullptr;
    const double ri = R[i];
    Vec<Dim> f{};
    Spin<Dim> torque{};
    // Entries not in contact name the zero record: adding +0 or -0 leaves every partial sum as it was, so the
    // sums are those over the touching entries in list order. The partner's side takes -f, an exact negation.
    for (std::size_t k = s.nbr_.offset[i]; k < s.nbr_.offset[i + 1]; ++k) {
      const std::uint32_t e = s.entry_contact_[k];
      f += kSide[e & 1u] * cforce[e >> 1];
      torque += ctorque[e];
    }
    // Plane walls: the same law against a fixed body of infinite mass. A disabled wall never holds a spring.
    // A particle clear of every wall (most of the bed) only needs its springs checked for zero: the test on
    // the position comes first, and the springs are read through raw pointers, not per-wall accessors.
    // Unrolled at compile time (wall w = 2 a + side, in that order): axis, side and normal are constants.
    [&]<int... w>(std::integer_sequence<int, w...>) __attribute__((always_inline)) {
      (wall_contact<w>(i, xi, ri, springs, f, torque, max_ov, max_frac), ...);
    }(std::make_integer_sequence<int, 2 * Dim>{});
    for (int a = 0; a < Dim; ++a) F[a][i] = f[a];
    if constexpr (Dim == 2) {
      T[0][i] = torque;
    } else {
      for (int c = 0; c < 3; ++c) T[c][i] = torque[c];
    }
  }
};

template <int Dim>
template <class Law, bool Mixed, bool Periodic, bool Sized>
double DemSolver<Dim>::compute_forces_of(double dt) {
  // A restored or copied list, or one grown by an insertion: linked, its springs into records.
  if (!marked_ || upper_offset_.size() != p_.size() + 1 || linked_entries_ != nbr_.entries()) link_mirrors();
  if (Law::kRollingHistory && roll_spring_.size() != spring_.size()) {
    roll_spring_.assign(spring_.size(), Spin<Dim>{});  // springs restored from a run without rolling springs
  }
  // Only the owned particles take forces; a ghost's pairs with owned particles are in their owners' half lists (the
  // owned slots come first), and its pairs with other ghosts are its own rank's business.
  const std::size_t n = n_owned_;
  if (Law::kRollingHistory && wall_roll_.size() != n * 2 * Dim) wall_roll_.assign(n * 2 * Dim, Spin<Dim>{});
  ForcePass<Law, Mixed, Periodic, Sized> pass(*this, dt);
  double max_ov = 0.0;
  double max_frac = 0.0;  // overlap over the contact's own diameter (the dem.max_overlap_fraction test)
  const auto sn = static_cast<std::ptrdiff_t>(n);
  // Pass 1: every pair once, from its lower slot. The law is antisymmetric bit for bit, so writing -f and -xi to
  // the partner's entry gives exactly what the partner would have computed itself; no two pairs share an entry,
  // so threads never write the same memory.
  // Most list entries do not touch (about 0.75 contacts per particle against 6 entries in a packed 2D bed), so the
  // pass runs in two parts per block of particles: a distance test writes the touching pairs into a compact array
  // without a branch, releasing (zeroing) the entries of the last evaluation's contacts that have ended; the law
  // runs over that array only. Entries of pairs not in contact stay zero, so the gathering pass below is unchanged
  // and the result is the same bit for bit. The blocks (one per thread) only share out the work: a pair's
  // evaluation does not depend on the block that finds it.
  const int max_threads = omp_get_max_threads();
  const auto nb = static_cast<std::size_t>(max_threads);
  if (contacts_.size() != nb) {
    contacts_.assign(nb, {});
    contact_count_.assign(nb, 0);
  }
#pragma omp parallel num_threads(max_threads)
  {
    const auto [t0, nt] = team_slot();
    for (std::size_t b = t0; b < nb; b += nt) pass.gather_touching(b, n * b / nb, n * (b + 1) / nb);
  }
  // The contacts' records, numbered block after block from 1 (record 0 stays zero: the entries not in contact).
  std::vector<std::size_t>& base = contact_base_;
  base.assign(nb + 1, 1);
  for (std::size_t b = 0; b < nb; ++b) base[b + 1] = base[b] + contact_count_[b];
  resize_with_room(contact_force_, base[nb]);
  resize_with_room(contact_torque_, 2 * base[nb]);
  // This evaluation's springs by record, record 0 the +0 of the pairs not in contact. Each of the two arrays that
  // take turns keeps room for growth (dem/growth.hpp), so that a compacting bed does not reallocate, and fault
  // its pages in, at every evaluation.
  resize_with_room(spring_next_, base[nb]);
  spring_next_[0] = Vec<Dim>{};
  if (Law::kRollingHistory) {
    resize_with_room(roll_spring_next_, base[nb]);
    roll_spring_next_[0] = Spin<Dim>{};
  }
  pass.spring_in = spring_.data();
  pass.roll_in = roll_spring_.data();
  pass.spring_out = spring_next_.data();
  pass.roll_out = roll_spring_next_.data();
  // The zero record is -0: adding it leaves every sum as it was, -0 and +0 included (x + (-0) = x for every x),
  // so a particle's sum is that of its contacts alone, whatever other pairs its list holds (a list built at
  // another time, or on another rank, holds other pairs out of contact).
  contact_force_[0] = -Vec<Dim>{};
  contact_torque_[0] = contact_torque_[1] = -Spin<Dim>{};
#pragma omp parallel num_threads(max_threads) reduction(max : max_ov, max_frac)
  {
    const auto [t0, nt] = team_slot();
    for (std::size_t b = t0; b < nb; b += nt) {
      pass.pair_contacts(contacts_[b].data(), contact_count_[b], base[b], max_ov, max_frac);
    }
  }
  spring_.swap(spring_next_);
  roll_spring_.swap(roll_spring_next_);
  marked_ = true;
  pass.cforce = contact_force_.data();
  pass.ctorque = contact_torque_.data();
  // A particle that touches a wall without a record of springs (all +0 until now) leaves its new springs here, one
  // list per thread; they get their records after the pass (few particles a step, in no particular order: each
  // (particle, wall) is set once).
  const int threads = omp_get_max_threads();
  if (new_wall_springs_.size() < static_cast<std::size_t>(threads)) new_wall_springs_.resize(static_cast<std::size_t>(threads));
  // Pass 2: each particle sums its own entries in list order (independent of the thread count), then its walls.
  // Each thread takes its own copy of the pass: the shared one the compiler reloads per particle (the wall springs'
  // push_back could change it), 4% more instructions in this loop.
#pragma omp parallel for schedule(static) reduction(max : max_ov, max_frac) firstprivate(pass)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) pass.sum_particle(static_cast<std::size_t>(ii), max_ov, max_frac);
  for (auto& list : new_wall_springs_) {
    for (const NewWallSpring& s : list) walls_.set(s.i, s.wall, s.xi);
    list.clear();
  }
  max_overlap_ = max_ov;
  max_overlap_fraction_ = Mixed || n == 0 ? max_frac : max_ov / (2.0 * p_.radius[0]);
  return max_ov;
}

}  // namespace fluidbed
