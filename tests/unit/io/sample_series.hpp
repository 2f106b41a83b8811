#pragma once
// The sample series written for tests/post/test_vtk_readback.py. The same formulas are in
// tests/post/vtk_check.py (sample_*): change both together.
#include <array>
#include <cstdint>

#include "core/field2.hpp"
#include "core/grid2.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed::test {

inline constexpr int sample_frames = 3;
inline double sample_time(int k) { return 0.1 * k / 3.0; }
inline Grid2 sample_grid() { return Grid2{4, 3, 0.0025, 0.005, 0.0, 0.0}; }

struct SampleFields {
  Field2 voidage, pressure, ug, vg;
};

/// The large sample: 128 x 64 cells, so a scalar array is exactly one compression block (64 KiB) and a vector
/// array three (the last block full).
inline Grid2 sample_large_grid() { return Grid2{128, 64, 0.0025, 0.005, 0.0, 0.0}; }
inline constexpr std::int64_t sample_large_particles = 20000;  ///< 480,000 bytes of Points: 7 full blocks and a part

inline SampleFields sample_fields(double t, const Grid2& g = sample_grid()) {
  SampleFields f{Field2(g.nx, g.ny), Field2(g.nx, g.ny), Field2(g.nx, g.ny), Field2(g.nx, g.ny)};
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      f.voidage(i, j) = 0.4 + 0.01 * i + j / 30.0 + t;
      f.pressure(i, j) = 101325.0 + 1000.0 * j - t * i;
      f.ug(i, j) = i * t;
      f.vg(i, j) = -1.0 * j + 0.5;
    }
  }
  return f;
}

/// Five particles stored out of id order, so the writers' sorting is exercised.
inline ParticleStore<2> sample_particles(double t) {
  ParticleStore<2> p;
  const Species s{0.004, 2700.0};
  for (const std::int64_t id : std::array<std::int64_t, 5>{4, 0, 3, 1, 2}) {
    const double d = static_cast<double>(id);
    p.add(id, static_cast<std::int32_t>(id % 2), s, {0.001 * (d + 1.0), 0.002 * d + t}, {0.5 * d, -t},
          10.0 * d - 1.0, static_cast<std::int32_t>(id / 2));
  }
  return p;
}

/// `n` particles of the same formulas as sample_particles, stored in decreasing id order.
inline ParticleStore<2> sample_particles(double t, std::int64_t n) {
  ParticleStore<2> p;
  const Species s{0.004, 2700.0};
  for (std::int64_t id = n - 1; id >= 0; --id) {
    const double d = static_cast<double>(id);
    p.add(id, static_cast<std::int32_t>(id % 2), s, {0.001 * (d + 1.0), 0.002 * d + t}, {0.5 * d, -t},
          10.0 * d - 1.0, static_cast<std::int32_t>(id / 2));
  }
  return p;
}

}  // namespace fluidbed::test
