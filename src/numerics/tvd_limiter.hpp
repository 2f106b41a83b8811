#pragma once
// One TVD flux-limiter family for every convected quantity (gas momentum, TFM momenta and phase fractions):
// the face value is the upwind value plus 0.5 psi(r) (phi_D - phi_C) (Sweby 1984, SIAM J. Numer. Anal. 21:995;
// paper section 2.2.1). Each limiter is also a type, so a loop is compiled once per limiter and the choice is
// made once, outside it (with_limiter), not per face.
#include <algorithm>
#include <cmath>
#include <utility>

namespace fluidbed::tvd {

/// Flux limiter psi(r); Upwind (psi = 0) is kept for comparison and first-order runs.
enum class Limiter { Upwind, Minmod, VanLeer, Superbee };

/// psi = 0: first-order upwind.
struct UpwindLaw {
  static constexpr bool high_order = false;
  static double psi(double /*r*/) { return 0.0; }
};
/// Minmod: psi = max(0, min(r, 1)).
struct MinmodLaw {
  static constexpr bool high_order = true;
  static double psi(double r) { return std::max(0.0, std::min(r, 1.0)); }
};
/// van Leer (1974): psi = (r + |r|) / (1 + |r|).
struct VanLeerLaw {
  static constexpr bool high_order = true;
  static double psi(double r) { return (r + std::abs(r)) / (1.0 + std::abs(r)); }
};
/// Superbee of Roe (1985): psi = max(0, min(2r, 1), min(r, 2)).
struct SuperbeeLaw {
  static constexpr bool high_order = true;
  static double psi(double r) { return std::max({0.0, std::min(2.0 * r, 1.0), std::min(r, 2.0)}); }
};

/// Calls f(Law{}) with the law type of `limiter`: the one run-time switch, taken before a loop.
template <class F>
decltype(auto) with_limiter(Limiter limiter, F&& f) {
  switch (limiter) {
    case Limiter::Minmod: return std::forward<F>(f)(MinmodLaw{});
    case Limiter::VanLeer: return std::forward<F>(f)(VanLeerLaw{});
    case Limiter::Superbee: return std::forward<F>(f)(SuperbeeLaw{});
    case Limiter::Upwind: break;
  }
  return std::forward<F>(f)(UpwindLaw{});
}

/// psi(r) of a limiter chosen at run time (for code outside the hot loops and tests).
inline double psi(Limiter limiter, double r) {
  return with_limiter(limiter, [r](auto law) { return decltype(law)::psi(r); });
}

/// High-order correction added to the upwind value on a face: 0.5 psi(r) (phi_D - phi_C),
/// r = (phi_C - phi_U) / (phi_D - phi_C), C the upwind cell, D the downwind one, U the cell upwind of C.
/// Computed, then kept or dropped by a select rather than a branch, so that loops whose extrema fall at random do
/// not mispredict (the discarded value may be inf or NaN; no floating-point trap is enabled).
template <class Law>
[[gnu::always_inline]] inline double correction(double phi_U, double phi_C, double phi_D) {
  if constexpr (!Law::high_order) {
    return 0.0;
  } else {
    const double up = phi_C - phi_U;
    const double down = phi_D - phi_C;
    const double corr = 0.5 * Law::psi(up / down) * down;
    // A local extremum or a flat region (r <= 0 or undefined): every TVD limiter falls back to upwind.
    return up * down <= 0.0 ? 0.0 : corr;
  }
}

/// Face value between cells L (lower index) and R for a face velocity `vel` (positive from L to R);
/// phi_LL lies before L and phi_RR after R.
template <class Law>
[[gnu::always_inline]] inline double face_value(double vel, double phi_LL, double phi_L, double phi_R, double phi_RR) {
  if (vel >= 0.0) return phi_L + correction<Law>(phi_LL, phi_L, phi_R);
  return phi_R + correction<Law>(phi_RR, phi_R, phi_L);
}

/// correction<Law> for a limiter chosen at run time.
inline double correction(Limiter limiter, double phi_U, double phi_C, double phi_D) {
  return with_limiter(limiter, [&](auto law) { return correction<decltype(law)>(phi_U, phi_C, phi_D); });
}
/// face_value<Law> for a limiter chosen at run time.
inline double face_value(Limiter limiter, double vel, double phi_LL, double phi_L, double phi_R, double phi_RR) {
  return with_limiter(limiter, [&](auto law) { return face_value<decltype(law)>(vel, phi_LL, phi_L, phi_R, phi_RR); });
}

}  // namespace fluidbed::tvd
