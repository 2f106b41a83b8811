#pragma once
// Contact laws as pure functions, composed from parts as LAMMPS's `pair granular` composes them: a normal spring
// (the paper's linear spring, Eqs. 2-8, or Hertz), a normal damping (the paper's constant dashpot, or Tsuji,
// Tanaka & Ishida 1992), a tangential spring (linear with k_t / k_n, or Mindlin) with the Coulomb slider, and a
// rolling resistance (none, a constant directional torque, or the elastic-plastic spring-dashpot; Ai et al.
// 2011). ContactLaw<Normal, Damping, Tangential, Rolling> is the composition; the force loop is templated on it.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/vec.hpp"

namespace fluidbed {

/// Parameters of one kind of contact (a species pair, or a species and a wall).
struct ContactParams {
  double k_n = 800.0;  ///< normal stiffness, N/m
  double k_t = 800.0;  ///< tangential stiffness, N/m
  double eta_n = 0.0;  ///< normal damping, kg/s
  double eta_t = 0.0;  ///< tangential damping, kg/s
  double mu = 0.3;     ///< Coulomb friction coefficient
  double e_star = 0.0;  ///< Hertz: effective Young's modulus E*, 1/E* = sum (1 - nu^2) / E, Pa
  double g_star = 0.0;  ///< Mindlin: effective shear modulus G*, 1/G* = sum 2 (2 - nu)(1 + nu) / E, Pa
  double alpha = 0.0;   ///< Tsuji damping: eta = alpha sqrt(m* dF_n/d delta), from the restitution
  double mu_r = 0.0;    ///< rolling resistance coefficient (Ai et al. 2011), dimensionless
  double eta_r = 0.0;   ///< rolling viscous damping ratio (Ai et al. 2011 Eq. 16)
};

/// Eq. 8: dashpot coefficient that gives restitution e for a linear spring k acting on mass m_eff
/// (the reduced mass of the pair, or the particle mass against a wall).
inline double damping_from_restitution(double m_eff, double k, double e) {
  const double l = std::log(1.0 / e);
  return 2.0 * std::sqrt(m_eff * k) * l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

/// Duration of a linear spring-dashpot contact (time from touch to separation at zero overlap).
inline double contact_duration(double m_eff, double k, double eta) {
  const double w0sq = k / m_eff;
  const double g = eta / (2.0 * m_eff);
  return std::numbers::pi / std::sqrt(w0sq - g * g);
}

/// Paper Table 3 item 5: t_cr = 2 pi sqrt(m/k), the period of one particle on one spring.
inline double critical_time(double m, double k) { return 2.0 * std::numbers::pi * std::sqrt(m / k); }

inline double reduced_mass(double m1, double m2) { return m1 * m2 / (m1 + m2); }

/// Geometry and motion of one contact as seen from particle i.
template <int Dim>
struct ContactKinematics {
  Vec<Dim> n;      ///< unit normal from i towards the partner
  double overlap;  ///< > 0 while in contact, m
  Vec<Dim> v_rel;  ///< velocity of i's contact point relative to the partner's, m/s
  // Filled only for the laws that read them (ContactLaw::kNeedsPairSize): the per-contact sizes.
  double r_eff = 0.0;   ///< R* = r_i r_j / (r_i + r_j), or r_i against a wall, m
  double m_eff = 0.0;   ///< m* = m_i m_j / (m_i + m_j), or m_i against a wall, kg
  double i_roll = 0.0;  ///< rolling inertia of Ai et al. 2011 Eq. 17, kg m^2
};

template <int Dim>
struct ContactForce {
  Vec<Dim> f;        ///< force on i, N
  Vec<Dim> f_t;      ///< its tangential part, N (gives the torque)
  double f_n = 0.0;  ///< signed normal force on i along n (negative: repulsive), N
  double k_n = 0.0;  ///< normal tangent stiffness dF_n / d delta at this overlap, N/m
};

/// Per component a where c holds, else b. The law is written with these selects and no branch, so that the force
/// pass compiles it over a block of contacts into vector code (force_pass.hpp) and no branch waits on a test that
/// the contacts answer at random (slide or stick). Each select picks the value the branch would have computed, so
/// the bits are those of the branching form; the value not picked may be inf or NaN.
constexpr double choose(bool c, double a, double b) { return c ? a : b; }
constexpr Vec2 choose(bool c, Vec2 a, Vec2 b) { return {c ? a.x : b.x, c ? a.y : b.y}; }
constexpr Vec3 choose(bool c, Vec3 a, Vec3 b) { return {c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z}; }

/// The stored tangential spring turned into the tangent plane of the current normal n, keeping its length
/// (the contact frame rotates with the pair; LAMMPS gran/hooke/history). In 2D the plane is the line of
/// t = (-n_y, n_x), so the rotated spring is +-|xi| t: one square root, no division. In 3D the spring is
/// projected onto the plane and scaled back to its length. A zero spring stays as it is (signs of zero included).
inline void rotate_into_tangent_plane(Vec2& xi, Vec2 n) {
  const double xi_len2 = norm2(xi);
  const Vec2 t{-n.y, n.x};
  const double along = dot(xi, t);
  const double len = std::sqrt(xi_len2);
  const Vec2 turned = choose(along > 0.0, len * t, choose(along < 0.0, -len * t, Vec2{}));
  xi = choose(xi_len2 > 0.0, turned, xi);
}
inline void rotate_into_tangent_plane(Vec3& xi, Vec3 n) {
  const double xi_len2 = norm2(xi);
  const Vec3 proj = xi - dot(xi, n) * n;
  const double p_len2 = norm2(proj);
  const Vec3 turned = choose(p_len2 > 0.0, std::sqrt(xi_len2 / p_len2) * proj, Vec3{});
  xi = choose(xi_len2 > 0.0, turned, xi);
}

/// Normal velocity for the dashpot of Eq. 2, corrected for a contact that starts or ends inside the step.
/// Eq. 10 samples the force once per step, so a contact that began a fraction a = overlap / (vn dt) of a step
/// before this evaluation has missed the dashpot impulse of that fraction, and one that will end a fraction
/// tau = overlap / (-vn dt) into the step would keep pulling for the whole step. The dashpot of those steps
/// gets the part of the step actually spent in contact; the spring needs no correction (its impulse there is
/// O(overlap) and the symplectic update keeps its energy). This removes the first-order, phase-dependent error
/// of the rebound velocity (2 ln(1/e)/N at N steps per contact) and leaves the O(ln(1/e)^2 / N) decay error
/// of the explicit dashpot (docs/verification-dem.md, test 2).
inline double normal_dashpot_velocity(double overlap, double vn, double dt) {
  const double travel = std::abs(vn) * dt;
  // Approaching (vn > 0): vn + overlap / dt; separating (vn < 0): vn * tau = -overlap / dt.
  return choose(overlap >= travel, vn, choose(vn > 0.0, vn + overlap / dt, -overlap / dt));
}

/// The elastic normal force (repulsive size) and its tangent stiffness dF/d delta.
struct NormalSpring {
  double force;      ///< N
  double stiffness;  ///< N/m
};

/// Paper Eq. 2, spring part: F = k_n delta.
struct LinearNormal {
  static constexpr bool kNeedsPairSize = false;
  static NormalSpring spring(const ContactParams& p, double overlap, double) { return {p.k_n * overlap, p.k_n}; }
};

/// Hertz (1882): F = (4/3) E* a delta with the contact radius a = sqrt(R* delta); dF/d delta = 2 E* a.
struct HertzNormal {
  static constexpr bool kNeedsPairSize = true;
  static NormalSpring spring(const ContactParams& p, double overlap, double r_eff) {
    const double a = std::sqrt(r_eff * overlap);
    return {(4.0 / 3.0) * p.e_star * a * overlap, 2.0 * p.e_star * a};
  }
};

/// Paper Eqs. 2-3 and 8: constant dashpots eta_n, eta_t (Eq. 8 from e on the reduced mass), the normal one with
/// the part-step correction of normal_dashpot_velocity.
struct PaperDamping {
  static constexpr bool kNeedsPairSize = false;
  static double normal(const ContactParams& p, double, double, double overlap, double vn, double dt) {
    return p.eta_n * normal_dashpot_velocity(overlap, vn, dt);
  }
  static double tangential(const ContactParams& p, double, double) { return p.eta_t; }
};

/// Tsuji, Tanaka & Ishida (1992): eta_n = alpha sqrt(m* dF_n/d delta) (for Hertz proportional to delta^(1/4)),
/// eta_t = alpha sqrt(m* k_t). With it the Hertz impact equation has no speed scale left, so the restitution is
/// the same at every impact speed; alpha is found for the requested e (tsuji_alpha, contact_model.hpp).
struct TsujiDamping {
  static constexpr bool kNeedsPairSize = true;
  static double normal(const ContactParams& p, double m_eff, double k_n, double, double vn, double) {
    return p.alpha * std::sqrt(m_eff * k_n) * vn;
  }
  static double tangential(const ContactParams& p, double m_eff, double k_t) { return p.alpha * std::sqrt(m_eff * k_t); }
};

/// Paper Eq. 3, spring part: constant k_t (k_t / k_n of the case).
struct LinearTangential {
  static constexpr bool kNeedsPairSize = false;
  static double stiffness(const ContactParams& p, double, double) { return p.k_t; }
};

/// Mindlin (1949), no-slip: k_t = 8 G* a with a = sqrt(R* delta) (Di Renzo & Di Maio 2004, "HM no-slip").
struct MindlinTangential {
  static constexpr bool kNeedsPairSize = true;
  static double stiffness(const ContactParams& p, double overlap, double r_eff) {
    return 8.0 * p.g_star * std::sqrt(r_eff * overlap);
  }
};

/// The spin components in the tangent plane of n (in 2D the spin, about z, always lies there).
inline double tangent_spin(double w, Vec2) { return w; }
inline Vec3 tangent_spin(Vec3 w, Vec3 n) { return w - dot(w, n) * n; }
inline double spin_length(double w) { return std::abs(w); }
inline double spin_length(Vec3 w) { return norm(w); }
/// A stored rolling torque turned into the current tangent plane, keeping its length (3D; 2D has nothing to turn).
inline void rotate_rolling_spring(double&, Vec2) {}
inline void rotate_rolling_spring(Vec3& m, Vec3 n) { rotate_into_tangent_plane(m, n); }

/// What a rolling part reads: the relative rolling spin w_r (omega_i - omega_j in the tangent plane, Ai et al.
/// 2011 Eq. 11), the repulsive normal force and the normal stiffness of this step.
template <int Dim>
struct RollingInput {
  Spin<Dim> w_r;
  double f_n;  ///< >= 0, N
  double k_n;  ///< N/m
};

/// No rolling resistance (the paper).
struct NoRolling {
  static constexpr bool kEnabled = false;
  static constexpr bool kHistory = false;
  template <int Dim>
  static Spin<Dim> torque(const ContactParams&, const ContactKinematics<Dim>&, const RollingInput<Dim>&, double,
                          Spin<Dim>&) {
    return Spin<Dim>{};
  }
};

/// Ai et al. 2011 model A (constant directional torque, Zhou et al. 1999): M_r = -mu_r R* F_n w_r / |w_r|.
struct ConstantRolling {
  static constexpr bool kEnabled = true;
  static constexpr bool kHistory = false;
  template <int Dim>
  static Spin<Dim> torque(const ContactParams& p, const ContactKinematics<Dim>& c, const RollingInput<Dim>& in, double,
                          Spin<Dim>&) {
    const double w = spin_length(in.w_r);
    return choose(w > 0.0, (-p.mu_r * c.r_eff * in.f_n / w) * in.w_r, Spin<Dim>{});
  }
};

/// Ai et al. 2011 model C (elastic-plastic spring-dashpot): a spring torque M_k accumulated from the relative
/// rotation with k_r = 2.25 k_n mu_r^2 R*^2 (Eq. 13), capped at M_m = mu_r R* F_n (Eq. 14), and a dashpot
/// -C_r w_r with C_r = eta_r 2 sqrt(I_r k_r) (Eqs. 15-17) that is off while the spring is at the cap (f = 0 of
/// Eq. 18), so that steady rolling feels exactly M_m, as with model A, but a contact at rest holds still.
struct EpsdRolling {
  static constexpr bool kEnabled = true;
  static constexpr bool kHistory = true;
  template <int Dim>
  static Spin<Dim> torque(const ContactParams& p, const ContactKinematics<Dim>& c, const RollingInput<Dim>& in,
                          double dt, Spin<Dim>& m_k) {
    const double k_r = 2.25 * in.k_n * p.mu_r * p.mu_r * c.r_eff * c.r_eff;
    rotate_rolling_spring(m_k, c.n);
    m_k = m_k - (k_r * dt) * in.w_r;
    const double m_max = p.mu_r * c.r_eff * in.f_n;
    const double len = spin_length(m_k);
    const bool capped = len > m_max;
    const Spin<Dim> at_cap = choose(len > 0.0, m_max / len, 0.0) * m_k;
    const Spin<Dim> damped = m_k - (p.eta_r * 2.0 * std::sqrt(c.i_roll * k_r)) * in.w_r;
    m_k = choose(capped, at_cap, m_k);
    return choose(capped, at_cap, damped);
  }
};

/// One contact law composed of its four parts. force() is Eqs. 2-7 with the parts' spring and dashpot; the
/// tangential spring `xi` is accumulated over the life of the contact (Cundall & Strack 1979), rotated into the
/// current tangent plane, advanced by the slip and truncated at the Coulomb limit so that spring plus dashpot
/// equals the sliding force (LAMMPS gran/hooke/history). The expressions are antisymmetric under exchange of the
/// partners, bit for bit, so that both partners of a pair evaluate the same contact with opposite signs.
template <class Normal, class Damping, class Tangential, class Rolling>
struct ContactLaw {
  using NormalPart = Normal;
  using DampingPart = Damping;
  using TangentialPart = Tangential;
  using RollingPart = Rolling;
  /// The loop fills ContactKinematics::r_eff, m_eff, i_roll only for laws that read them.
  static constexpr bool kNeedsPairSize =
      Normal::kNeedsPairSize || Damping::kNeedsPairSize || Tangential::kNeedsPairSize || Rolling::kEnabled;
  static constexpr bool kRolling = Rolling::kEnabled;
  static constexpr bool kRollingHistory = Rolling::kHistory;

  template <int Dim>
  static ContactForce<Dim> force(const ContactParams& p, const ContactKinematics<Dim>& c, double dt, Vec<Dim>& xi) {
    const double vn = dot(c.v_rel, c.n);
    const Vec<Dim> v_t = c.v_rel - vn * c.n;  // Eqs. 4-5
    // The normal force lies along n; its signed size is the same from both partners, which keeps the law
    // antisymmetric and spares a square root in the Coulomb limit below.
    const NormalSpring s = Normal::spring(p, c.overlap, c.r_eff);
    const double fn = -s.force - Damping::normal(p, c.m_eff, s.stiffness, c.overlap, vn, dt);  // Eq. 2
    const Vec<Dim> f_n = fn * c.n;

    const double k_t = Tangential::stiffness(p, c.overlap, c.r_eff);
    const double eta_t = Damping::tangential(p, c.m_eff, k_t);
    rotate_into_tangent_plane(xi, c.n);
    xi += dt * v_t;
    Vec<Dim> f_t = -k_t * xi - eta_t * v_t;  // Eq. 3

    const double ft_max = p.mu * std::abs(fn);  // Eq. 6
    const double ft2 = norm2(f_t);
    const bool slides = ft2 > ft_max * ft_max;
    const Vec<Dim> f_slide = (ft_max / std::sqrt(ft2)) * f_t;  // Eq. 7: slide at the Coulomb limit
    xi = choose(slides, choose(k_t > 0.0, (-1.0 / k_t) * (f_slide + eta_t * v_t), Vec<Dim>{}), xi);
    f_t = choose(slides, f_slide, f_t);
    return {f_n + f_t, f_t, fn, s.stiffness};
  }

  /// Rolling torque on i (Rolling part) for relative spin w_rel = omega_i - omega_j (omega_i against a wall),
  /// after force() gave `cf`; `m_k` is the contact's rolling spring (unused without history).
  template <int Dim>
  static Spin<Dim> rolling_torque(const ContactParams& p, const ContactKinematics<Dim>& c, const ContactForce<Dim>& cf,
                                  Spin<Dim> w_rel, double dt, Spin<Dim>& m_k) {
    const RollingInput<Dim> in{tangent_spin(w_rel, c.n), std::max(0.0, -cf.f_n), cf.k_n};
    return Rolling::template torque<Dim>(p, c, in, dt, m_k);
  }
};

/// The paper's law: linear spring, constant dashpots, linear tangential spring, no rolling resistance.
using PaperContactLaw = ContactLaw<LinearNormal, PaperDamping, LinearTangential, NoRolling>;

/// Eqs. 2-7: the paper's law (PaperContactLaw) as one call.
template <int Dim>
inline ContactForce<Dim> linear_spring_dashpot(const ContactParams& p, const ContactKinematics<Dim>& c, double dt,
                                               Vec<Dim>& xi) {
  return PaperContactLaw::force<Dim>(p, c, dt, xi);
}

}  // namespace fluidbed
