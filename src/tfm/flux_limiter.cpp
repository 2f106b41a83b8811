#include "tfm/flux_limiter.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed::tfm {

double superbee(double r) { return std::max({0.0, std::min(2.0 * r, 1.0), std::min(r, 2.0)}); }

double minmod(double r) { return std::max(0.0, std::min(r, 1.0)); }

double van_leer(double r) { return (r + std::abs(r)) / (1.0 + std::abs(r)); }

double limiter_value(Limiter limiter, double r) {
  switch (limiter) {
    case Limiter::Upwind: return 0.0;
    case Limiter::Minmod: return minmod(r);
    case Limiter::VanLeer: return van_leer(r);
    case Limiter::Superbee: return superbee(r);
  }
  return 0.0;
}

double limited_correction(Limiter limiter, double phi_U, double phi_C, double phi_D) {
  const double up = phi_C - phi_U;
  const double down = phi_D - phi_C;
  // A local extremum or a flat region (r <= 0 or undefined): every TVD limiter falls back to upwind.
  if (up * down <= 0.0) return 0.0;
  return 0.5 * limiter_value(limiter, up / down) * down;
}

double tvd_face_value(Limiter limiter, double vel, double phi_LL, double phi_L, double phi_R, double phi_RR) {
  if (vel >= 0.0) return phi_L + limited_correction(limiter, phi_LL, phi_L, phi_R);
  return phi_R + limited_correction(limiter, phi_RR, phi_R, phi_L);
}

}  // namespace fluidbed::tfm
