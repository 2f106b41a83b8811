#pragma once
// The sample series written for tests/post/test_vtk_readback.py. The same formulas are in
// tests/post/vtk_check.py (sample_*): change both together.
#include <array>
#include <cstdint>
#include <vector>

#include <string>
#include <utility>
#include "dem/particle_store.hpp"
#include "io/particle_arrays.hpp"
#include "io/vtk_writer.hpp"

namespace fluidbed::test {

inline constexpr int sample_frames = 3;
inline double sample_time(int k) { return 0.1 * k / 3.0; }
/// A 2D ImageData grid of nx x ny cells.
inline VtiGrid grid_2d(int nx, int ny, double dx, double dy, double x0 = 0.0, double y0 = 0.0) {
  VtiGrid g;
  g.n = {nx, ny, 1};
  g.h = {dx, dy, 0.0};
  g.origin = {x0, y0, 0.0};
  return g;
}
inline VtiGrid sample_grid() { return grid_2d(4, 3, 0.0025, 0.005); }

/// Cell arrays of a 2D sample, i fastest.
struct SampleFields {
  std::vector<double> voidage, pressure, ug, vg;
};

/// The large sample: 128 x 64 cells, so a scalar array is exactly one compression block (64 KiB) and a vector
/// array three (the last block full).
inline VtiGrid sample_large_grid() { return grid_2d(128, 64, 0.0025, 0.005); }
inline constexpr std::int64_t sample_large_particles = 20000;  ///< 480,000 bytes of Points: 7 full blocks and a part

inline SampleFields sample_fields(double t, const VtiGrid& g = sample_grid()) {
  SampleFields f;
  for (int j = 0; j < g.n[1]; ++j) {
    for (int i = 0; i < g.n[0]; ++i) {
      f.voidage.push_back(0.4 + 0.01 * i + j / 30.0 + t);
      f.pressure.push_back(101325.0 + 1000.0 * j - t * i);
      f.ug.push_back(i * t);
      f.vg.push_back(-1.0 * j + 0.5);
    }
  }
  return f;
}

/// A scalar cell array and a 2D vector one (written with z = 0) over contiguous values.
inline VtiComponents scalar(std::string name, const std::vector<double>& f) {
  return {std::move(name), {f.data(), nullptr, nullptr}, 1};
}
inline VtiComponents vector(std::string name, const std::vector<double>& x, const std::vector<double>& y) {
  return {std::move(name), {x.data(), y.data(), nullptr}, 2};
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

/// The 3D sample (tests/post/test_vtk_readback_3d.py): 4 x 3 x 2 cells and 5 spheres stored out of id order.
inline VtiGrid sample_grid_3d() {
  VtiGrid g;
  g.dimension = 3;
  g.n = {4, 3, 2};
  g.h = {0.0025, 0.005, 0.004};
  g.origin = {0.1, 0.0, 0.002};
  return g;
}

/// Cell arrays of the 3D sample, i fastest: voidage, pressure, gas velocity (3 components).
struct SampleFields3d {
  std::vector<double> voidage, pressure, ug, vg, wg;
};
inline SampleFields3d sample_fields_3d(double t) {
  const VtiGrid g = sample_grid_3d();
  SampleFields3d f;
  for (int k = 0; k < g.n[2]; ++k) {
    for (int j = 0; j < g.n[1]; ++j) {
      for (int i = 0; i < g.n[0]; ++i) {
        f.voidage.push_back(0.4 + 0.01 * i + j / 30.0 + k / 7.0 + t);
        f.pressure.push_back(1000.0 * j - k);
        f.ug.push_back(i * t);
        f.vg.push_back(0.5 - j);
        f.wg.push_back(0.25 * k - t);
      }
    }
  }
  return f;
}

/// Owned arrays of the 3D sample particles, and their ParticleArrays view.
struct SampleParticles3d {
  std::vector<std::int64_t> id;
  std::array<std::vector<double>, 3> x, v, omega;
  std::vector<double> radius;
  std::vector<std::int32_t> species, layer;
  ParticleArrays view() const {
    ParticleArrays a;
    a.dimension = 3;
    a.id = id;
    for (std::size_t d = 0; d < 3; ++d) {
      a.x[d] = x[d];
      a.v[d] = v[d];
      a.omega[d] = omega[d];
    }
    a.radius = radius;
    a.species = species;
    a.layer = layer;
    return a;
  }
};
inline SampleParticles3d sample_particles_3d(double t) {
  SampleParticles3d p;
  for (const std::int64_t id : std::array<std::int64_t, 5>{4, 0, 3, 1, 2}) {
    const double d = static_cast<double>(id);
    p.id.push_back(id);
    p.x[0].push_back(0.001 * (d + 1.0));
    p.x[1].push_back(0.002 * d + t);
    p.x[2].push_back(0.003 * d);
    p.v[0].push_back(0.5 * d);
    p.v[1].push_back(-t);
    p.v[2].push_back(0.25 * d);
    p.omega[0].push_back(d);
    p.omega[1].push_back(-2.0 * d);
    p.omega[2].push_back(10.0 * d - 1.0);
    p.radius.push_back(0.002 + 0.0005 * d);
    p.species.push_back(static_cast<std::int32_t>(id % 2));
    p.layer.push_back(static_cast<std::int32_t>(id / 2));
  }
  return p;
}

}  // namespace fluidbed::test
