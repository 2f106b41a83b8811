#pragma once
// Cundall-Strack linear spring, dashpot and Coulomb slider (paper Eqs. 2-8) as pure functions.
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
};

template <int Dim>
struct ContactForce {
  Vec<Dim> f;    ///< force on i, N
  Vec<Dim> f_t;  ///< its tangential part, N (gives the torque)
};

/// The stored tangential spring turned into the tangent plane of the current normal n, keeping its length
/// (the contact frame rotates with the pair; LAMMPS gran/hooke/history). In 2D the plane is the line of
/// t = (-n_y, n_x), so the rotated spring is +-|xi| t: one square root, no division. In 3D the spring is
/// projected onto the plane and scaled back to its length.
inline void rotate_into_tangent_plane(Vec2& xi, Vec2 n) {
  const double xi_len2 = norm2(xi);
  if (xi_len2 > 0.0) {
    const Vec2 t{-n.y, n.x};
    const double along = dot(xi, t);
    xi = along > 0.0 ? std::sqrt(xi_len2) * t : (along < 0.0 ? -std::sqrt(xi_len2) * t : Vec2{});
  }
}
inline void rotate_into_tangent_plane(Vec3& xi, Vec3 n) {
  const double xi_len2 = norm2(xi);
  if (xi_len2 > 0.0) {
    const Vec3 proj = xi - dot(xi, n) * n;
    const double p_len2 = norm2(proj);
    xi = p_len2 > 0.0 ? std::sqrt(xi_len2 / p_len2) * proj : Vec3{};
  }
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
  if (overlap >= travel) return vn;
  // Approaching (vn > 0): vn + overlap / dt; separating (vn < 0): vn * tau = -overlap / dt.
  return vn > 0.0 ? vn + overlap / dt : -overlap / dt;
}

/// Eqs. 2-7 with the tangential spring accumulated over the life of the contact (Cundall & Strack 1979).
/// `xi` is the tangential spring elongation; it is rotated into the current tangent plane, advanced by the
/// tangential slip, and truncated at the Coulomb limit so that spring plus dashpot equals the sliding force
/// (the treatment of LAMMPS gran/hooke/history). The expressions are antisymmetric under exchange of the
/// partners, bit for bit, so that both partners of a pair evaluate the same contact with opposite signs.
template <int Dim>
inline ContactForce<Dim> linear_spring_dashpot(const ContactParams& p, const ContactKinematics<Dim>& c, double dt,
                                               Vec<Dim>& xi) {
  const double vn = dot(c.v_rel, c.n);
  const Vec<Dim> v_t = c.v_rel - vn * c.n;  // Eqs. 4-5
  // The normal force lies along n; its signed size is the same from both partners, which keeps the law
  // antisymmetric and spares a square root in the Coulomb limit below.
  const double fn = -p.k_n * c.overlap - p.eta_n * normal_dashpot_velocity(c.overlap, vn, dt);  // Eq. 2
  const Vec<Dim> f_n = fn * c.n;

  rotate_into_tangent_plane(xi, c.n);
  xi += dt * v_t;
  Vec<Dim> f_t = -p.k_t * xi - p.eta_t * v_t;  // Eq. 3

  const double ft_max = p.mu * std::abs(fn);  // Eq. 6
  const double ft2 = norm2(f_t);
  if (ft2 > ft_max * ft_max) {
    f_t = (ft_max / std::sqrt(ft2)) * f_t;  // Eq. 7: slide at the Coulomb limit
    xi = (-1.0 / p.k_t) * (f_t + p.eta_t * v_t);
  }
  return {f_n + f_t, f_t};
}

}  // namespace fluidbed
