#include "models/dem_model.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <span>
#include <sstream>
#include <fmt/format.h>
#include <limits>
#include <spdlog/spdlog.h>

#include "analysis/cell_view.hpp"
#include "analysis/layer_tracers.hpp"
#include "fluid/gas_boundary.hpp"
#include "analysis/mixing_index.hpp"
#include "coupling/cfd_dem.hpp"
#include "core/error.hpp"
#include "dem/dem_solver.hpp"
#include "dem/packing.hpp"
#include "dem/settle.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/hdf5_file.hpp"

namespace fluidbed {

template <int Dim>
ParticleStore<Dim> particles_from_csv(const std::string& path, const DemConfig& dem) {
  const std::vector<ParticleCsvRow> rows = read_particles_csv(path, Dim);
  check_particle_rows(rows, path, dem.domain, dem.n_species());
  ParticleStore<Dim> p;
  p.reserve(rows.size());
  for (const ParticleCsvRow& row : rows) {
    const Species& species = dem.species[static_cast<std::size_t>(row.species)];
    // A row with a diameter is a particle of its own size; one without has its species' diameter.
    const Species s = row.diameter > 0.0 ? species.of_diameter(row.diameter) : species;
    if constexpr (Dim == 2) {
      p.add(row.id, row.species, s, {row.x, row.y}, {row.vx, row.vy}, row.omega);
    } else {
      p.add(row.id, row.species, s, {row.x, row.y, row.z}, {row.vx, row.vy, row.vz}, {row.omega_x, row.omega_y, row.omega});
    }
  }
  return p;
}
template ParticleStore<2> particles_from_csv<2>(const std::string&, const DemConfig&);
template ParticleStore<3> particles_from_csv<3>(const std::string&, const DemConfig&);

namespace {

// The checkpoint's name of the spring component c against wall w ("dem/wall_xi_left_x", ...).
template <int Dim>
std::string wall_spring_name(int w, int c) {
  static constexpr const char* kAxis[3] = {"x", "y", "z"};
  static constexpr const char* kSide[6] = {"left", "right", "bottom", "top", "back", "front"};
  return std::string("dem/wall_xi_") + kSide[w] + "_" + kAxis[c];
}

// Writes a portable state (DemSolver::checkpoint_view: every particle in ascending id, its springs by partner id),
// each array read through the view's order one HDF5 chunk at a time, so no array of the store is copied whole.
template <int Dim>
void save_dem(Hdf5File& f, const typename DemSolver<Dim>::CheckpointView& s, bool own_sizes) {
    static constexpr const char* kAxis[3] = {"x", "y", "z"};
    const ParticleStore<Dim>& p = s.particles();
    const std::vector<std::uint32_t>& order = s.order;
    const std::size_t n = order.size();
    f.create_group("dem");
    // Every state attribute of the store under its own name (ParticleStore::for_each_array), then the
    // positions of the last list build.
    p.for_each_array([&](const std::string& name, const auto& a, ArrayRole role) {
      if (role != ArrayRole::State) return;
      using T = typename std::decay_t<decltype(a)>::value_type;
      f.write("dem/" + name, n, std::function<void(std::size_t, std::size_t, T*)>(
                                   [&a, &order](std::size_t first, std::size_t m, T* d) {
                                     for (std::size_t k = first; k < first + m; ++k) *d++ = a[order[k]];
                                   }));
    });
    // The wall springs, one array per wall and component over every particle (+0 where a particle holds none), as
    // the store once held them.
    const WallSprings<Dim>& walls = s.walls();
    for (int w = 0; w < 2 * Dim; ++w) {
      for (int c = 0; c < Dim; ++c) {
        f.write(wall_spring_name<Dim>(w, c), n, [&walls, &order, w, c](std::size_t first, std::size_t m, double* d) {
          for (std::size_t k = first; k < first + m; ++k) *d++ = walls.get(order[k], w)[c];
        });
      }
    }
    // Particles of their own sizes keep them (the species' diameters restore every other bed, as they always have).
    if (own_sizes) {
      f.write("dem/diameter", n, [&p, &order](std::size_t first, std::size_t m, double* d) {
        for (std::size_t k = first; k < first + m; ++k) *d++ = 2.0 * p.radius[order[k]];
      });
    }
    for (int a = 0; a < Dim; ++a) {
      const std::vector<double>& b = s.build(a);
      f.write(std::string("dem/") + kAxis[a] + "_build", n, [&b, &order](std::size_t first, std::size_t m, double* d) {
        for (std::size_t k = first; k < first + m; ++k) *d++ = b[order[k]];
      });
    }
    // The pair springs each particle holds, by its partner's id (CSR over the particles, in ascending id): no
    // storage slot is written, so the state restarts on any number of ranks. Read through the order too: `at`
    // is the CSR's offsets in ascending id, and the e-th spring written is entry e - at[k] of particle order[k].
    const HeldSprings<Dim>& h = s.held();
    std::vector<std::size_t> at(n + 1, 0);
    for (std::size_t k = 0; k < n; ++k) at[k + 1] = at[k] + h.offset[order[k] + 1] - h.offset[order[k]];
    const auto each_spring = [&h, &at, &order](std::size_t first, std::size_t m, auto&& put) {
      std::size_t k = static_cast<std::size_t>(std::upper_bound(at.begin(), at.end(), first) - at.begin()) - 1;
      for (std::size_t e = first; e < first + m; ++e) {
        while (e >= at[k + 1]) ++k;
        put(h.offset[order[k]] + (e - at[k]));
      }
    };
    f.write("dem/held_offset", at.size(), [&at](std::size_t first, std::size_t m, std::int64_t* d) {
      for (std::size_t k = first; k < first + m; ++k) *d++ = static_cast<std::int64_t>(at[k]);
    });
    f.write("dem/held_partner_id", at[n], [&](std::size_t first, std::size_t m, std::int64_t* d) {
      each_spring(first, m, [&](std::size_t q) { *d++ = h.partner_id[q]; });
    });
    for (int a = 0; a < Dim; ++a) {
      f.write(std::string("dem/held_xi_") + kAxis[a], at[n], [&](std::size_t first, std::size_t m, double* d) {
        each_spring(first, m, [&](std::size_t q) { *d++ = h.xi[q][a]; });
      });
    }
    // One spin component of a rolling spring (a scalar in 2D).
    auto spin_component = [](const auto& spin, int c) {
      if constexpr (Dim == 2) {
        (void)c;
        return spin;
      } else {
        return spin[c];
      }
    };
    // Rolling springs (laws with one): one array per spin component, absent when the law has none.
    if (h.keeps_rolling()) {
      for (int c = 0; c < kSpinComponents<Dim>; ++c) {
        f.write(fmt::format("dem/held_roll_{}", c), at[n], [&](std::size_t first, std::size_t m, double* d) {
          each_spring(first, m, [&](std::size_t q) { *d++ = spin_component(h.roll[q], c); });
        });
      }
    }
    // Rolling springs against the walls, 2 Dim per particle (in ascending id), likewise absent without them.
    const std::vector<Spin<Dim>>& wall_roll = s.wall_roll();
    if (!wall_roll.empty()) {
      constexpr std::size_t kWalls = 2 * Dim;
      for (int c = 0; c < kSpinComponents<Dim>; ++c) {
        f.write(fmt::format("dem/wall_roll_{}", c), n * kWalls, [&](std::size_t first, std::size_t m, double* d) {
          for (std::size_t k = first; k < first + m; ++k)
            *d++ = spin_component(wall_roll[order[k / kWalls] * kWalls + k % kWalls], c);
        });
      }
    }
    f.set_attribute("dem", "dimension", static_cast<std::int64_t>(Dim));
    f.set_attribute("dem", "time", s.state.time);
    f.set_attribute("dem", "steps", static_cast<std::int64_t>(s.state.steps));
    f.set_attribute("dem", "rebuilds", static_cast<std::int64_t>(s.state.rebuilds));
    f.set_attribute("dem", "need_rebuild", static_cast<std::int64_t>(s.state.need_rebuild));
    f.set_attribute("dem", "time_origin", s.state.time_origin);
    f.set_attribute("dem", "steps_origin", static_cast<std::int64_t>(s.state.steps_origin));
    f.set_attribute("dem", "removed_count", static_cast<std::int64_t>(s.state.removed_count));
    f.set_attribute("dem", "removed_mass", s.state.removed_mass);
    f.set_attribute("dem", "inserted_count", static_cast<std::int64_t>(s.state.feed.inserted));
    f.set_attribute("dem", "inserted_mass", s.state.feed.mass);
    f.set_attribute("dem", "feed_draws", static_cast<std::int64_t>(s.state.feed.draws));
    f.set_attribute("dem", "next_id", s.state.feed.next_id);
}

// One double per particle of the checkpoint array dem/NAME, checked against the particle count.
std::vector<double> read_per_particle(const Hdf5File& f, const std::string& name, std::size_t n) {
  std::vector<double> v = f.read_double("dem/" + name);
  if (v.size() != n) {
    throw_input_error(fmt::format("{}: dem/{} has {} values for {} particles", f.path().string(), name, v.size(), n));
  }
  return v;
}

// The particles of a DEM checkpoint: ids, species, layers, own sizes, and every state array of the store.
template <int Dim>
void load_dem_particles(const Hdf5File& f, const CaseConfig& config_, typename DemSolver<Dim>::State& s) {
  const std::int64_t dim = f.has_attribute("dem", "dimension") ? f.attribute_int64("dem", "dimension") : 2;
  if (dim != Dim) {
    throw_input_error(fmt::format("{}: a checkpoint of a {}D run cannot restart this {}D case", f.path().string(),
                                  dim, Dim));
  }
  const auto id = f.read_int64("dem/id");
  const auto species = f.read_int32("dem/species");
  const auto layer = f.read_int32("dem/layer");
  if (species.size() != id.size() || layer.size() != id.size()) {
    throw_input_error(fmt::format("{}: inconsistent particle arrays", f.path().string()));
  }
  ParticleStore<Dim>& p = s.particles;
  // A run without gas saves no fluid arrays (the solver takes them again, at zero, if this case has gas).
  p.hold_fluid_arrays(f.has("dem/drag_k"));
  p.reserve(id.size());
  for (std::size_t i = 0; i < id.size(); ++i) {
    if (species[i] < 0 || static_cast<std::size_t>(species[i]) >= config_.dem.n_species()) {
      throw_input_error(fmt::format("{}: particle {} has species {} which the case does not define",
                                    f.path().string(), id[i], species[i]));
    }
    p.add(id[i], species[i], config_.dem.species[static_cast<std::size_t>(species[i])], {}, {}, {}, layer[i]);
  }
  // The order keys (DemSolver::canonical_order); a checkpoint from before them restarts from none.
  if (f.has("dem/order_key")) {
    const auto key = f.read_int64("dem/order_key");
    if (key.size() != id.size()) {
      throw_input_error(fmt::format("{}: dem/order_key has {} values for {} particles", f.path().string(), key.size(), id.size()));
    }
    p.order_key.assign(key.begin(), key.end());
  }
  if (f.has("dem/diameter")) {
    std::vector<double> d = f.read_double("dem/diameter");
    if (d.size() != id.size()) {
      throw_input_error(fmt::format("{}: dem/diameter has {} values for {} particles", f.path().string(), d.size(), id.size()));
    }
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (!(d[i] > 0.0)) throw_input_error(fmt::format("{}: particle {} has diameter {}", f.path().string(), id[i], d[i]));
      p.set_size(i, config_.dem.species[static_cast<std::size_t>(species[i])].of_diameter(d[i]));
    }
  }
  p.for_each_array([&](const std::string& name, auto& a, ArrayRole role) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    if constexpr (std::is_same_v<T, double>) {
      if (role == ArrayRole::State) a = read_per_particle(f, name, id.size());
    }
  });
}

// The wall springs: one array per wall and component, or (2D checkpoints written before they had a name per wall)
// one array of 8 per particle.
template <int Dim>
void load_dem_wall_springs(const Hdf5File& f, typename DemSolver<Dim>::State& s, std::size_t n) {
  s.walls.reset(n);
  if (Dim == 2 && !f.has("dem/wall_xi_left_x")) {
    const std::vector<double> wall = f.read_double("dem/wall_xi");
    if (wall.size() != 8 * n) {
      throw_input_error(fmt::format("{}: the neighbour list or contact history is inconsistent", f.path().string()));
    }
    if constexpr (Dim == 2) {
      for (std::size_t i = 0; i < n; ++i) {
        for (int w = 0; w < 4; ++w) s.walls.set(i, w, {wall[8 * i + 2 * w], wall[8 * i + 2 * w + 1]});
      }
    }
    return;
  }
  for (int w = 0; w < 2 * Dim; ++w) {
    for (int c = 0; c < Dim; ++c) {
      const std::vector<double> v = read_per_particle(f, wall_spring_name<Dim>(w, c).substr(4), n);
      for (std::size_t i = 0; i < v.size(); ++i) {
        Vec<Dim> xi = s.walls.get(i, w);
        xi[c] = v[i];
        s.walls.set(i, w, xi);
      }
    }
  }
}

// The positions of the last counted list build, and the pair springs by partner id: as written (dem/held_*), or
// from the neighbour list of a checkpoint written before the springs were kept by id (dem/nbr_*: storage slots).
template <int Dim>
void load_dem_springs(const Hdf5File& f, const CaseConfig& config_, typename DemSolver<Dim>::State& s, std::size_t n) {
  static constexpr const char* kAxis[3] = {"x", "y", "z"};
  for (std::size_t a = 0; a < s.build.size(); ++a) s.build[a] = read_per_particle(f, std::string(kAxis[a]) + "_build", n);
  const bool rolling_law = config_.dem.contact.needs_rolling_history();
  HeldSprings<Dim>& h = s.held;
  h.clear(0, rolling_law);
  auto bad = [&] { throw_input_error(fmt::format("{}: the neighbour list or contact history is inconsistent", f.path().string())); };
  auto set_spin = [](Spin<Dim>& r, int c, double v) {
    if constexpr (Dim == 2) {
      (void)c;
      r = v;
    } else {
      r[c] = v;
    }
  };
  if (f.has("dem/held_offset")) {
    const auto offset = f.read_int64("dem/held_offset");
    const auto partner = f.read_int64("dem/held_partner_id");
    std::array<std::vector<double>, Dim> xi;
    for (int a = 0; a < Dim; ++a) xi[static_cast<std::size_t>(a)] = f.read_double(std::string("dem/held_xi_") + kAxis[a]);
    std::array<std::vector<double>, kSpinComponents<Dim>> roll;
    const bool has_roll = f.has("dem/held_roll_0");
    for (int c = 0; has_roll && c < kSpinComponents<Dim>; ++c) roll[static_cast<std::size_t>(c)] = f.read_double(fmt::format("dem/held_roll_{}", c));
    if (offset.size() != n + 1 || offset.front() != 0 || static_cast<std::size_t>(offset.back()) != partner.size()) bad();
    for (const auto& x : xi) if (x.size() != partner.size()) bad();
    for (int c = 0; has_roll && c < kSpinComponents<Dim>; ++c) if (roll[static_cast<std::size_t>(c)].size() != partner.size()) bad();
    for (std::size_t i = 0; i < n; ++i) {
      if (offset[i + 1] < offset[i]) bad();
      h.add_particle();
      for (auto q = static_cast<std::size_t>(offset[i]); q < static_cast<std::size_t>(offset[i + 1]); ++q) {
        Vec<Dim> x;
        for (int a = 0; a < Dim; ++a) x[a] = xi[static_cast<std::size_t>(a)][q];
        Spin<Dim> r{};
        for (int c = 0; has_roll && c < kSpinComponents<Dim>; ++c) set_spin(r, c, roll[static_cast<std::size_t>(c)][q]);
        h.add(partner[q], x, r);
      }
    }
    return;
  }
  const auto offset = f.read_int64("dem/nbr_offset");
  const auto partner = f.read_int64("dem/nbr_partner");
  std::array<std::vector<double>, Dim> hist;
  for (int a = 0; a < Dim; ++a) hist[static_cast<std::size_t>(a)] = f.read_double(std::string("dem/nbr_xi_") + kAxis[a]);
  const bool has_roll = f.has("dem/nbr_roll_0");
  std::array<std::vector<double>, kSpinComponents<Dim>> roll;
  for (int c = 0; has_roll && c < kSpinComponents<Dim>; ++c) roll[static_cast<std::size_t>(c)] = f.read_double(fmt::format("dem/nbr_roll_{}", c));
  bool consistent = offset.size() == n + 1 && offset.front() == 0 && static_cast<std::size_t>(offset.back()) == partner.size();
  for (const auto& x : hist) consistent = consistent && x.size() == partner.size();
  for (int c = 0; has_roll && c < kSpinComponents<Dim>; ++c) consistent = consistent && roll[static_cast<std::size_t>(c)].size() == partner.size();
  if (!consistent) bad();
  const std::vector<std::int64_t>& id = s.particles.id;
  for (std::size_t i = 0; i < n; ++i) {
    if (offset[i + 1] < offset[i]) throw_input_error(fmt::format("{}: bad neighbour offsets", f.path().string()));
    h.add_particle();
    for (auto k = static_cast<std::size_t>(offset[i]); k < static_cast<std::size_t>(offset[i + 1]); ++k) {
      if (partner[k] < 0 || static_cast<std::size_t>(partner[k]) >= n) {
        throw_input_error(fmt::format("{}: neighbour index out of range", f.path().string()));
      }
      Vec<Dim> x;
      for (int a = 0; a < Dim; ++a) x[a] = hist[static_cast<std::size_t>(a)][k];
      Spin<Dim> r{};
      for (int c = 0; has_roll && c < kSpinComponents<Dim>; ++c) set_spin(r, c, roll[static_cast<std::size_t>(c)][k]);
      bool held = !HeldSprings<Dim>::plus_zero(x);
      if constexpr (Dim == 2) {
        held = held || !HeldSprings<Dim>::plus_zero(r);
      } else {
        held = held || !HeldSprings<Dim>::plus_zero(r);
      }
      if (held) h.add(id[static_cast<std::size_t>(partner[k])], x, rolling_law ? r : Spin<Dim>{});
    }
  }
}

// The rolling springs against the walls (rolling laws only), one array per spin component.
template <int Dim>
void load_dem_rolling(const Hdf5File& f, typename DemSolver<Dim>::State& s, std::size_t n) {
  if (!f.has("dem/wall_roll_0")) return;
  s.wall_roll.resize(2 * Dim * n);
  for (int c = 0; c < kSpinComponents<Dim>; ++c) {
    const std::vector<double> h = f.read_double(fmt::format("dem/wall_roll_{}", c));
    if (h.size() != s.wall_roll.size()) {
      throw_input_error(fmt::format("{}: the rolling wall springs are inconsistent", f.path().string()));
    }
    for (std::size_t k = 0; k < h.size(); ++k) {
      if constexpr (Dim == 2) {
        s.wall_roll[k] = h[k];
      } else {
        s.wall_roll[k][c] = h[k];
      }
    }
  }
}

// The clock, the counters of the outflow and of the feed.
template <int Dim>
void load_dem_clock(const Hdf5File& f, typename DemSolver<Dim>::State& s) {
  s.time = f.attribute_double("dem", "time");
  s.steps = static_cast<std::uint64_t>(f.attribute_int64("dem", "steps"));
  s.rebuilds = static_cast<std::uint64_t>(f.attribute_int64("dem", "rebuilds"));
  s.need_rebuild = f.attribute_int64("dem", "need_rebuild") != 0;
  // Checkpoints written before the clock kept an origin and before the outflow top: the clock starts at the
  // checkpoint's time and nothing has left.
  const bool has_origin = f.has_attribute("dem", "time_origin");
  s.time_origin = has_origin ? f.attribute_double("dem", "time_origin") : s.time;
  s.steps_origin = has_origin ? static_cast<std::uint64_t>(f.attribute_int64("dem", "steps_origin")) : s.steps;
  if (f.has_attribute("dem", "removed_count")) {
    s.removed_count = static_cast<std::uint64_t>(f.attribute_int64("dem", "removed_count"));
    s.removed_mass = f.attribute_double("dem", "removed_mass");
  }
  // Checkpoints from before the feed: nothing inserted, the next id follows the largest (DemSolver::restore).
  if (f.has_attribute("dem", "inserted_count")) {
    s.feed.inserted = static_cast<std::uint64_t>(f.attribute_int64("dem", "inserted_count"));
    s.feed.mass = f.attribute_double("dem", "inserted_mass");
    s.feed.draws = static_cast<std::uint64_t>(f.attribute_int64("dem", "feed_draws"));
    s.feed.next_id = f.attribute_int64("dem", "next_id");
  }
}

template <int Dim>
typename DemSolver<Dim>::State load_dem(const Hdf5File& f, const CaseConfig& config_) {
  typename DemSolver<Dim>::State s;
  load_dem_particles<Dim>(f, config_, s);
  const std::size_t n = s.particles.size();
  load_dem_wall_springs<Dim>(f, s, n);
  load_dem_springs<Dim>(f, config_, s, n);
  load_dem_rolling<Dim>(f, s, n);
  load_dem_clock<Dim>(f, s);
  return s;
}

/// The gas grid of the case: the [grid] cells, periodic along the domain's periodic axes.
template <int Dim>
Grid<Dim> gas_grid(const CaseConfig& c) {
  Grid<Dim> g = c.grid.grid_of<Dim>();
  for (int a = 0; a < Dim; ++a) g.periodic[static_cast<std::size_t>(a)] = c.domain.periodic[static_cast<std::size_t>(a)];
  return g;
}

template <int Dim>
class DemModel final : public ModelRun {
 public:
  DemModel(const CaseConfig& c, const std::string& out_dir, bool fresh, spdlog::logger& log, const Comm& comm)
      : config_(c),
        comm_(&comm),
        sim_(make_solver(c, fresh ? initial_particles(c, out_dir, log, comm) : ParticleStore<Dim>{}, comm),
             c.gas_enabled ? std::optional<GasSolver<Dim>>(GasSolver<Dim>(gas_grid<Dim>(c), c.gas)) : std::nullopt,
             c.coupling),
        log_(&log) {
    if (fresh) sim_.initialize();
    if (comm.size() > 1) log.info("{}", parallel_summary());
  }

  /// The case's DEM solver, split over the ranks of comm (blocks of the gas grid, or of the [grid] cells of a case
  /// without gas; ghosts over the deposition kernel's cells when there is gas).
  static DemSolver<Dim> make_solver(const CaseConfig& c, ParticleStore<Dim> particles, const Comm& comm) {
    DemSolver<Dim> s(c.dem, std::move(particles));
    if (comm.size() > 1) {
      const Grid<Dim> g = gas_grid<Dim>(c);
      Index<Dim> cells{};
      Vec<Dim> kernel{};
      for (int a = 0; a < Dim; ++a) {
        cells[a] = g.n(a);
        // Multilinear weights reach half a cell beyond a cell's centre band; the counting kernel only the cell.
        kernel[a] = !c.gas_enabled ? 0.0 : (c.coupling.voidage == VoidageMethod::Centre ? 1e-9 * g.h[a] : 0.5 * g.h[a]);
      }
      s.distribute(comm, cells, g.h, g.origin, kernel, c.parallel.rebalance_threshold);
    }
    return s;
  }

  double time() const override { return sim_.time(); }
  double last_step() const override { return last_step_; }
  void advance(double t_end) override {
    // A step that ends within this fraction of a step of t_end is the last one: round-off of n dt, not a step.
    constexpr double kLand = 1e-9;
    const double full = sim_.macro_dt();
    const double remaining = t_end - sim_.time();
    last_step_ = 0.0;
    if (remaining <= kLand * full) {
      if (remaining > 0.0) sim_.dem().land_time(t_end);
      return;
    }
    if (remaining < full * (1.0 - kLand)) {
      sim_.advance(remaining);  // the shortened last step; the clock's origin moves to t_end
      last_step_ = remaining;
      sim_.dem().set_time(t_end, sim_.dem().step_count());
    } else {
      sim_.advance(full);
      last_step_ = full;
      // n dt within round-off of t_end reads t_end; the clock keeps its origin, so a continuation runs on as
      // the uninterrupted run does.
      if (remaining <= full * (1.0 + kLand)) sim_.dem().land_time(t_end);
    }
    if (sim_.dem().removed_count() != lost_seen_) {
      lost_seen_ = sim_.dem().removed_count();
      if (loss_level() > loss_level_) report_losses();
    }
    const double frac = sim_.dem().max_overlap_fraction();
    if (frac > config_.max_overlap_fraction) {
      throw_simulation_error(fmt::format(
          "t = {:.6g} s: a contact overlaps by {:.3g} m, {:.1f}% of its diameter (the smaller of a pair, the particle's "
          "own at a wall), more than dem.max_overlap_fraction = {:.0f}% ({}). Likely cause: the springs are too soft "
          "for the loads (stiffness {} N/m) or particles hit at high speed (a bed lifted as a plug hitting a top wall); "
          "remedy: raise contact.stiffness (and lower dem.time_step), ramp the inlet up (inlet.ramp_time), or raise "
          "dem.max_overlap_fraction if this is intended.",
          time(), sim_.dem().max_overlap(), 100.0 * frac, 100.0 * config_.max_overlap_fraction, deepest_contact(),
          config_.dem.stiffness));
    }
    if (sim_.has_gas() && !std::isfinite(sim_.gas().pressure_drop())) {
      throw_simulation_error(fmt::format("t = {:.6g} s: the gas pressure is not finite. Likely cause: an unstable gas "
                                         "step; remedy: lower dem.time_step or coupling.dem_substeps.", time()));
    }
  }
  double macro_dt() const override { return sim_.macro_dt(); }

  std::vector<std::string> monitor_columns() const override {
    std::vector<std::string> c{"kinetic_energy_J", "pressure_drop_Pa", "max_overlap_m", "gas_mass_residual", "solids_mass_kg",
            "gas_mass_balance", "simple_iterations", "min_voidage", "fluid_force_y_N", "gas_reaction_y_N",
            "neighbor_rebuilds", "lacey_index", "particles_lost", "mass_lost_kg",
            // Per metre of depth (over coupling.depth, the slab the monolayer stands for): the TFM's basis.
            "solids_mass_per_depth_kg_m", "kinetic_energy_per_depth_J_m", "linear_solver_fallbacks",
            "inlet_velocity_m_s"};
    // The feed (insertion), only in a case that has one (the others' monitor.csv stays as it was):
    // solids_mass_kg = M(0) + mass_inserted_kg - mass_lost_kg.
    if (config_.dem.insertion.enabled()) {
      c.push_back("particles_inserted");
      c.push_back("mass_inserted_kg");
    }
    return c;
  }
  std::vector<std::optional<double>> monitor_values() override {
    const ParticleStore<Dim>& p = sim_.dem().particles();
    // Sums over the particles exactly, over every rank (collective).
    const double mass = sim_.dem().total_mass();
    std::vector<std::optional<double>> v{sim_.dem().kinetic_energy(), std::nullopt, sim_.dem().max_overlap(),
                                         std::nullopt, mass, std::nullopt, std::nullopt, std::nullopt,
                                         std::nullopt, std::nullopt, static_cast<double>(sim_.dem().rebuild_count()),
                                         std::nullopt,
                                         static_cast<double>(sim_.dem().removed_count()),
                                         sim_.dem().removed_mass()};
    // Per metre of depth: over the slab the 2D monolayer stands for (coupling.depth), or the 3D bed's depth.
    const double depth = Dim == 2 ? config_.coupling.depth : config_.domain.depth;
    v.push_back(mass / depth);
    v.push_back(*v[0] / depth);
    v.push_back(std::nullopt);
    v.push_back(std::nullopt);
    if (sim_.has_gas()) {
      const GasStepReport& r = sim_.last_gas_report();
      v[v.size() - 2] = static_cast<double>(r.linear_fallbacks);
      // The superficial velocity the last gas step delivered: its bottom mass flow over rho_g and the bottom's area
      // (2D: per metre of depth, as mass_in).
      double bottom = config_.domain.width;
      if constexpr (Dim == 3) bottom *= config_.domain.depth;
      // Before the first gas step (the row at t = 0), the schedules' value at that time.
      v.back() = sim_.gas_steps() == 0 ? inlet_mean_velocity(config_.gas.boundary, sim_.gas().grid(), sim_.time())
                                       : r.mass_in / (config_.gas.rho_g * bottom);
      v[1] = sim_.gas().pressure_drop();
      v[3] = r.mass_residual;
      v[5] = r.mass_balance_relative;
      v[6] = static_cast<double>(r.simple_iterations);
      v[7] = sim_.min_voidage();
      v[8] = sim_.total_fluid_force().y;
      v[9] = sim_.total_gas_reaction().y;
      LaceyCounts<Dim> counts = lacey_counts<Dim>(p, sim_.dem().owned(), config_.particles.layers / 2,
                                                  cell_geometry(sim_.gas().grid()), MixingConfig{});
      comm_->sum(std::span<std::int64_t>(counts.count));
      comm_->sum(std::span<std::int64_t>(counts.coloured));
      const LaceyResult l = lacey_from_counts(counts);
      if (l.valid) v[11] = l.index;
    }
    if (config_.dem.insertion.enabled()) {
      v.push_back(static_cast<double>(sim_.dem().inserted_count()));
      v.push_back(sim_.dem().inserted_mass());
    }
    return v;
  }
  FieldView fields() override {
    if (!sim_.has_gas()) return {};
    FieldView f;
    const Grid<Dim>& g = sim_.gas().grid();
    f.dimension = Dim;
    for (int a = 0; a < Dim; ++a) {
      f.n[static_cast<std::size_t>(a)] = g.n(a);
      f.h[static_cast<std::size_t>(a)] = g.h[a];
      f.origin[static_cast<std::size_t>(a)] = g.origin[a];
    }
    // The coupling's cell fields have no ghosts (contiguous interiors); the pressure's ghosts are dropped.
    f.eps = sim_.voidage().data().data();
    p_view_ = sim_.gas().fields().p.interior();
    f.p = p_view_.data();
    for (int a = 0; a < Dim; ++a) {
      f.ug[static_cast<std::size_t>(a)] = sim_.gas_velocity()[static_cast<std::size_t>(a)].data().data();
      f.us[static_cast<std::size_t>(a)] = sim_.solids_velocity()[static_cast<std::size_t>(a)].data().data();
    }
    return f;
  }
  std::optional<ParticleArrays> particles() const override {
    if (!sim_.dem().distributed()) {
      ParticleArrays a = particle_arrays(sim_.dem().particles());
      a.own_sizes = sim_.dem().has_own_sizes();
      return a;
    }
    // Every rank's particles on rank 0 (collective); the other ranks see none.
    gathered_ = sim_.dem().all_particles(0);
    if (comm_->rank() != 0) return std::nullopt;
    ParticleArrays a = particle_arrays(gathered_);
    a.own_sizes = gathered_.has_own_sizes(config_.dem.species);
    return a;
  }

  void save(Hdf5File* file) const override {
    // The state of every particle, gathered on rank 0 in ascending id with its springs by partner id: the same file
    // on any number of ranks, restorable on any number (collective; rank 0 writes).
    const typename DemSolver<Dim>::CheckpointView st = sim_.dem().checkpoint_view();
    if (file == nullptr) return;
    Hdf5File& f = *file;
    save_dem<Dim>(f, st, st.particles().has_own_sizes(config_.dem.species));
    f.set_attribute("dem", "gas_steps", static_cast<std::int64_t>(sim_.gas_steps()));
    if (sim_.has_gas()) {
      const GasFields<Dim>& g = sim_.gas().fields();
      f.create_group("gas");
      f.write("gas/p", g.p.interior());
      for (int a = 0; a < Dim; ++a) f.write(std::string("gas/") + kFaceName[a], g.u[a].interior());
      f.write("gas/eps", sim_.voidage().data());
    }
  }

  void load(const Hdf5File& f) override {
    sim_.dem().restore(load_dem<Dim>(f, config_));
    loss_level_ = loss_level();  // what the interrupted run has reported already
    lost_seen_ = sim_.dem().removed_count();
    Field<Dim> eps;
    if (sim_.has_gas()) {
      GasFields<Dim>& g = sim_.gas().fields();
      auto read = [&](const std::string& name, std::size_t size) {
        std::vector<double> v = f.read_double("gas/" + name);
        if (v.size() != size) {
          throw_input_error(fmt::format("{}: gas/{} has {} values, the case's grid needs {}", f.path().string(), name,
                                        v.size(), size));
        }
        return v;
      };
      g.p.set_interior(read("p", g.p.box().count()));
      for (int a = 0; a < Dim; ++a) g.u[a].set_interior(read(kFaceName[a], g.u[a].box().count()));
      eps = Field<Dim>(sim_.gas().grid().owned, 0);
      eps.data() = read("eps", eps.data().size());
    }
    sim_.restore(std::move(eps), static_cast<std::uint64_t>(f.attribute_int64("dem", "gas_steps")));
  }

  CostInfo cost() const override {
    return {sim_.dem().total_particles(), sim_.has_gas() ? config_.grid.cells() : 0, sim_.dem().step_count()};
  }
  std::string parallel_summary() const override {
    const BlockLayout<Dim>* layout = sim_.dem().layout();
    if (layout == nullptr) return {};
    const DemParallelStats st = sim_.dem().parallel_stats();
    // Largest and smallest over the ranks (a maximum of the negated value), and totals.
    double v[12] = {static_cast<double>(st.owned), -static_cast<double>(st.owned), static_cast<double>(st.partners),
                    st.imbalance, st.forward_s, st.reduce_s, st.rebuild_comm_s,
                    st.steps > 0 ? static_cast<double>(st.forward_messages) / static_cast<double>(st.steps) : 0.0,
                    st.busy_s, -st.busy_s, st.rebuild_s - st.rebuild_comm_s, st.forward_after_build_s};
    comm_->max(std::span<double>(v));
    std::int64_t t[4] = {static_cast<std::int64_t>(st.owned), static_cast<std::int64_t>(st.ghosts),
                         static_cast<std::int64_t>(st.forward_bytes), static_cast<std::int64_t>(st.rebuild_bytes)};
    comm_->sum(std::span<std::int64_t>(t));
    std::string cells;
    for (int a = 0; a < Dim; ++a) {
      cells += (a ? " x " : "") + std::to_string(layout->cells()[a] / layout->counts()[a]);
    }
    const double steps = std::max<double>(1.0, static_cast<double>(st.steps));
    const double ranks = comm_->size();
    return fmt::format("decomposition: {} blocks of {}+ cells over {} ranks along the Hilbert curve; particles per "
                       "rank {:.0f}-{:.0f}, ghosts {:.3f} per owned particle, up to {:.0f} partner ranks; blocks dealt "
                       "again {} times (largest/mean rank compute time at the last check {:.3f}, threshold {}); DEM "
                       "compute {:.2f}-{:.2f} s per rank; communication over {} steps, per rank: {:.1f} kB in {:.1f} messages a step to the "
                       "ghosts, {:.1f} kB a step in list builds; time inside it (waits for the other ranks included), "
                       "the most of any rank: {:.3f} s forwarding ghosts ({:.3f} s of it after steps with a list "
                       "build), {:.3f} s in the step's reduction, {:.3f} s in list-build exchanges (and {:.3f} s of "
                       "their packing and ghost search, within the compute time)",
                       layout->blocks(), cells, comm_->size(), -v[1], v[0],
                       t[0] > 0 ? static_cast<double>(t[1]) / static_cast<double>(t[0]) : 0.0, v[2], st.rebalances,
                       v[3], config_.parallel.rebalance_threshold, -v[9], v[8], st.steps, t[2] / ranks / steps / 1e3,
                       v[7], t[3] / ranks / steps / 1e3, v[4], v[11], v[5], v[6], v[10]);
  }
  std::string describe() const override {
    const std::uint64_t n = sim_.dem().total_particles();
    if (!sim_.has_gas()) {
      return fmt::format("DEM, {} particles, dt = {:g} s, no gas", n, sim_.dem().config().dt);
    }
    return fmt::format("CFD-DEM{}, {} particles, dt = {:g} s, gas {} x {}{} cells every {} DEM step{}",
                       Dim == 3 ? " in 3D" : "", n, sim_.dem().config().dt,
                       config_.grid.nx, config_.grid.ny, Dim == 3 ? fmt::format(" x {}", config_.grid.nz) : "",
                       config_.coupling.dem_substeps, config_.coupling.dem_substeps == 1 ? "" : "s");
  }

 private:
  /// Every rank builds the same particles (read, placed, or settled together), each keeping its own once the
  /// solver is distributed; files are written by rank 0.
  static ParticleStore<Dim> initial_particles(const CaseConfig& c, const std::string& out_dir, spdlog::logger& log,
                                              const Comm& comm) {
    namespace fs = std::filesystem;
    auto resolve = [&](const std::string& f) { return case_relative_path(c.source_path, f); };
    ParticleStore<Dim> p;
    const fs::path cache = c.settle.cache.empty() ? fs::path() : resolve(c.settle.cache);
    const bool cached = !cache.empty() && c.settle.enabled && fs::exists(cache);
    const std::string stale = cached ? settle_cache_mismatch(c, cache) : std::string();
    if (c.particles.source == ParticleSource::File) {
      p = particles_from_csv<Dim>(resolve(c.particles.file).string(), c.dem);
      log.info("read {} particles from {}", p.size(), resolve(c.particles.file).string());
    } else if (cached && stale.empty()) {
      p = particles_from_csv<Dim>(cache.string(), c.dem);
      log.info("reusing the settled bed {} ({} particles)", cache.string(), p.size());
    } else {
      if (cached) {
        log.info("not reusing the settled bed {}: {}; settling anew", cache.string(),
                 stale == "no record" ? "it has no record of what it was settled with (" +
                                            settled_bed_record_path(cache).string() + ")"
                                      : "it was settled with other parameters: " + stale);
      }
      p = place_random<Dim>(c.dem, c.particles.packing);
      log.info("placed {} particles at random (seed {})", p.size(), c.particles.packing.seed);
      if (c.settle.enabled) {
        // The bed settles under a lid: light particles rebounding off the pile can rise above a top placed at the
        // fill height, and a container is closed while it is filled. The lid touches nothing until a particle
        // reaches it (placement keeps half a gap from it), so a bed that never rises there settles as before.
        DemConfig vacuum = c.dem;
        vacuum.walls.top = true;
        vacuum.walls.top_outflow = false;
        // A container while it is filled: walls on the outflow sides too (a periodic axis stays periodic).
        vacuum.walls.left = vacuum.walls.right = vacuum.walls.bottom = vacuum.walls.back = vacuum.walls.front = true;
        vacuum.walls.side_outflow = {};
        vacuum.insertion = InsertionConfig{};
        CaseConfig settle_case = c;
        settle_case.dem = vacuum;
        settle_case.gas_enabled = false;
        DemSolver<Dim> settler = make_solver(settle_case, std::move(p), comm);
        const auto t0 = std::chrono::steady_clock::now();
        SettleResult r;
        try {
          r = settle_bed(settler, c.settle.kinetic_energy_per_particle, c.settle.max_time);
        } catch (const Error& e) {
          if (e.kind() != ErrorKind::SimulationFailed) throw;
          throw_simulation_error(fmt::format("while settling the bed in vacuum before t = 0 (settle.*): {}", e.what()));
        }
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        p = settler.distributed() ? settler.all_particles(-1) : std::move(settler.particles());
        log.info("settled in vacuum for {:.3f} s ({} steps, {:.1f} s wall): kinetic energy {:.3g} J per particle{}",
                 r.time, r.steps, wall, r.kinetic_energy_per_particle,
                 r.converged ? "" : " (max_time reached before the threshold)");
        ParticleArrays settled = particle_arrays(p);
        settled.own_sizes = p.has_own_sizes(c.dem.species);
        if (comm.rank() == 0) write_particles_csv(fs::path(out_dir) / "settled.csv", settled);
        if (!c.settle.cache.empty() && comm.rank() == 0) {
          fs::create_directories(cache.parent_path());
          write_particles_csv(cache, settled);
          write_file_atomic(settled_bed_record_path(cache), settled_bed_record(c));
          log.info("saved the settled bed to {}", cache.string());
        }
      }
    }
    const double h = bed_height<Dim>(p, c.dem.domain.width, 30);
    p.layer.resize(p.size());
    assign_layers(p.y, p.layer, c.particles.layers, h);
    log.info("bed height {:.4f} m, {} colour layers", h, c.particles.layers);
    return p;
  }

  /// Where the deepest contact (relative to its own diameter) is, for the overlap diagnosis: the particle pair
  /// (from the neighbour list) or the particle and wall; the deepest over every rank (collective). Runs only on the
  /// failure path.
  std::string deepest_contact() const {
    double worst = -1.0;
    const std::string where = deepest_contact_here(worst);
    return comm_->first_failure(where, -worst).value_or(where);
  }
  std::string deepest_contact_here(double& worst) const {
    const ParticleStore<Dim>& p = sim_.dem().particles();
    const NeighborList<Dim>& nbr = sim_.dem().neighbors();
    auto at = [&](std::size_t i) {
      return Dim == 2 ? fmt::format("({:.6g}, {:.6g})", p.x[i], p.y[i])
                      : fmt::format("({:.6g}, {:.6g}, {:.6g})", p.x[i], p.y[i], p.coord(Dim - 1)[i]);
    };
    std::string where;
    for (std::size_t i = 0; i < sim_.dem().owned(); ++i) {
      for (std::size_t k = nbr.offset[i]; k < nbr.offset[i + 1]; ++k) {
        const std::size_t j = nbr.partner[k];
        const double ov = (p.radius[i] + p.radius[j] - norm(p.pos(j) - p.pos(i))) / (2.0 * std::min(p.radius[i], p.radius[j]));
        if (ov > worst) {
          worst = ov;
          const std::size_t a = p.id[i] < p.id[j] ? i : j, b = a == i ? j : i;
          where = fmt::format("particles {} (d = {:.3g} m) and {} (d = {:.3g} m) at {} m and {} m", p.id[a],
                              2.0 * p.radius[a], p.id[b], 2.0 * p.radius[b], at(a), at(b));
        }
      }
      static constexpr const char* kSide[6] = {"left", "right", "bottom", "top", "back", "front"};
      const Vec<Dim> extent = config_.dem.domain.template extent<Dim>();
      const double r = p.radius[i];
      for (int axis = 0; axis < Dim; ++axis) {
        const double x = p.coord(axis)[i];
        for (int high = 0; high < 2; ++high) {
          const double ov = (high ? x + r - extent[axis] : r - x) / (2.0 * r);
          const int w = 2 * axis + high;
          if (ov > worst && (w != 3 || config_.dem.walls.top)) {
            worst = ov;
            where = fmt::format("particle {} at {} m and the {} wall", p.id[i], at(i), kSide[w]);
          }
        }
      }
    }
    return where;
  }

  /// Fraction of the bed's initial mass that has left through an outflow top.
  double lost_fraction() const {
    const double lost = sim_.dem().removed_mass();
    const double left = sim_.dem().total_mass();
    return lost > 0.0 ? lost / (lost + left) : 0.0;
  }
  /// How much of the bed has left: 0 nothing, then above 0, 1%, 10%, 50% of its mass.
  int loss_level() const {
    const double f = lost_fraction();
    int level = 0;
    for (const double mark : {0.0, 0.01, 0.1, 0.5}) level += f > mark ? 1 : 0;
    return level;
  }
  /// A log line when the first particle leaves and when the loss passes 1%, 10% and 50% of the bed.
  void report_losses() {
    loss_level_ = loss_level();
    const std::uint64_t n = sim_.dem().removed_count();
    log_->warn("t = {:.4g} s: {} particle{} ({:.3g} kg, {:.2g}% of the bed's mass) left through the outflow top so "
               "far (domain.particle_top = \"outflow\"; monitor.csv columns particles_lost, mass_lost_kg)",
               time(), n, n == 1 ? "" : "s", sim_.dem().removed_mass(), 100.0 * lost_fraction());
  }

  static constexpr const char* kFaceName[3] = {"u", "v", "w"};  ///< checkpoint names of the face velocities
  CaseConfig config_;
  const Comm* comm_;
  CfdDemSimulation<Dim> sim_;
  mutable ParticleStore<Dim> gathered_;  ///< distributed: every rank's particles on rank 0, for particles()
  spdlog::logger* log_;
  std::vector<double> p_view_;  ///< the gas pressure without its ghosts, as the writers and observers take it
  int loss_level_ = 0;
  std::uint64_t lost_seen_ = 0;
  double last_step_ = 0.0;  ///< of the last advance(), s
};

}  // namespace

std::unique_ptr<ModelRun> make_dem_model(const CaseConfig& config, const std::string& out_dir, bool fresh,
                                         spdlog::logger& log, const Comm& comm) {
  if (config.domain.dimension == 3) return std::make_unique<DemModel<3>>(config, out_dir, fresh, log, comm);
  return std::make_unique<DemModel<2>>(config, out_dir, fresh, log, comm);
}

}  // namespace fluidbed
