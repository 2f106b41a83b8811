#pragma once
// TVD flux limiters and the limited face value of a cell-centred scalar (paper section 2.2.1).
// Inline: they sit in the innermost convection loops.
#include <algorithm>
#include <cmath>

namespace fluidbed::tfm {

/// Flux limiter psi(r); Upwind (psi = 0) is kept for comparison and first-order runs.
enum class Limiter { Upwind, Minmod, VanLeer, Superbee };

/// Superbee limiter of Roe (1985): psi = max(0, min(2r, 1), min(r, 2)).
inline double superbee(double r) { return std::max({0.0, std::min(2.0 * r, 1.0), std::min(r, 2.0)}); }
/// Minmod limiter: psi = max(0, min(r, 1)).
inline double minmod(double r) { return std::max(0.0, std::min(r, 1.0)); }
/// van Leer limiter (1974): psi = (r + |r|) / (1 + |r|).
inline double van_leer(double r) { return (r + std::abs(r)) / (1.0 + std::abs(r)); }
/// psi(r) of the chosen limiter.
inline double limiter_value(Limiter limiter, double r) {
  switch (limiter) {
    case Limiter::Upwind: return 0.0;
    case Limiter::Minmod: return minmod(r);
    case Limiter::VanLeer: return van_leer(r);
    case Limiter::Superbee: return superbee(r);
  }
  return 0.0;
}

/// High-order correction added to the upwind value on a face:
/// 0.5 psi(r) (phi_D - phi_C) with r = (phi_C - phi_U) / (phi_D - phi_C),
/// where C is the upwind cell, D the downwind cell and U the cell upwind of C.
inline double limited_correction(Limiter limiter, double phi_U, double phi_C, double phi_D) {
  const double up = phi_C - phi_U;
  const double down = phi_D - phi_C;
  // A local extremum or a flat region (r <= 0 or undefined): every TVD limiter falls back to upwind.
  if (up * down <= 0.0) return 0.0;
  return 0.5 * limiter_value(limiter, up / down) * down;
}

/// Face value between cells L (lower index) and R for a face velocity `vel` (positive from L to R).
/// phi_LL lies before L and phi_RR after R; the upwind side is chosen from the sign of vel.
inline double tvd_face_value(Limiter limiter, double vel, double phi_LL, double phi_L, double phi_R, double phi_RR) {
  if (vel >= 0.0) return phi_L + limited_correction(limiter, phi_LL, phi_L, phi_R);
  return phi_R + limited_correction(limiter, phi_RR, phi_R, phi_L);
}

}  // namespace fluidbed::tfm
