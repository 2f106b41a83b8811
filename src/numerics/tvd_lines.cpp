#include "numerics/tvd_lines.hpp"

namespace fluidbed::tvd {
namespace {

template <class Law, bool Flux>
__attribute__((target_clones("avx512f", "avx2", "default"))) void line(int n, const double* __restrict vel,
                                                                       const double* __restrict phi, std::ptrdiff_t s,
                                                                       double* __restrict out) {
  for (int i = 0; i < n; ++i) {
    const double v = face_value_select<Law>(vel[i], phi[i - 2 * s], phi[i - s], phi[i], phi[i + s]);
    out[i] = Flux ? vel[i] * v : v;
  }
}

template <bool Flux>
void dispatch(Limiter limiter, int n, const double* vel, const double* phi, std::ptrdiff_t s, double* out) {
  with_limiter(limiter, [&](auto law) { line<decltype(law), Flux>(n, vel, phi, s, out); });
}

}  // namespace

void face_values(Limiter limiter, int n, const double* vel, const double* phi, std::ptrdiff_t s, double* out) {
  dispatch<false>(limiter, n, vel, phi, s, out);
}

void face_fluxes(Limiter limiter, int n, const double* vel, const double* phi, std::ptrdiff_t s, double* out) {
  dispatch<true>(limiter, n, vel, phi, s, out);
}

}  // namespace fluidbed::tvd
