// Checkpoint datasets by component name (checkpoint_io.hpp): fields of either dimension with their ghost layers and
// 3D particle arrays come back bit for bit; a field of another shape is refused naming both shapes; the 2D particle
// datasets keep the names of today's checkpoints.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "io/checkpoint_io.hpp"
#include "io/csv.hpp"
#include "sample_series.hpp"
#include "test_helpers.hpp"

namespace fluidbed {
namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (std::bit_cast<std::uint64_t>(a[k]) != std::bit_cast<std::uint64_t>(b[k])) return false;
  }
  return true;
}

TEST(CheckpointIo, FieldsRoundTripWithGhostsAndRefuseAnotherShape) {
  const test::ScratchDir scratch;
  const auto path = scratch.path / "c.h5";
  Field<3> f(IndexBox<3>{{0, 0, 0}, {4, 3, 2}}, 1);
  for (std::size_t k = 0; k < f.data().size(); ++k) f.data()[k] = std::sin(0.1 * static_cast<double>(k)) * 1e-300;
  f.data()[5] = -0.0;
  Field<2> g(IndexBox<2>{{0, 0}, {3, 5}}, 2, 0.25);
  {
    Hdf5File h = Hdf5File::create(path);
    write_field(h, "gas/p", f);
    write_field(h, "gas/eps", g);
    h.commit();
  }
  const Hdf5File h = Hdf5File::open(path);
  h.verify();
  Field<3> back(IndexBox<3>{{0, 0, 0}, {4, 3, 2}}, 1, 7.0);
  read_field(h, "gas/p", back);
  EXPECT_TRUE(same_bits(back.data(), f.data()));
  Field<2> back2(IndexBox<2>{{0, 0}, {3, 5}}, 2);
  read_field(h, "gas/eps", back2);
  EXPECT_TRUE(same_bits(back2.data(), g.data()));
  Field<3> other(IndexBox<3>{{0, 0, 0}, {4, 3, 3}}, 1);
  try {
    read_field(h, "gas/p", other);
    ADD_FAILURE() << "accepted a field of another shape";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("gas/p is 3D, ghost 1, cells [0, 4) [0, 3) [0, 2); the case needs 3D, "
                                         "ghost 1, cells [0, 4) [0, 3) [0, 3)"),
              std::string::npos)
        << e.what();
  }
  Field<2> flat(IndexBox<2>{{0, 0}, {4, 3}}, 1);
  EXPECT_THROW(read_field(h, "gas/p", flat), Error);
}

TEST(CheckpointIo, ParticleArraysByComponentName) {
  const test::ScratchDir scratch;
  const auto path = scratch.path / "p.h5";
  test::SampleParticles3d p3 = test::sample_particles_3d(0.1 / 3.0);
  p3.omega[1][2] = -0.0;
  const ParticleStore p2 = test::sample_particles(0.05);
  {
    Hdf5File h = Hdf5File::create(path);
    write_particle_arrays(h, "dem3", p3.view());
    write_particle_arrays(h, "dem", particle_arrays(p2));
    h.commit();
  }
  const Hdf5File h = Hdf5File::open(path);
  for (const char* n : {"x", "y", "z", "vx", "vy", "vz", "omega_x", "omega_y", "omega_z", "id", "species", "layer"}) {
    EXPECT_TRUE(h.has(std::string("dem3/") + n)) << n;
  }
  // The 2D datasets are those of today's checkpoints (dem/x, dem/y, dem/vx, dem/vy, dem/omega).
  for (const char* n : {"x", "y", "vx", "vy", "omega", "id", "species", "layer"}) EXPECT_TRUE(h.has(std::string("dem/") + n)) << n;
  EXPECT_FALSE(h.has("dem/z"));
  const ParticleArraysData d = read_particle_arrays(h, "dem3", 3);
  EXPECT_EQ(d.id, p3.id);
  EXPECT_EQ(d.species, p3.species);
  EXPECT_EQ(d.layer, p3.layer);
  for (std::size_t a = 0; a < 3; ++a) {
    EXPECT_TRUE(same_bits(d.x[a], p3.x[a])) << a;
    EXPECT_TRUE(same_bits(d.v[a], p3.v[a])) << a;
    EXPECT_TRUE(same_bits(d.omega[a], p3.omega[a])) << a;
  }
  const ParticleArraysData d2 = read_particle_arrays(h, "dem", 2);
  EXPECT_TRUE(same_bits(d2.x[0], p2.x) && same_bits(d2.x[1], p2.y) && same_bits(d2.omega[2], p2.omega));
  // A 2D group read as 3D misses its z.
  EXPECT_THROW(read_particle_arrays(h, "dem", 3), Error);
}

// particle_arrays() views a 3D store by its member names (those of ParticleStore<3>).
TEST(CheckpointIo, ViewOfAThreeDimensionalStore) {
  struct Store3 {
    std::vector<std::int64_t> id{7, 3};
    std::vector<std::int32_t> species{0, 1}, layer{2, 0};
    std::vector<double> radius{0.002, 0.001}, x{0.1, 0.2}, y{0.3, 0.4}, z{0.5, 0.6}, vx{1, 2}, vy{3, 4}, vz{5, 6},
        omega_x{7, 8}, omega_y{9, 10}, omega_z{11, 12};
  } s;
  const ParticleArrays a = particle_arrays(s);
  EXPECT_EQ(a.dimension, 3);
  EXPECT_EQ(a.x[2][1], 0.6);
  EXPECT_EQ(a.v[2][0], 5.0);
  EXPECT_EQ(a.omega[1][1], 10.0);
  EXPECT_EQ(a.order_by_id(), (std::vector<std::size_t>{1, 0}));
  EXPECT_EQ(particle_arrays(test::sample_particles(0.0)).dimension, 2);
}

}  // namespace
}  // namespace fluidbed
