#pragma once
// TVD face values of whole lines of faces (the limiter family of core/tvd_limiter.hpp): the same bits as
// face_value<Law> face by face, computed without branches so that a line vectorises. Cloned for AVX-512 and AVX2
// (with -ffp-contract=off every clone rounds as the scalar code).
#include <cstddef>

#include "numerics/tvd_limiter.hpp"

namespace fluidbed::tvd {

/// face_value<Law> with the upwind choice and the extremum test as selects: both sides are computed and one is
/// kept. Every kept operation is the one face_value performs, in its order, so the bits are the same.
template <class Law>
[[gnu::always_inline]] inline double face_value_select(double vel, double phi_LL, double phi_L, double phi_R,
                                                       double phi_RR) {
  const bool fwd = vel >= 0.0;
  const double u = fwd ? phi_LL : phi_RR, c = fwd ? phi_L : phi_R, d = fwd ? phi_R : phi_L;
  return c + correction<Law>(u, c, d);
}

/// out[i] = face_value(vel[i], phi[i - 2s], phi[i - s], phi[i], phi[i + s]) for 0 <= i < n: the faces of a line
/// whose face i lies between the cells phi[i - s] and phi[i] (s: the stride of the face's axis).
void face_values(Limiter limiter, int n, const double* vel, const double* phi, std::ptrdiff_t s, double* out);

/// out[i] = vel[i] * face_value(vel[i], phi[i - 2s], phi[i - s], phi[i], phi[i + s]): the convective fluxes.
void face_fluxes(Limiter limiter, int n, const double* vel, const double* phi, std::ptrdiff_t s, double* out);

}  // namespace fluidbed::tvd
