#pragma once
// The soft-sphere DEM of the paper's section 2.1: contact forces (Eqs. 2-8, or the law the case composes,
// contact_law.hpp), torques (Eq. 9) and the explicit update of Eq. 10, with plane walls on both sides of every axis
// (or periodic axes, or outflow sides) and a Verlet neighbour list carrying the contact history, keyed by particle
// ids, across rebuilds. One code for 2D discs of sphere mass (spin about z) and 3D
// spheres (spin vector); instantiated for Dim = 2 and 3.
#include <array>
#include <cmath>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "dem/contact_law.hpp"
#include "dem/dem_config.hpp"
#include "dem/held_springs.hpp"
#include "dem/neighbor_list.hpp"
#include "dem/particle_domain.hpp"
#include "dem/particle_store.hpp"
#include "dem/wall_springs.hpp"
#include "parallel/comm.hpp"

namespace fluidbed {

/// Plane walls, numbered 2 axis + side: the particle store's wall springs and WallConfig use this order.
enum class Wall : int { Left = 0, Right = 1, Bottom = 2, Top = 3, Back = 4, Front = 5 };

/// Diagnostics of one step, cheap enough to compute every step.
struct DemStepInfo {
  double max_overlap = 0.0;  ///< m
  bool rebuilt = false;
  std::size_t removed = 0;   ///< particles that left through an outflow side in this step (all ranks)
  std::size_t inserted = 0;  ///< particles added by the feed (DemConfig::insertion) after this step
};

/// What the decomposition of a distributed run costs, for docs/parallel.md's model: counts of this rank.
struct DemParallelStats {
  std::size_t owned = 0;
  std::size_t ghosts = 0;           ///< copies of other ranks' particles held now
  std::size_t ghost_sends = 0;      ///< particles this rank sends to others each step
  int partners = 0;                 ///< ranks it exchanges ghosts with
  std::uint64_t migrated = 0;       ///< particles that arrived from other ranks since the start
  std::uint64_t rebalances = 0;     ///< times the blocks were dealt again
  double imbalance = 1.0;           ///< largest over mean rank compute time at the last check
  double busy_s = 0.0;              ///< this rank's DEM compute seconds since the start (communication left out)
  // Communication since the start, this rank: the ghosts' positions every step (forward), the step's reduction,
  // the list builds' distributed part (balance check, migration and ghost set-up: rebuild_s in all, of it
  // rebuild_comm_s inside communication calls, the rest packing and searching). Seconds of wall time inside them
  // (waiting for the slowest partner included), bytes sent, messages sent.
  std::uint64_t steps = 0;
  double forward_s = 0.0, reduce_s = 0.0, rebuild_s = 0.0, rebuild_comm_s = 0.0;
  double forward_after_build_s = 0.0;  ///< of forward_s, in steps that began with a list build (the rest: plain steps)
  std::uint64_t forward_bytes = 0, rebuild_bytes = 0;
  std::uint64_t forward_messages = 0, rebuild_messages = 0;
};

template <int Dim>
class DemSolver {
 public:
  using Store = ParticleStore<Dim>;
  using List = NeighborList<Dim>;

  /// The particles are put in the canonical storage order (ascending id) first: the run then depends only on the
  /// particles, not on the order they were handed over in. Ids must be unique. Contact history starts released.
  DemSolver(DemConfig config, Store particles);

  /// Split the run over the ranks of `comm` (docs/parallel.md): the grid of `cells` cells of size h from `origin`
  /// (the gas grid, or any grid over the box) is cut into blocks at least one ghost reach wide, dealt along the
  /// Hilbert curve by their particle counts; each rank keeps the particles of its blocks, and holds ghosts of the
  /// others' within the contact reach and within `kernel_reach` per axis (the coupling's deposition kernel, 0
  /// without gas), both plus a skin. Every rank must hold the same particles here (or the same restored state).
  /// Blocks are dealt again when the largest rank cost exceeds `rebalance_threshold` times the mean (at a counted
  /// list rebuild; the results do not change). On one rank the solver stays as it is.
  void distribute(const Comm& comm, const Index<Dim>& cells, const Vec<Dim>& h, const Vec<Dim>& origin,
                  const Vec<Dim>& kernel_reach, double rebalance_threshold = 1.2);
  bool distributed() const { return domain_.has_value(); }
  /// Whether a fluid acts on the particles: the update reads drag_k, the gas velocity and force_ext (the default,
  /// right for whatever the store holds), or, for a run known to have no gas, the store gives those arrays up.
  void couple_to_fluid(bool on) {
    fluid_ = on;
    p_.hold_fluid_arrays(on);
  }
  const Comm& comm() const { return domain_ ? domain_->comm() : serial_comm(); }
  /// The block layout of a distributed run (null on one rank).
  const BlockLayout<Dim>* layout() const { return domain_ ? &domain_->layout() : nullptr; }
  /// Particles this rank owns: slots [0, owned()) of particles(); the slots after are ghosts, copies of other
  /// ranks' particles (none on one rank).
  std::size_t owned() const { return n_owned_; }
  /// Particles over all ranks (collective in a distributed run).
  std::uint64_t total_particles() const;
  /// Every rank's owned particles in ascending id, on rank `root` (empty elsewhere) or, with root = -1, on every
  /// rank. Collective.
  Store all_particles(int root) const;
  /// Counts of this rank's decomposition (zeros on one rank).
  DemParallelStats parallel_stats() const;
  /// Changes whenever the store's slots change (a rebuild, a removal, a feed): a cache of per-slot data keys on it.
  std::uint64_t store_generation() const { return generation_; }
  /// The slots of the store (owned and ghosts) in ascending (order key, id): the order every per-cell sum over
  /// particles takes, the same on any split of the particles over ranks. On one rank it is the storage order itself
  /// (the store is sorted so at the sorting rebuilds), so the sums stream through memory.
  std::span<const std::uint32_t> canonical_order() const;

  /// Advance by one time step of config().dt.
  DemStepInfo step();
  /// Advance by one step of length h (a shortened last step that lands on an end time); the clock continues
  /// from there in steps of config().dt.
  DemStepInfo step(double h);
  /// Contact forces and torques for the current positions (into particles().force, torque), no update.
  double compute_forces() { return compute_forces(config_.dt); }

  const DemConfig& config() const { return config_; }
  Store& particles() { return p_; }
  const Store& particles() const { return p_; }
  std::uint64_t step_count() const { return steps_; }
  std::uint64_t rebuild_count() const { return rebuilds_; }
  /// Simulated time: the time of the last clock origin plus whole steps of config().dt since it, so that it does
  /// not drift as a running sum of dt would.
  double time() const { return time_; }
  void set_time(double t, std::uint64_t steps) {
    time_ = t;
    steps_ = steps;
    time_origin_ = t;
    steps_origin_ = steps;
  }
  /// Call the time exactly t after a step that ended within round-off of t; the clock keeps its origin, so later
  /// steps continue the sequence of whole steps.
  void land_time(double t) { time_ = t; }

  /// Translational plus rotational kinetic energy, J, summed exactly (the same bits for any order and split of the
  /// particles; collective in a distributed run).
  double kinetic_energy() const;
  /// Total mass of the particles, kg (exact, collective as kinetic_energy).
  double total_mass() const;
  /// Largest overlap of the last force evaluation, m.
  double max_overlap() const { return max_overlap_; }
  /// Largest overlap of the last force evaluation relative to its own contact: the smaller diameter of the pair,
  /// or the particle's diameter against a wall.
  double max_overlap_fraction() const { return max_overlap_fraction_; }
  /// Particles removed through an outflow side since the start of the run, and their mass (kg).
  std::uint64_t removed_count() const { return removed_count_; }
  double removed_mass() const { return removed_mass_; }
  /// Particles added by the feed since the start of the run, and their mass (kg): with the removed ones, the
  /// balance M(t) = M(0) + inserted_mass - removed_mass.
  std::uint64_t inserted_count() const { return feed_.inserted; }
  double inserted_mass() const { return feed_.mass; }
  /// The periodic axes the solver applies (DomainConfig::periodic).
  const PeriodicBox<Dim>& periodic() const { return periodic_; }

  /// The feed's counters: what it has added, how many random draws it has used, the id the next particle gets.
  struct FeedState {
    std::uint64_t inserted = 0;
    double mass = 0.0;
    std::uint64_t draws = 0;
    std::int64_t next_id = 0;
  };
  const ContactParams& pair_params(int a, int b) const {
    return pair_params_[static_cast<std::size_t>(a) * config_.n_species() + static_cast<std::size_t>(b)];
  }
  const ContactParams& wall_params(int species) const { return wall_params_[static_cast<std::size_t>(species)]; }

  /// The complete DEM state, storage order, neighbour list and wall springs included, so that a restart continues
  /// bit for bit as the uninterrupted run would have.
  struct State {
    Store particles;
    List neighbors;
    WallSprings<Dim> walls;  ///< tangential springs against the plane walls, by particle slot
    std::array<std::vector<double>, Dim> build;  ///< positions at the last list build, per axis
    double time = 0.0;
    std::uint64_t steps = 0;
    std::uint64_t rebuilds = 0;
    bool need_rebuild = true;
    double time_origin = 0.0;
    std::uint64_t steps_origin = 0;
    std::uint64_t removed_count = 0;
    double removed_mass = 0.0;
    FeedState feed{};
    std::vector<Spin<Dim>> wall_roll;  ///< rolling springs against the walls (rolling-spring laws only)
    /// The pair springs by partner id, when `neighbors` is empty (a portable state: any storage order, any
    /// number of ranks); the list is then built anew before the next force evaluation.
    HeldSprings<Dim> held{};
  };
  State state() const;
  /// The state of every particle (all ranks gathered on rank 0, ascending id), its springs by partner id and no
  /// neighbour list: what a checkpoint keeps, restorable on any number of ranks. Collective; the other ranks get
  /// a state without particles.
  State portable_state() const;
  /// What a checkpoint writes: the portable state, with the particle arrays read where they are. On one process
  /// the store, the wall springs, the list-build positions and the springs by partner id are the solver's own,
  /// read through `order` (the slot of each particle in ascending id), and `state` holds the clock and the feed:
  /// no copy of the store, which was the run's memory peak at its last checkpoint, nor of the springs (the peak
  /// of a settled bed's, section 39 of docs/performance.md). On several ranks `state` is portable_state() (rank 0
  /// holds every particle, the others none) and `order` the identity. Collective. The arrays stay valid until the
  /// solver steps.
  struct CheckpointView {
    State state;
    std::vector<std::uint32_t> order;
    const Store* own_particles = nullptr;  ///< one process: the solver's store; else state.particles
    const WallSprings<Dim>* own_walls = nullptr;
    const std::vector<Spin<Dim>>* own_wall_roll = nullptr;
    std::array<const std::vector<double>*, Dim> own_build{};
    const HeldSprings<Dim>* own_held = nullptr;  ///< one process: the solver's, in its storage order
    const Store& particles() const { return own_particles ? *own_particles : state.particles; }
    /// The springs by partner id, particle order[k]'s k-th (in ascending id).
    const HeldSprings<Dim>& held() const { return own_held ? *own_held : state.held; }
    const WallSprings<Dim>& walls() const { return own_walls ? *own_walls : state.walls; }
    const std::vector<Spin<Dim>>& wall_roll() const { return own_wall_roll ? *own_wall_roll : state.wall_roll; }
    const std::vector<double>& build(int a) const {
      const auto k = static_cast<std::size_t>(a);
      return own_build[k] ? *own_build[k] : state.build[k];
    }
  };
  CheckpointView checkpoint_view() const;
  /// Whether some particle's size differs from its species' diameter (a size distribution, or a file's sizes).
  bool has_own_sizes() const { return sized_; }
  /// Restores a state(): with its neighbour list it continues as saved; a portable state (no list) on any number
  /// of ranks, each keeping the particles of its blocks (after distribute()).
  void restore(State s);
  const List& neighbors() const {
    sync_list_springs();
    return nbr_;
  }
  /// The tangential springs against the plane walls.
  const WallSprings<Dim>& wall_springs() const { return walls_; }

  /// Builds the neighbour list and, distributed, the ghosts now when they are due (a fresh solver, a restored
  /// state): what a deposition before the first step needs on several ranks. Changes no result.
  void prepare() {
    // Not counted: the Verlet trigger's rebuild, when due, still comes at the next step, as on one rank.
    if (domain_ && (list_stale_ || need_rebuild_ || nbr_.offset.size() != p_.size() + 1)) rebuild(false);
  }

  /// Ask for a neighbour-list rebuild before the next force evaluation (e.g. after particles were moved).
  void invalidate_neighbors() { need_rebuild_ = true; }

 private:
  DemStepInfo advance(double h);
  double compute_forces(double dt);
  /// compute_forces for a box with (Periodic) or without periodic axes: the law chosen, the pass run.
  template <bool Periodic>
  double compute_forces_on(double dt);
  /// Law: the composed contact law (contact_law.hpp); Mixed: species looked up per contact, overlap judged per
  /// contact; Periodic: minimum-image separations; Sized: particles have their own sizes, so the paper's dashpot
  /// (Eq. 8) is taken on each pair's own reduced mass.
  template <class Law, bool Mixed, bool Periodic, bool Sized>
  double compute_forces_of(double dt);
  /// The pointwise contact functions and the loops of compute_forces_of, over the pointers it hoists once.
  template <class Law, bool Mixed, bool Periodic, bool Sized>
  struct ForcePass;
  /// A new neighbour list (and, distributed, migration and ghosts). Counted: the Verlet trigger's (the positions of
  /// the build are kept and the count rises); not counted: the same list for other reasons (a restore, a removal
  /// on several ranks), which changes no result and leaves the trigger's schedule alone.
  void rebuild(bool counted);
  /// The springs of the owned particles' list entries into held_ (by partner id).
  void gather_held_springs();
  /// The owned particles' springs by partner id as they are now: held_, gathered from the list first when the list
  /// holds them (held_ is then out of date, and no one reads it before the next rebuild gathers it anew).
  const HeldSprings<Dim>& current_held_springs() const;
  /// A State with the clock, the removal and feed counters, and no particles or springs.
  State clock_state() const;
  /// held_'s springs into records named by the entries of the same pairs in the new list.
  void carry_held_springs();
  /// Keep the owned particles `order` names (in that order), with everything that is theirs; ghosts are dropped.
  /// With `springs_later` the springs by partner id stay where they are, read through held_from_ by the
  /// carry_held_springs that follows (a rebuild's sort: a copy of them would be its peak of memory).
  void select_owned(const std::vector<std::size_t>& order, bool springs_later = false);
  /// Distributed: the ghosts leave the store (the owned slots stay as they are).
  void drop_ghosts();
  /// Distributed: the particles whose block belongs to another rank go there, with their springs.
  void migrate(bool dealt_again);
  /// Distributed: deal the blocks again when the ranks' costs are out of balance.
  bool rebalance_if_needed();  ///< whether the blocks were dealt again (collective)
  void measure_costs();
  /// At a sorting rebuild: each owned particle's order key (its cell of a global lattice of the list's cell size)
  /// and the order (key, id) the store takes.
  std::vector<std::size_t> assign_order_keys();
  /// Distributed: ghosts follow their owners; the flags and largest overlaps of the step reduced over ranks.
  void finish_step_distributed(int& moved_far, int& bad, int& escaped);
  void link_mirrors();
  /// link_mirrors without a search, for lists in the canonical order, visited in it (`visit`: the slots in that
  /// order; empty when it is the slots' own); false (links unfinished) for any other list.
  bool link_sorted_mirrors(std::span<const std::uint32_t> visit);
  /// Drop the particles whose centre is beyond an outflow side, keeping the order of the others, their neighbour
  /// entries and contact springs; counts them and their mass.
  std::size_t remove_escaped();
  std::size_t remove_escaped_distributed();
  /// The feed: add the particles due by the current time (DemConfig::insertion), each at the first of its random
  /// draws that overlaps no particle; those not placed within their tries wait for the next step.
  std::size_t insert_due();
  /// Distributed: every rank's particles within reach of the feed's region (positions and radii), on every rank.
  void gather_near_region(std::vector<Vec<Dim>>& x, std::vector<double>& r) const;
  static constexpr std::uint64_t kSortEvery = 16;
  /// The step found a particle outside the domain or not finite: fail naming the one with the smallest id.
  void check_particles() const;
  /// The message check_particles would give for this rank's particles, with the offending id (none: nullopt).
  std::optional<std::pair<std::int64_t, std::string>> particle_failure() const;
  /// Inside the domain (beyond an outflow side counts as inside: it is removed) with a finite state. The bounds
  /// are copied out of the config so that the step's loop keeps them in registers.
  struct DomainTest {
    Vec<Dim> extent;
    std::array<bool, 2 * Dim> outflow;  ///< per side, Wall order
    bool any_outflow;
    /// Coordinate x on axis a within the domain's bounds.
    bool inside(int a, double x) const {
      return (x >= 0.0 || outflow[static_cast<std::size_t>(2 * a)]) &&
             (x <= extent[a] || outflow[static_cast<std::size_t>(2 * a + 1)]);
    }
    /// Beyond an outflow side on axis a.
    bool escaped(int a, double x) const {
      return (x < 0.0 && outflow[static_cast<std::size_t>(2 * a)]) ||
             (x > extent[a] && outflow[static_cast<std::size_t>(2 * a + 1)]);
    }
    bool operator()(const Store& p, std::size_t i) const {
      bool ok = true;
      for (int a = 0; a < Dim; ++a) ok = ok && inside(a, p.coord(a)[i]);
      for (int a = 0; a < Dim; ++a) ok = ok && std::isfinite(p.velocity(a)[i]);
      for (int c = 0; c < kSpinComponents<Dim>; ++c) ok = ok && std::isfinite(p.spin_component(c)[i]);
      return ok;
    }
  };
  DomainTest domain_test() const {
    DomainTest t{config_.domain.extent<Dim>(), {}, false};
    for (int w = 0; w < 2 * Dim; ++w) {
      const bool out = config_.walls.outflow(w) && !config_.walls.enabled(w / 2, w % 2);
      t.outflow[static_cast<std::size_t>(w)] = out;
      t.any_outflow = t.any_outflow || out;
    }
    return t;
  }

  DemConfig config_;
  Store p_;
  WallSprings<Dim> walls_;
  /// Springs of the particles that first touched a wall in the force pass, one list per thread (compute_forces_of).
  struct NewWallSpring {
    std::size_t i;
    int wall;
    Vec<Dim> xi;
  };
  std::vector<std::vector<NewWallSpring>> new_wall_springs_;
  std::vector<ContactParams> pair_params_;
  std::vector<ContactParams> wall_params_;
  /// Eq. 8 per unit square root of mass, eta / sqrt(m_eff), per species pair and per species on a wall, for beds
  /// whose particles have their own sizes (sized_).
  std::vector<double> pair_damping_per_root_mass_;
  std::vector<double> wall_damping_per_root_mass_;
  bool sized_ = false;  ///< some particle's size differs from its species' diameter
  bool fluid_ = true;  ///< couple_to_fluid
  List nbr_;
  std::array<std::vector<double>, Dim> build_;
  /// The owned particles' springs by partner id, in store order: gathered from the list when it is rebuilt, or
  /// restored from a portable state (list_springs_ false until the list is built).
  HeldSprings<Dim> held_;
  /// Between a rebuild's sort and its carry_held_springs: the particle of held_ that slot i was (else empty).
  std::vector<std::size_t> held_from_;
  bool list_springs_ = false;  ///< nbr_ holds the current springs (else held_ does)
  bool list_stale_ = true;     ///< nbr_ must be built anew before the next force evaluation (not counted)
  std::size_t n_owned_ = 0;
  std::optional<ParticleDomain<Dim>> domain_;
  GhostPlan plan_;
  double rebalance_threshold_ = 1.2;
  std::uint64_t generation_ = 0;
  bool key_sorted_ = true;  ///< the store is in ascending (order key, id) (one rank)
  mutable std::vector<std::uint32_t> canonical_;
  mutable std::uint64_t canonical_generation_ = ~0ull;
  std::uint64_t migrated_ = 0, rebalances_ = 0;
  double imbalance_ = 1.0;
  std::vector<int> owned_block_;  ///< per owned particle its block, from migration to the ghost search of one rebuild
  std::vector<double> cost_;  ///< per owned particle when the last verdict dealt (measure_costs)
  double busy_s_ = 0.0;      ///< compute seconds of this rank since the last balance check (waits left out)
  bool step_built_ = false;  ///< the step under way began with a list build
  std::chrono::steady_clock::time_point step_start_{};
  double step_comm_s_ = 0.0;  ///< the communicator's seconds_communicating() when the step began
  DemParallelStats comm_stats_;  ///< the communication counters (the other fields are filled by parallel_stats())
  /// Rolling spring of particle slot i against wall w at wall_roll_[2 Dim i + w], in the store's order (laws with
  /// a rolling spring only, else empty; kept here so that the paper's law does not carry it per particle).
  std::vector<Spin<Dim>> wall_roll_;
  /// Reorder wall_roll_ as ParticleStore::permute reorders the particles.
  void permute_wall_roll(const std::vector<std::size_t>& order);
  NeighborScratch scratch_;  ///< the list build's per-thread buffers, kept so a rebuild does not fault pages in
  // Each contact is evaluated once, by the partner in the lower storage slot, into a record of its own; both list
  // entries of the pair name it, and each particle then sums the records its entries name, in list order.
  // The half list (built by link_mirrors): particle i's entries of higher-slot partners are
  // upper_entry_[upper_offset_[i] .. upper_offset_[i + 1]), upper_mirror_ the partner's entry of the same pair.
  std::vector<std::uint32_t> upper_offset_;  // 32-bit, as the entries it counts
  std::vector<std::uint32_t> upper_entry_, upper_mirror_;
  std::size_t linked_entries_ = 0;  ///< list entries when the half list was built
  /// Per entry 2 c + side: the contact record c (0, a zero record, when not in contact) and the side (0 the lower
  /// slot's entry, which takes +f, 1 the partner's, which takes -f).
  std::vector<std::uint32_t> entry_contact_;
  std::vector<Vec<Dim>> contact_force_;    ///< per record: force on the lower slot
  std::vector<Spin<Dim>> contact_torque_;  ///< per record, two: torque on the lower slot, on the partner
  // The pair springs of the linked list (marked_), by record as contact_force_ numbers them, the lower slot's side
  // (record 0: +0): the pair pass reads and writes them in its own order, where springs per list entry would be
  // read and written at both entries of every pair, far apart, and held for every entry (three to four times the
  // contacts). A new list gets records from the carried springs (carry_held_springs), a restored or copied one from
  // its entries (adopt_entry_springs); sync_list_springs writes them into the entries (nbr_.history, nbr_.rolling)
  // where that form is read. The _next_ arrays are an evaluation's output, swapped in after it.
  std::vector<Vec<Dim>> spring_, spring_next_;
  std::vector<Spin<Dim>> roll_spring_, roll_spring_next_;
  /// Entry q's spring and rolling spring, from its record after an evaluation (the partner's side negated, as the
  /// entries mirror them), else from the entry.
  Vec<Dim> entry_spring(std::size_t q) const { return entry_value(q, spring_, nbr_.history); }
  Spin<Dim> entry_roll(std::size_t q) const { return entry_value(q, roll_spring_, nbr_.rolling); }
  template <class T>
  T entry_value(std::size_t q, const std::vector<T>& records, const std::vector<T>& entries) const {
    if (!marked_) return q < entries.size() ? entries[q] : T{};
    const std::uint32_t e = entry_contact_[q];
    return (e & 1u) != 0 ? -records[e >> 1] : records[e >> 1];
  }
  /// The records' springs into the list's entries (nbr_.history, nbr_.rolling), for the readers of the per-entry
  /// form; const for them (the springs do not change, only where they are written).
  void sync_list_springs() const;
  /// The springs in the entries of a list just linked into records (none: every record +0); the entries let go.
  void adopt_entry_springs();
  /// carry_first_'s per-particle counts (at i + 1) into each particle's first record, from 1; the record arrays
  /// sized for them (record 0 +0; the rolling ones only for a law with a rolling spring).
  void number_records();
  /// Record g: spring xi (and rolling spring) of the pair at half-list place u, named by both its entries.
  void set_record(std::size_t g, std::size_t u, const Vec<Dim>& xi, const Spin<Dim>& roll);
  std::vector<std::uint32_t> carry_at_;  ///< carry_held_springs: per held spring, 1 + its half-list place (0: none)
  /// Per particle, of one pass at a time (a build's mirror linking, then its carrying of springs): link_sorted_mirrors'
  /// next entry per partner; carry_held_springs' and adopt_entry_springs' first record.
  std::vector<std::uint32_t> carry_first_;
  std::vector<std::size_t> contact_base_;  ///< first record of each block
  /// A touching pair of the force pass: its lower slot i and its place u in the half list.
  struct Contact {
    std::uint32_t i, u;
    std::uint32_t record;  ///< the record of the pair's spring in the last evaluation (0: none, a new contact)
  };
  // The touching pairs of the force evaluation, one array per block of particles (one block per thread), with
  // their counts.
  std::vector<std::vector<Contact>> contacts_;
  std::vector<std::size_t> contact_count_;
  /// A force evaluation ran on the current list: entry_contact_ marks its touching pairs, the only entries that
  /// can hold a spring to release.
  bool marked_ = false;
  double cell_size_ = 0.0;
  double max_overlap_ = 0.0;
  double max_overlap_fraction_ = 0.0;
  double time_ = 0.0;
  std::uint64_t steps_ = 0;
  double time_origin_ = 0.0;
  std::uint64_t steps_origin_ = 0;
  std::uint64_t removed_count_ = 0;
  double removed_mass_ = 0.0;
  FeedState feed_{};
  PeriodicBox<Dim> periodic_{};
  std::uint64_t rebuilds_ = 0;
  bool need_rebuild_ = true;
};

extern template class DemSolver<2>;
extern template class DemSolver<3>;

/// Build the contact parameter tables (Eq. 8 with the reduced mass of each species pair).
std::vector<ContactParams> make_pair_params(const DemConfig& c);
std::vector<ContactParams> make_wall_params(const DemConfig& c);

}  // namespace fluidbed
