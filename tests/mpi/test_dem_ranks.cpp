// The DEM split over 1 to 4 ranks (ctest runs this under mpiexec -n 1..4) against the same DEM on one process, bit
// for bit: every particle's state, every pair and wall spring by id, the kinetic energy of every step, for a
// frictional 3D bed with random spins, a 2D bed periodic in x with an outflow side and a feed, a Hertz-Mindlin
// mixture with rolling springs, a bed whose blocks are dealt again every rebuild, and a state saved on one process
// and continued on all ranks. Each rank also runs the one-process reference itself (the beds are small).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "dem/dem_solver.hpp"
#include "dem/packing.hpp"
#include "mpi_world.hpp"

namespace fluidbed {
namespace {

template <int Dim>
struct Bed {
  DemConfig config;
  ParticleStore<Dim> particles;
  Index<Dim> cells{};
  double threshold = 1.2;
};

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// Every pair spring of a state by (particle id, partner id), as bits.
template <int Dim>
std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::uint64_t>> springs_of(const typename DemSolver<Dim>::State& s) {
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::uint64_t>> m;
  const HeldSprings<Dim>& h = s.held;
  for (std::size_t i = 0; i < h.particles(); ++i) {
    for (std::size_t q = h.offset[i]; q < h.offset[i + 1]; ++q) {
      std::vector<std::uint64_t> bits;
      for (int a = 0; a < Dim; ++a) bits.push_back(std::bit_cast<std::uint64_t>(h.xi[q][a]));
      if (h.keeps_rolling()) {
        if constexpr (Dim == 2) {
          bits.push_back(std::bit_cast<std::uint64_t>(h.roll[q]));
        } else {
          for (int c = 0; c < 3; ++c) bits.push_back(std::bit_cast<std::uint64_t>(h.roll[q][c]));
        }
      }
      m[{s.particles.id[i], h.partner_id[q]}] = bits;
    }
  }
  return m;
}

template <int Dim>
void expect_same_state(const typename DemSolver<Dim>::State& a, const typename DemSolver<Dim>::State& b,
                       const std::string& what) {
  // Both portable states list the particles in ascending id.
  std::vector<std::string> names;
  std::vector<bool> same;
  a.particles.for_each_array([&](const std::string& name, const auto&, ArrayRole role) {
    if (role == ArrayRole::State) names.push_back(name);
  });
  std::size_t k = 0;
  a.particles.for_each_array([&](const std::string& name, const auto& u, ArrayRole role) {
    if (role != ArrayRole::State) return;
    std::size_t m = 0;
    b.particles.for_each_array([&](const std::string&, const auto& v, ArrayRole r2) {
      if (r2 != ArrayRole::State) return;
      if constexpr (std::is_same_v<decltype(u), decltype(v)>) {
        if (m == k) {
          EXPECT_TRUE(same_bits(u, v)) << what << ": particle array " << name;
        }
      }
      ++m;
    });
    ++k;
  });
  EXPECT_TRUE(springs_of<Dim>(a) == springs_of<Dim>(b)) << what << ": pair springs by id";
  for (std::size_t i = 0; i < a.particles.size() && i < b.particles.size(); ++i) {
    for (int w = 0; w < 2 * Dim; ++w) {
      const Vec<Dim> x = a.walls.get(i, w), y = b.walls.get(i, w);
      for (int c = 0; c < Dim; ++c) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(x[c]), std::bit_cast<std::uint64_t>(y[c])) << what << ": wall spring";
      }
    }
  }
  EXPECT_EQ(a.rebuilds, b.rebuilds) << what;
  EXPECT_EQ(a.removed_count, b.removed_count) << what;
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.removed_mass), std::bit_cast<std::uint64_t>(b.removed_mass)) << what;
  EXPECT_EQ(a.feed.inserted, b.feed.inserted) << what;
  EXPECT_EQ(a.feed.draws, b.feed.draws) << what;
}

/// The bed run `steps` steps on `comm`; the kinetic energy of every step into `ke`; the portable state at the end.
template <int Dim>
typename DemSolver<Dim>::State run(const Bed<Dim>& bed, const Comm& comm, int steps, std::vector<double>& ke,
                                   std::uint64_t* rebalances = nullptr) {
  DemSolver<Dim> s(bed.config, bed.particles);
  Vec<Dim> h{}, origin{}, kernel{};
  const Vec<Dim> extent = bed.config.domain.template extent<Dim>();
  for (int a = 0; a < Dim; ++a) h[a] = extent[a] / bed.cells[a];
  s.distribute(comm, bed.cells, h, origin, kernel, bed.threshold);
  for (int k = 0; k < steps; ++k) {
    s.step();
    ke.push_back(s.kinetic_energy());
  }
  if (rebalances) *rebalances = s.parallel_stats().rebalances;
  return s.portable_state();
}

template <int Dim>
typename DemSolver<Dim>::State expect_ranks_agree(const Bed<Dim>& bed, int steps, const std::string& what,
                                                  std::uint64_t* rebalances = nullptr) {
  const Comm& c = world();
  std::vector<double> ke_one, ke_all;
  const auto one = run<Dim>(bed, serial_comm(), steps, ke_one);
  const auto all = run<Dim>(bed, c, steps, ke_all, rebalances);
  EXPECT_TRUE(same_bits(ke_one, ke_all)) << what << ": kinetic energy of every step, " << c.size() << " ranks";
  if (c.rank() == 0) {
    EXPECT_EQ(one.particles.size(), all.particles.size()) << what;
    if (one.particles.size() == all.particles.size()) {
      expect_same_state<Dim>(one, all, what + ", " + std::to_string(c.size()) + " ranks");
    }
  }
  return one;
}

/// Random velocities and spins, so that contacts slide and roll from the start.
template <int Dim>
void stir(ParticleStore<Dim>& p, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto u = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53 - 0.5; };
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < Dim; ++a) p.velocity(a)[i] = 0.3 * u();
    if constexpr (Dim == 2) {
      p.set_spin(i, 60.0 * u());
    } else {
      p.set_spin(i, Vec3{60.0 * u(), 60.0 * u(), 60.0 * u()});
    }
  }
}

DemConfig box_config(int dim, Vec3 box, Vec3 gravity) {
  DemConfig c;
  c.domain.dimension = dim;
  c.domain.width = box.x;
  c.domain.height = box.y;
  c.domain.depth = box.z;
  c.domain.gravity = gravity;
  c.dt = 1e-4;
  c.skin = 0.0004;
  c.walls.top = true;
  return c;
}

TEST(DemRanks, FrictionalBed3d) {
  Bed<3> bed;
  bed.config = box_config(3, {0.06, 0.08, 0.04}, {0.0, -9.81, 0.0});
  PackingConfig pc;
  pc.count = 900;
  pc.x_max = 0.06;
  pc.y_max = 0.08;
  pc.z_max = 0.04;
  pc.seed = 3;
  bed.particles = place_random<3>(bed.config, pc);
  stir(bed.particles, 5);
  bed.cells = {6, 8, 4};
  expect_ranks_agree<3>(bed, 400, "3D frictional bed");
}

TEST(DemRanks, PeriodicOutflowAndFeed2d) {
  Bed<2> bed;
  bed.config = box_config(2, {0.08, 0.12, 0.0}, {3.0, -9.81, 0.0});
  bed.config.domain.periodic[0] = true;
  bed.config.walls.bottom = false;
  bed.config.walls.side_outflow[2] = true;
  InsertionConfig& in = bed.config.insertion;
  in.rate = 2000.0;
  in.region_lo = {0.0, 0.09, 0.0};
  in.region_hi = {0.08, 0.11, 0.0};
  in.velocity = {0.0, -0.5, 0.0};
  in.seed = 11;
  PackingConfig pc;
  pc.count = 200;
  pc.x_max = 0.08;
  pc.y_max = 0.06;
  pc.seed = 4;
  bed.particles = place_random<2>(bed.config, pc);
  stir(bed.particles, 6);
  bed.cells = {8, 12};
  const auto st = expect_ranks_agree<2>(bed, 1200, "2D periodic bed with outflow and feed");
  EXPECT_GT(st.removed_count, 0u) << "no particle left";
  EXPECT_GT(st.feed.inserted, 0u) << "no particle was fed";
}

TEST(DemRanks, HertzMindlinMixtureWithRollingSprings3d) {
  Bed<3> bed;
  bed.config = box_config(3, {0.05, 0.06, 0.04}, {0.0, -9.81, 0.0});
  DemConfig& c = bed.config;
  Species small;
  small.diameter = 0.003;
  small.density = 1500.0;
  c.species = {Species{}, small};
  c.pair.assign(4, InteractionParams{0.8, 0.4, 0.1});
  c.wall.assign(2, InteractionParams{0.8, 0.4, 0.1});
  c.contact.normal = NormalModel::Hertz;
  c.contact.damping = DampingModel::Tsuji;
  c.contact.tangential = TangentialModel::Mindlin;
  c.contact.rolling = RollingModel::Epsd;
  ElasticMaterial m;
  m.youngs_modulus = 1e7;
  c.material = {m, m};
  c.contact.wall_material = m;
  PackingConfig pc;
  pc.count = 500;
  pc.x_max = 0.05;
  pc.y_max = 0.03;  // packed close, so that contacts (and their springs) start at once
  pc.z_max = 0.04;
  pc.species_fraction = {0.5, 0.5};
  pc.seed = 8;
  bed.particles = place_random<3>(bed.config, pc);
  stir(bed.particles, 9);
  bed.cells = {5, 6, 4};
  const auto st = expect_ranks_agree<3>(bed, 400, "Hertz-Mindlin mixture with rolling springs");
  EXPECT_GT(st.held.entries(), 100u) << "few springs held";
}

TEST(DemRanks, BlocksDealtAgainEveryRebuildChangeNothing) {
  Bed<2> bed;
  bed.config = box_config(2, {0.1, 0.1, 0.0}, {-6.0, -8.0, 0.0});
  PackingConfig pc;
  pc.count = 350;
  pc.x_max = 0.1;
  pc.y_max = 0.08;
  pc.seed = 12;
  bed.particles = place_random<2>(bed.config, pc);
  bed.cells = {10, 10};
  bed.threshold = 1.0;  // any imbalance at all
  std::uint64_t rebalances = 0;
  expect_ranks_agree<2>(bed, 1500, "2D bed tipped sideways, dealt again at every rebuild", &rebalances);
  if (world().size() > 1) {
    EXPECT_GT(rebalances, 0u) << "the blocks were never dealt again";
  }
}

TEST(DemRanks, AStateSavedOnOneProcessContinuesOnEveryRankCount) {
  Bed<3> bed;
  bed.config = box_config(3, {0.05, 0.06, 0.04}, {0.0, -9.81, 0.0});
  PackingConfig pc;
  pc.count = 600;
  pc.x_max = 0.05;
  pc.y_max = 0.06;
  pc.z_max = 0.04;
  pc.seed = 21;
  bed.particles = place_random<3>(bed.config, pc);
  stir(bed.particles, 22);
  bed.cells = {5, 6, 4};
  // The uninterrupted run, one process.
  std::vector<double> ke;
  const auto whole = run<3>(bed, serial_comm(), 500, ke);
  // 200 steps on one process, its portable state continued for 300 on all ranks.
  const auto half = run<3>(bed, serial_comm(), 200, ke);
  DemSolver<3> s(bed.config, ParticleStore<3>{});
  s.distribute(world(), bed.cells, {0.01, 0.01, 0.01}, {}, {}, 1.2);
  s.restore(half);
  for (int k = 0; k < 300; ++k) s.step();
  const auto continued = s.portable_state();
  if (world().rank() == 0) {
    expect_same_state<3>(whole, continued, "restored on " + std::to_string(world().size()) + " ranks");
  }
}

}  // namespace
}  // namespace fluidbed
