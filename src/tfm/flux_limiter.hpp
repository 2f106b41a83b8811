#pragma once
// TVD flux limiters and the limited face value of a cell-centred scalar (paper section 2.2.1).
namespace fluidbed::tfm {

/// Flux limiter psi(r); Upwind (psi = 0) is kept for comparison and first-order runs.
enum class Limiter { Upwind, Minmod, VanLeer, Superbee };

/// Superbee limiter of Roe (1985): psi = max(0, min(2r, 1), min(r, 2)).
double superbee(double r);
/// Minmod limiter: psi = max(0, min(r, 1)).
double minmod(double r);
/// van Leer limiter (1974): psi = (r + |r|) / (1 + |r|).
double van_leer(double r);
/// psi(r) of the chosen limiter.
double limiter_value(Limiter limiter, double r);

/// High-order correction added to the upwind value on a face:
/// 0.5 psi(r) (phi_D - phi_C) with r = (phi_C - phi_U) / (phi_D - phi_C),
/// where C is the upwind cell, D the downwind cell and U the cell upwind of C.
double limited_correction(Limiter limiter, double phi_U, double phi_C, double phi_D);

/// Face value between cells L (lower index) and R for a face velocity `vel` (positive from L to R).
/// phi_LL lies before L and phi_RR after R; the upwind side is chosen from the sign of vel.
double tvd_face_value(Limiter limiter, double vel, double phi_LL, double phi_L, double phi_R, double phi_RR);

}  // namespace fluidbed::tfm
