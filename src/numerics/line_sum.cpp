#include "numerics/line_sum.hpp"

namespace fluidbed {

__attribute__((target_clones("avx2", "default"))) double line_dot(const double* u, const double* v, int n) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += u[i] * v[i];
    s1 += u[i + 1] * v[i + 1];
    s2 += u[i + 2] * v[i + 2];
    s3 += u[i + 3] * v[i + 3];
  }
  double s = (s0 + s1) + (s2 + s3);
  for (; i < n; ++i) s += u[i] * v[i];
  return s;
}

}  // namespace fluidbed
