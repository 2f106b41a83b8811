#include "dem/dem_solver.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>
#include <fmt/format.h>
#include <omp.h>

#include "core/error.hpp"
#include "core/team.hpp"
#include "dem/growth.hpp"
#include "dem/selection.hpp"
#include "dem/kernel_support.hpp"

namespace fluidbed {

using dem_kernel::AxisPtrs;
using dem_kernel::axis_ptrs;
using dem_kernel::spin_norm2;

namespace {
// The parameters of the laws beyond the paper's: Hertz and Mindlin moduli of the two materials, the Tsuji
// coefficient for the restitution (found once here, not per contact), the rolling coefficients.
void set_law_params(const DemConfig& c, const ElasticMaterial& a, const ElasticMaterial& b, const InteractionParams& ip,
                    ContactParams& p) {
  const ContactModelConfig& m = c.contact;
  if (m.normal == NormalModel::Hertz || m.tangential == TangentialModel::Mindlin) {
    p.e_star = effective_youngs_modulus(a, b);
    p.g_star = effective_shear_modulus(a, b);
  }
  if (m.normal == NormalModel::Hertz || m.damping == DampingModel::Tsuji) {
    p.alpha = m.normal == NormalModel::Hertz ? tsuji_alpha_for_hertz(ip.restitution) : tsuji_alpha_for_linear(ip.restitution);
  }
  p.mu_r = ip.rolling_friction;
  p.eta_r = m.rolling_damping;
}
}  // namespace

std::vector<ContactParams> make_pair_params(const DemConfig& c) {
  const std::size_t ns = c.n_species();
  std::vector<ContactParams> t(ns * ns);
  for (std::size_t a = 0; a < ns; ++a) {
    for (std::size_t b = 0; b < ns; ++b) {
      const InteractionParams& ip = c.pair_params(static_cast<int>(a), static_cast<int>(b));
      const double m_eff = reduced_mass(c.species[a].mass(), c.species[b].mass());
      ContactParams& p = t[a * ns + b];
      p.k_n = c.stiffness;
      p.k_t = c.stiffness * c.tangential_stiffness_ratio;
      p.eta_n = damping_from_restitution(m_eff, p.k_n, ip.restitution);  // Eq. 8, reduced mass
      p.eta_t = p.eta_n;  // the paper's single dashpot eta for both directions (Eqs. 2-3)
      p.mu = ip.friction;
      set_law_params(c, c.material_of(a), c.material_of(b), ip, p);
    }
  }
  return t;
}

std::vector<ContactParams> make_wall_params(const DemConfig& c) {
  std::vector<ContactParams> t(c.n_species());
  for (std::size_t a = 0; a < c.n_species(); ++a) {
    ContactParams& p = t[a];
    p.k_n = c.stiffness;
    p.k_t = c.stiffness * c.tangential_stiffness_ratio;
    p.eta_n = damping_from_restitution(c.species[a].mass(), p.k_n, c.wall[a].restitution);  // Eq. 8, wall fixed
    p.eta_t = p.eta_n;
    p.mu = c.wall[a].friction;
    set_law_params(c, c.material_of(a), c.contact.wall_material, c.wall[a], p);
  }
  return t;
}

namespace {

// Particles of a state's arrays as a message: their store records attribute by attribute (pack_particles), then
// each one's wall springs, rolling wall springs, build position and pair springs by partner id; and back,
// appended. The message migration, gathers and checkpoints share.
template <int Dim>
void pack_records(Bytes& b, const ParticleStore<Dim>& p, const WallSprings<Dim>& walls,
                  const std::vector<Spin<Dim>>& wall_roll, const std::array<std::vector<double>, Dim>& build,
                  const HeldSprings<Dim>& held, std::span<const std::uint32_t> slots, std::size_t owned) {
  pack_particles<Dim>(b, p, slots);
  const bool roll = !wall_roll.empty();
  pack(b, static_cast<std::uint8_t>(roll));
  const bool has = held.particles() == owned;
  for (const std::uint32_t i : slots) {
    for (int w = 0; w < 2 * Dim; ++w) pack(b, walls.get(i, w));
    if (roll) {
      for (int w = 0; w < 2 * Dim; ++w) pack(b, wall_roll[i * 2 * Dim + static_cast<std::size_t>(w)]);
    }
    for (int a = 0; a < Dim; ++a) {
      const std::vector<double>& bl = build[static_cast<std::size_t>(a)];
      pack(b, bl.size() == owned ? bl[i] : p.coord(a)[i]);
    }
    const std::size_t q0 = has ? held.offset[i] : 0, q1 = has ? held.offset[i + 1] : 0;
    pack(b, static_cast<std::uint64_t>(q1 - q0));
    for (std::size_t q = q0; q < q1; ++q) {
      pack(b, held.partner_id[q]);
      pack(b, held.xi[q]);
      pack(b, held.keeps_rolling() ? held.roll[q] : Spin<Dim>{});
    }
  }
}

template <int Dim>
std::size_t unpack_records(Unpacker& u, ParticleStore<Dim>& p, WallSprings<Dim>& walls,
                           std::vector<Spin<Dim>>& wall_roll, std::array<std::vector<double>, Dim>& build,
                           HeldSprings<Dim>& held) {
  const std::size_t first = p.size();
  const std::size_t n = unpack_particles(u, p);
  const bool roll = u.get<std::uint8_t>() != 0;
  if (roll || !wall_roll.empty()) wall_roll.resize(2 * Dim * p.size(), Spin<Dim>{});
  for (std::size_t i = first; i < first + n; ++i) {
    walls.push_back();
    for (int w = 0; w < 2 * Dim; ++w) walls.set(i, w, u.get<Vec<Dim>>());
    if (roll) {
      for (int w = 0; w < 2 * Dim; ++w) wall_roll[i * 2 * Dim + static_cast<std::size_t>(w)] = u.get<Spin<Dim>>();
    }
    for (int a = 0; a < Dim; ++a) build[static_cast<std::size_t>(a)].push_back(u.get<double>());
    const auto m = static_cast<std::size_t>(u.get<std::uint64_t>());
    held.add_particle();
    for (std::size_t q = 0; q < m; ++q) {
      const auto id = u.get<std::int64_t>();
      const auto xi = u.get<Vec<Dim>>();
      const auto r = u.get<Spin<Dim>>();
      held.add(id, xi, r);
    }
  }
  return n;
}
}  // namespace

template <int Dim>
DemSolver<Dim>::DemSolver(DemConfig config, Store particles) : config_(std::move(config)), p_(std::move(particles)) {
  pair_params_ = make_pair_params(config_);
  wall_params_ = make_wall_params(config_);
  const std::size_t ns = config_.n_species();
  for (std::size_t a = 0; a < ns; ++a) {
    for (std::size_t b = 0; b < ns; ++b) {
      pair_damping_per_root_mass_.push_back(damping_from_restitution(
          1.0, config_.stiffness, config_.pair_params(static_cast<int>(a), static_cast<int>(b)).restitution));
    }
    wall_damping_per_root_mass_.push_back(damping_from_restitution(1.0, config_.stiffness, config_.wall[a].restitution));
  }
  // Cells of the largest particle that can be present (a species' largest size, or a larger one read from a file)
  // plus the skin: every pair within reach is then in neighbouring cells.
  double d_max = p_.max_diameter();
  for (const Species& s : config_.species) d_max = std::max(d_max, s.d_max());
  cell_size_ = d_max + config_.skin;
  sized_ = p_.has_own_sizes(config_.species);
  periodic_ = config_.domain.periodic_box<Dim>();
  if (config_.domain.periodic[1]) {
    throw_input_error("the y axis cannot be periodic: gravity, the inlet and the outlet lie along it");
  }
  for (int a = 0; a < Dim; ++a) {
    if (!periodic_.periodic(a)) continue;
    // A periodic axis has no walls, and a particle must not meet its own partner twice (directly and through
    // an image), which the image search rules out for periods longer than two reaches.
    const char* names[3] = {"width", "height", "depth"};
    if (!(periodic_.length[a] > 2.0 * cell_size_)) {
      throw_input_error(fmt::format("a periodic axis needs a period above 2 (largest diameter + dem.skin) = {} m; "
                                    "domain.{} is {} m", 2.0 * cell_size_, names[a], periodic_.length[a]));
    }
    if (a == 0) config_.walls.left = config_.walls.right = false;
    if (a == 2) config_.walls.back = config_.walls.front = false;
    config_.walls.side_outflow[static_cast<std::size_t>(2 * a)] = false;
    config_.walls.side_outflow[static_cast<std::size_t>(2 * a + 1)] = false;
    std::vector<double>& x = p_.coord(a);
    for (double& xi : x) {
      if (xi >= 0.0 && xi <= periodic_.length[a]) xi = periodic_.wrap(a, xi);
    }
  }
  p_.sort_by_id();
  // The order keys come from this solver's own sorting rebuilds: a store handed over starts from none (id order).
  std::fill(p_.order_key.begin(), p_.order_key.end(), 0);
  for (std::size_t i = 1; i < p_.size(); ++i) {
    if (p_.id[i] == p_.id[i - 1]) {
      throw_input_error(fmt::format("particle id {} is given twice: every particle needs its own id", p_.id[i]));
    }
  }
  feed_.next_id = p_.size() == 0 ? 0 : p_.id.back() + 1;
  if (config_.insertion.enabled()) {
    const InsertionConfig& in = config_.insertion;
    if (in.species < 0 || static_cast<std::size_t>(in.species) >= config_.n_species()) {
      throw_input_error(fmt::format("insertion.species = {} is not a species index", in.species));
    }
    for (int a = 0; a < Dim; ++a) {
      if (!(in.region_lo[a] <= in.region_hi[a])) throw_input_error("insertion: the region's low corner lies above its high one");
    }
  }
  walls_.reset(p_.size());
  n_owned_ = p_.size();
  held_.clear(p_.size(), config_.contact.needs_rolling_history());
}

template <int Dim>
void DemSolver<Dim>::distribute(const Comm& comm, const Index<Dim>& cells, const Vec<Dim>& h, const Vec<Dim>& origin,
                                const Vec<Dim>& kernel_reach, double rebalance_threshold) {
  if (comm.size() == 1) return;
  rebalance_threshold_ = rebalance_threshold;
  // Ghosts within the contact reach and, with the kernel's cells, a skin beyond: a particle moves less than half the
  // skin between rebuilds, and the deposition happens after the step that sets off a rebuild.
  Vec<Dim> kernel{};
  Index<Dim> per_block{};
  for (int a = 0; a < Dim; ++a) {
    kernel[a] = kernel_reach[a] > 0.0 ? kernel_reach[a] + config_.skin : 0.0;
    const double reach = std::max(cell_size_, kernel[a]);
    per_block[a] = std::max(1, static_cast<int>(std::ceil(reach / h[a] * (1.0 + 1e-12))));
  }
  domain_.emplace(comm, BlockLayout<Dim>(cells, h, origin, per_block, periodic_.on), periodic_);
  domain_->set_reach(cell_size_, kernel);
  for (int a = 0; a < Dim; ++a) {
    const BlockLayout<Dim>& l = domain_->layout();
    if (l.counts()[a] > 1 && l.min_width(a) < domain_->reach(a)) {
      throw_simulation_error(fmt::format("the blocks of the decomposition are {} m wide along axis {}, less than the "
                                         "ghost reach of {} m (internal error)", l.min_width(a), a, domain_->reach(a)));
    }
  }
  // Every rank holds the same particles here: the blocks are dealt by their particle counts, then each keeps its own.
  std::vector<double> weight(static_cast<std::size_t>(domain_->layout().blocks()), 0.0);
  for (std::size_t i = 0; i < p_.size(); ++i) weight[static_cast<std::size_t>(domain_->layout().block_at(p_.pos(i)))] += 1.0;
  domain_->layout().assign(weight, comm.size());
  imbalance_ = imbalance(domain_->layout().rank_weights(weight, comm.size()));
  if (!list_springs_) {
    // A restored (portable) state or a fresh one: nothing is in a list yet.
  } else {
    gather_held_springs();
    list_springs_ = false;
  }
  std::vector<std::size_t> keep;
  for (std::size_t i = 0; i < n_owned_; ++i) {
    if (domain_->owner_of(p_.pos(i)) == comm.rank()) keep.push_back(i);
  }
  select_owned(keep);
  list_stale_ = true;
}

template <int Dim>
std::uint64_t DemSolver<Dim>::total_particles() const {
  std::int64_t n[1] = {static_cast<std::int64_t>(n_owned_)};
  comm().sum(std::span<std::int64_t>(n));
  return static_cast<std::uint64_t>(n[0]);
}

template <int Dim>
typename DemSolver<Dim>::Store DemSolver<Dim>::all_particles(int root) const {
  Bytes mine;
  std::vector<std::uint32_t> slots(n_owned_);
  for (std::size_t i = 0; i < n_owned_; ++i) slots[i] = static_cast<std::uint32_t>(i);
  pack_particles<Dim>(mine, p_, slots);
  const std::vector<Bytes> all = root < 0 ? comm().allgather(mine) : comm().gather(mine, root);
  Store out;
  for (const Bytes& b : all) {
    Unpacker u(b);
    while (!u.done()) unpack_particles(u, out);
  }
  out.sort_by_id();
  return out;
}

template <int Dim>
DemParallelStats DemSolver<Dim>::parallel_stats() const {
  DemParallelStats s = comm_stats_;
  s.owned = n_owned_;
  s.ghosts = p_.size() - n_owned_;
  s.ghost_sends = plan_.sent();
  s.partners = static_cast<int>(plan_.ranks.size());
  s.migrated = migrated_;
  s.rebalances = rebalances_;
  s.imbalance = imbalance_;
  return s;
}

template <int Dim>
void DemSolver<Dim>::rebuild(bool counted) {
  // The springs of the owned particles by partner id: only the held ones (about one entry in four in a packed bed),
  // not a copy of the whole old list, so the rebuild needs little memory beyond the list itself.
  if (list_springs_) gather_held_springs();
  list_springs_ = false;
  marked_ = false;  // the records belong to the list about to go (measure_costs reads only its contact marks)
  if (domain_) {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = domain_->comm().seconds_communicating();
    const bool dealt_again = counted && rebalance_if_needed();  // from the list about to go, when it deals
    drop_ghosts();  // the new set comes after migration
    migrate(dealt_again);
    comm_stats_.rebuild_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    comm_stats_.rebuild_comm_s += domain_->comm().seconds_communicating() - c0;
  }
  // Re-sort by cell only every few rebuilds: the list itself does not need sorted storage, and particles drift
  // from their cells slowly, so memory locality is kept at a fraction of the permutation cost.
  if (counted && rebuilds_ % kSortEvery == 0) {
    std::vector<std::size_t> order = assign_order_keys();
    select_owned(order, true);
    if (held_.particles() == order.size()) held_from_ = std::move(order);
    key_sorted_ = true;
  } else if (!domain_) {
    walls_.compact();  // springs back at +0 give up their records
  }
  if (counted) {
    for (int a = 0; a < Dim; ++a) build_[static_cast<std::size_t>(a)] = p_.coord(a);
  }
  n_owned_ = p_.size();
  if (domain_) {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = domain_->comm().seconds_communicating();
    plan_ = domain_->exchange_ghosts(p_, n_owned_, owned_block_);
    owned_block_.clear();  // the positions move on
    comm_stats_.rebuild_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    comm_stats_.rebuild_comm_s += domain_->comm().seconds_communicating() - c0;
    comm_stats_.rebuild_bytes += plan_.sent() * ParticleStore<Dim>::bytes_per_particle();
    comm_stats_.rebuild_messages += plan_.ranks.size();
    ++generation_;  // new ghosts in new slots
  }
  // Each particle's partners in the canonical order (ascending order key and id), the order its forces are summed in:
  // on one rank after a sorting rebuild the slots themselves, else their places in that order.
  std::vector<std::uint32_t> rank;
  if (domain_ || !key_sorted_) {
    const std::span<const std::uint32_t> order = canonical_order();
    rank.resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) rank[order[k]] = static_cast<std::uint32_t>(k);
  }
  build_neighbor_list(p_, n_owned_, cell_size_, config_.skin, nbr_, scratch_, periodic_, rank);
  link_mirrors();
  carry_held_springs();
  list_springs_ = true;
  list_stale_ = false;
  if (counted) {
    need_rebuild_ = false;
    ++rebuilds_;
  }
}

template <int Dim>
void DemSolver<Dim>::gather_held_springs() {
  const std::size_t n = n_owned_;
  const bool rolling_law = config_.contact.needs_rolling_history();
  HeldSprings<Dim>& h = held_;
  h.clear(n, rolling_law);
  if (nbr_.offset.size() < n + 1) return;
  // After a force evaluation on this list only its touching pairs (marked with a record) can hold a spring, the
  // others naming the record of +0; before one, the entries hold them. The tests are combined without branches:
  // about one entry in three holds a spring, in no pattern a branch predictor could follow.
  const bool rolling = rolling_law && (marked_ ? roll_spring_.size() == spring_.size()
                                               : nbr_.rolling.size() == nbr_.history.size());
  auto held = [&](std::size_t q) {
    bool keep = !HeldSprings<Dim>::plus_zero(entry_spring(q));
    if (rolling) keep = keep | !HeldSprings<Dim>::plus_zero(entry_roll(q));
    return keep;
  };
  // Counted, then copied, both in parallel over the particles (the entries land in list order either way).
  const auto sn = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    std::size_t c = 0;
    for (std::size_t q = nbr_.offset[i]; q < nbr_.offset[i + 1]; ++q) c += static_cast<std::size_t>(held(q));
    h.offset[i + 1] = static_cast<std::uint32_t>(c);  // at most the list's entries: 32-bit
  }
  for (std::size_t i = 0; i < n; ++i) h.offset[i + 1] += h.offset[i];
  const std::size_t m = h.offset[n];
  h.partner_id.resize(m);
  h.xi.resize(m);
  h.roll.resize(rolling_law ? m : 0);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    std::size_t c = h.offset[i];
    // The held entries picked out without a branch, in chunks, then copied.
    constexpr std::size_t kChunk = 64;
    std::size_t pick[kChunk];
    for (std::size_t q0 = nbr_.offset[i], end = nbr_.offset[i + 1]; q0 < end; q0 += kChunk) {
      std::size_t m = 0;
      for (std::size_t q = q0; q < std::min(end, q0 + kChunk); ++q) {
        pick[m] = q;
        m += static_cast<std::size_t>(held(q));
      }
      for (std::size_t t = 0; t < m; ++t, ++c) {
        const std::size_t q = pick[t];
        h.partner_id[c] = p_.id[nbr_.partner[q]];
        h.xi[c] = entry_spring(q);
        if (rolling_law) h.roll[c] = rolling ? entry_roll(q) : Spin<Dim>{};
      }
    }
  }
}

template <int Dim>
void DemSolver<Dim>::carry_held_springs() {
  // Each held spring to the record of the same pair in the new list, found by the partner's id (so that it does not
  // matter where either partner is stored now); a pair that left the list had released its spring (it was beyond
  // contact). The lower slot's copy makes the record (its entry is the record's side 0, as the force pass numbers
  // them); the partner holds the same spring negated. Records are numbered particle after particle.
  if (held_.particles() != n_owned_) return;  // nothing held (a fresh solver)
  const bool rolling = held_.keeps_rolling() && config_.contact.needs_rolling_history();
  const std::size_t n = n_owned_;
  // Slot i's springs: held_'s particle i, or the one it was before a sort (held_from_). held_'s entries are
  // numbered in its own order, which `at` follows.
  const std::vector<std::size_t> from = std::exchange(held_from_, {});
  const auto row = [&from](std::size_t i) { return from.empty() ? i : from[i]; };
  std::vector<std::uint32_t>& at = carry_at_;  // per held spring: 1 + its place u in the half list, or 0
  at.assign(held_.offset[n], 0);
  std::vector<std::uint32_t>& first = carry_first_;
  first.assign(n + 1, 0);
  const auto sn = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const std::size_t u0 = upper_offset_[i], u1 = upper_offset_[i + 1];
    // The search goes on from the last match, round the half list once: both lists hold the partners in the
    // canonical order, which changes only at a sorting rebuild, so each entry is usually looked at once. A partner
    // is in a list at most once (a period spans more than two reaches). A partner below i is not found: its own
    // copy makes the record.
    std::size_t u = u0, found = 0;
    for (std::size_t q = held_.offset[row(i)]; q < held_.offset[row(i) + 1]; ++q) {
      const std::int64_t j = held_.partner_id[q];
      for (std::size_t step = u0; step < u1; ++step, ++u) {
        if (u == u1) u = u0;
        if (p_.id[nbr_.partner[upper_entry_[u]]] == j) {
          at[q] = static_cast<std::uint32_t>(u + 1);
          ++found;
          ++u;
          break;
        }
      }
    }
    first[i + 1] = found;
  }
  number_records();
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    std::size_t g = first[i];
    for (std::size_t q = held_.offset[row(i)]; q < held_.offset[row(i) + 1]; ++q) {
      if (at[q] != 0) set_record(g++, at[q] - 1, held_.xi[q], rolling ? held_.roll[q] : Spin<Dim>{});
    }
  }
}

template <int Dim>
void DemSolver<Dim>::number_records() {
  std::vector<std::uint32_t>& first = carry_first_;
  const std::size_t n = first.size() - 1;
  first[0] = 1;  // record 0 is the +0 spring
  for (std::size_t i = 0; i < n; ++i) first[i + 1] += first[i];
  // With room for growth, as the force pass keeps its arrays (they take turns with these).
  const std::size_t records = first[n];
  const bool rolling = config_.contact.needs_rolling_history();
  resize_with_room(spring_, records);
  spring_[0] = Vec<Dim>{};
  if (rolling) reserve_with_room(roll_spring_, records);
  roll_spring_.assign(rolling ? records : 0, Spin<Dim>{});
}

template <int Dim>
void DemSolver<Dim>::set_record(std::size_t g, std::size_t u, const Vec<Dim>& xi, const Spin<Dim>& roll) {
  spring_[g] = xi;
  if (!roll_spring_.empty()) roll_spring_[g] = roll;
  entry_contact_[upper_entry_[u]] = static_cast<std::uint32_t>(2 * g);
  entry_contact_[upper_mirror_[u]] = static_cast<std::uint32_t>(2 * g + 1);
}

template <int Dim>
void DemSolver<Dim>::adopt_entry_springs() {
  // The springs a list brings in its entries (a restored or copied list) into records, as carry_held_springs makes
  // them: from the lower slot's entry of every pair that holds one (not +0), owned particles only (the force pass
  // evaluates no other), numbered particle after particle. The entries are then let go.
  const std::size_t m = nbr_.entries();
  const bool springs = nbr_.history.size() == m && m > 0;
  const bool rolling = config_.contact.needs_rolling_history() && nbr_.rolling.size() == m;
  auto held = [&](std::size_t k) {
    bool keep = !HeldSprings<Dim>::plus_zero(nbr_.history[k]);
    if (rolling) keep = keep | !HeldSprings<Dim>::plus_zero(nbr_.rolling[k]);
    return keep;
  };
  const std::size_t n = n_owned_;
  std::vector<std::uint32_t>& first = carry_first_;
  first.assign(n + 1, 0);
  for (std::size_t i = 0; springs && i < n; ++i) {
    for (std::size_t u = upper_offset_[i]; u < upper_offset_[i + 1]; ++u) first[i + 1] += held(upper_entry_[u]) ? 1 : 0;
  }
  number_records();
  for (std::size_t i = 0; springs && i < n; ++i) {
    std::size_t g = first[i];
    for (std::size_t u = upper_offset_[i]; u < upper_offset_[i + 1]; ++u) {
      const std::size_t k = upper_entry_[u];
      if (held(k)) set_record(g++, u, nbr_.history[k], rolling ? nbr_.rolling[k] : Spin<Dim>{});
    }
  }
  nbr_.history = {};
  nbr_.rolling = {};
  marked_ = true;
}

template <int Dim>
std::vector<std::size_t> DemSolver<Dim>::assign_order_keys() {
  // The lattice of the list's cells from the domain's origin (not the particles' bounding box): the same cell for a
  // particle on every rank. A position beyond a side (an outflow) is clamped into the last cell.
  const Vec<Dim> extent = config_.domain.template extent<Dim>();
  Index<Dim> n{};
  for (int a = 0; a < Dim; ++a) n[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / cell_size_)));
  std::size_t cells = 1;
  for (int a = 0; a < Dim; ++a) cells *= static_cast<std::size_t>(n[a]);
  const std::size_t m = n_owned_;
  for (std::size_t i = 0; i < m; ++i) {
    std::int64_t key = 0;
    for (int a = Dim - 1; a >= 0; --a) {
      const int c = std::clamp(static_cast<int>(std::floor(p_.coord(a)[i] / cell_size_)), 0, n[a] - 1);
      key = key * n[a] + c;
    }
    p_.order_key[i] = key;
  }
  // Ascending id, then a stable counting sort by key: the order (key, id).
  const std::vector<std::uint32_t> by_id = p_.slots_in_id_order();
  std::vector<std::size_t> start(cells + 1, 0);
  for (std::size_t i = 0; i < m; ++i) ++start[static_cast<std::size_t>(p_.order_key[i]) + 1];
  for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<std::size_t> order(m);
  for (const std::uint32_t i : by_id) order[start[static_cast<std::size_t>(p_.order_key[i])]++] = i;
  return order;
}

namespace {
/// Slots 0..n-1 in ascending (key, id) (ids unique): as one integer key * span + (id - lowest id) where that fits in
/// 64 bits (always, below about 4e9 particles times lattice cells), sorted by its digits (least significant first,
/// 11 bits each, over the bits in use: a few linear passes rather than n log n comparisons); otherwise compared.
std::vector<std::uint32_t> slots_by_key_and_id(std::span<const std::int64_t> key, std::span<const std::int64_t> id) {
  const std::size_t n = key.size();
  std::vector<std::uint32_t> slot(n);
  for (std::size_t k = 0; k < n; ++k) slot[k] = static_cast<std::uint32_t>(k);
  if (n < 2) return slot;
  const auto [klo, khi] = std::minmax_element(key.begin(), key.end());
  const auto [ilo, ihi] = std::minmax_element(id.begin(), id.end());
  const auto id_span = static_cast<std::uint64_t>(*ihi - *ilo) + 1;
  const auto key_span = static_cast<std::uint64_t>(*khi - *klo) + 1;
  if (key_span > std::numeric_limits<std::uint64_t>::max() / id_span) {
    std::sort(slot.begin(), slot.end(), [&](std::uint32_t a, std::uint32_t b) {
      return key[a] != key[b] ? key[a] < key[b] : id[a] < id[b];
    });
    return slot;
  }
  std::vector<std::uint64_t> v(n), v2(n);
  for (std::size_t k = 0; k < n; ++k) {
    v[k] = static_cast<std::uint64_t>(key[k] - *klo) * id_span + static_cast<std::uint64_t>(id[k] - *ilo);
  }
  const int bits = std::bit_width(key_span * id_span - 1);
  constexpr int kDigit = 11;
  std::vector<std::uint32_t> slot2(n);
  std::vector<std::size_t> count(std::size_t{1} << kDigit);
  for (int shift = 0; shift < bits; shift += kDigit) {
    std::fill(count.begin(), count.end(), 0);
    const std::uint64_t mask = (std::uint64_t{1} << kDigit) - 1;
    for (std::size_t k = 0; k < n; ++k) ++count[(v[k] >> shift) & mask];
    std::size_t at = 0;
    for (std::size_t& c : count) at += std::exchange(c, at);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t e = count[(v[k] >> shift) & mask]++;
      v2[e] = v[k];
      slot2[e] = slot[k];
    }
    v.swap(v2);
    slot.swap(slot2);
  }
  return slot;
}
}  // namespace

template <int Dim>
std::span<const std::uint32_t> DemSolver<Dim>::canonical_order() const {
  if (canonical_generation_ == generation_ && canonical_.size() == p_.size()) return canonical_;
  if (key_sorted_ && !domain_) {
    canonical_.resize(p_.size());
    for (std::size_t k = 0; k < canonical_.size(); ++k) canonical_[k] = static_cast<std::uint32_t>(k);
  } else {
    canonical_ = slots_by_key_and_id(p_.order_key, p_.id);
  }
  canonical_generation_ = generation_;
  return canonical_;
}

template <int Dim>
void DemSolver<Dim>::drop_ghosts() {
  // The ghosts are the store's last slots: cut, not copied.
  p_.for_each_array([this](const std::string&, auto& a, ArrayRole) { a.resize(n_owned_); });
  nbr_.offset.clear();  // the list named the ghosts' slots
  upper_offset_.clear();
  marked_ = false;
  ++generation_;
}

template <int Dim>
void DemSolver<Dim>::select_owned(const std::vector<std::size_t>& order, bool springs_later) {
  // What is the particles' own goes with them: the store, the springs against the walls and of the pairs, the
  // positions of the last build. The ghosts (slots from n_owned_ on) are never named, so they go.
  p_.permute(order);
  walls_.permute(order);
  permute_wall_roll(order);
  if (held_.particles() == n_owned_ && !springs_later) held_.select(order);
  if (owned_block_.size() == n_owned_) {
    select_slots(owned_block_, order);
  } else {
    owned_block_.clear();
  }
  for (std::vector<double>& b : build_) {
    if (b.size() == n_owned_) select_slots(b, order);
  }
  n_owned_ = order.size();
  nbr_.offset.clear();  // the list named the old slots
  upper_offset_.clear();
  marked_ = false;
  ++generation_;
}

template <int Dim>
void DemSolver<Dim>::migrate(bool dealt_again) {
  // Called with no ghosts in the store: every slot is owned. Particles whose block is another rank's go there,
  // the last of the others fill their slots, the arrivals follow in the order of their senders' ranks.
  const int me = domain_->rank();
  const auto nr = static_cast<std::size_t>(domain_->size());
  std::vector<Bytes> out(nr);
  std::vector<std::size_t> keep;
  keep.reserve(n_owned_);
  for (int a = 0; a < Dim; ++a) {
    if (build_[static_cast<std::size_t>(a)].size() != n_owned_) build_[static_cast<std::size_t>(a)] = p_.coord(a);
  }
  if (held_.particles() != n_owned_) held_.clear(n_owned_, config_.contact.needs_rolling_history());
  std::vector<std::vector<std::uint32_t>> leaving(nr);
  owned_block_.resize(n_owned_);  // for the ghost search after it (rebuild), which would find them again
  for (std::size_t i = 0; i < n_owned_; ++i) {
    const int b = domain_->layout().block_at(p_.pos(i));
    owned_block_[i] = b;
    const int r = domain_->layout().owner(b);
    if (r == me) {
      keep.push_back(i);
    } else {
      leaving[static_cast<std::size_t>(r)].push_back(static_cast<std::uint32_t>(i));
    }
  }
  // Between list builds a particle moves less than half a skin, so it stays in its block or enters one next to
  // it: only the neighbour ranks talk. After a new deal, or a jump no rule foresaw, every rank may: all talk.
  const std::vector<int>& nbr = domain_->neighbour_ranks();
  double far = 0.0;
  for (std::size_t r = 0; r < nr; ++r) {
    if (!leaving[r].empty() && !std::binary_search(nbr.begin(), nbr.end(), static_cast<int>(r))) far = 1.0;
  }
  if (!dealt_again) far = domain_->comm().max(far);
  std::vector<Bytes> in;
  if (dealt_again || far != 0.0) {
    for (std::size_t r = 0; r < nr; ++r) {
      if (!leaving[r].empty()) pack_records<Dim>(out[r], p_, walls_, wall_roll_, build_, held_, leaving[r], n_owned_);
    }
    in = domain_->comm().exchange(out);
  } else {
    std::vector<Bytes> near(nbr.size());
    for (std::size_t k = 0; k < nbr.size(); ++k) {
      const auto r = static_cast<std::size_t>(nbr[k]);
      if (!leaving[r].empty()) pack_records<Dim>(near[k], p_, walls_, wall_roll_, build_, held_, leaving[r], n_owned_);
    }
    std::vector<Bytes> got = domain_->comm().exchange_among(nbr, near);
    in.assign(nr, Bytes{});
    for (std::size_t k = 0; k < nbr.size(); ++k) in[static_cast<std::size_t>(nbr[k])] = std::move(got[k]);
  }
  if (keep.size() != n_owned_) {
    // The slots of those that left are filled by the last of those that stay (the storage order is free: every
    // sum runs in the canonical order), so only those move, in place.
    const std::size_t m = keep.size();
    std::vector<std::size_t> order(m);
    std::size_t below = 0;
    auto tail = static_cast<std::size_t>(std::lower_bound(keep.begin(), keep.end(), m) - keep.begin());
    for (std::size_t k = 0; k < m; ++k) {
      order[k] = below < keep.size() && keep[below] == k ? keep[below++] : keep[tail++];
    }
    select_owned(order);
  }
  for (std::size_t r = 0; r < nr; ++r) {
    if (static_cast<int>(r) == me) continue;
    Unpacker u(in[r]);
    while (!u.done()) {
      const std::size_t got = unpack_records<Dim>(u, p_, walls_, wall_roll_, build_, held_);
      for (std::size_t k = n_owned_; k < n_owned_ + got; ++k) {
        owned_block_.push_back(domain_->layout().block_at(p_.pos(k)));
      }
      n_owned_ += got;
      migrated_ += got;
    }
  }
  ++generation_;
}

template <int Dim>
void DemSolver<Dim>::measure_costs() {
  // A particle's share of its rank's work, in units of a particle without partners (its update and list search,
  // about 50 ns): 0.1 per list entry (the distance tests) and 0.8 per contact (the law, about 40 ns), from the
  // settling runs of docs/performance.md, section 18. It apportions a rank's measured time among its blocks.
  cost_.assign(n_owned_, 1.0);
  if (nbr_.offset.size() < n_owned_ + 1 || entry_contact_.size() != nbr_.entries()) return;
  const auto sn = static_cast<std::ptrdiff_t>(n_owned_);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    std::size_t contacts = 0;
    for (std::size_t k = nbr_.offset[i]; k < nbr_.offset[i + 1]; ++k) contacts += entry_contact_[k] != 0 ? 1 : 0;
    const auto entries = static_cast<double>(nbr_.offset[i + 1] - nbr_.offset[i]);
    cost_[i] = 1.0 + 0.1 * entries + 0.8 * static_cast<double>(contacts);
  }
}

template <int Dim>
bool DemSolver<Dim>::rebalance_if_needed() {
  // The verdict on the ranks' measured compute time since the last check (their waits for each other left out), as
  // LAMMPS's balancing by time does: no count model knows what a contact law, a cache or a shared core costs. A
  // rank's time is shared among its blocks by the particles' counted costs. Every rank reaches the same verdict and
  // the same deal from the same reduced figures; the deal changes no result (docs/parallel.md), only the speed.
  const Comm& c = domain_->comm();
  const BlockLayout<Dim>& layout = domain_->layout();
  const auto nr = static_cast<std::size_t>(c.size());
  const auto me = static_cast<std::size_t>(c.rank());
  std::vector<double> busy(nr, 0.0);  // per rank: seconds busy
  busy[me] = busy_s_;
  c.max(std::span<double>(busy));  // each rank's own entry, the others zero
  busy_s_ = 0.0;
  // Without time measured yet (the first build, after a restore) or with an idle rank, the counts decide alone.
  const bool timed = std::all_of(busy.begin(), busy.end(), [](double t) { return t > 0.0; });
  if (timed) {
    imbalance_ = imbalance(busy);
    if (imbalance_ <= rebalance_threshold_) return false;  // the usual verdict: no costs counted
  }
  measure_costs();
  double counted = 0.0;
  for (std::size_t i = 0; i < n_owned_; ++i) counted += cost_[i];
  if (!timed) {
    std::vector<double> cost(nr, 0.0);
    cost[me] = counted;
    c.max(std::span<double>(cost));
    imbalance_ = imbalance(cost);
    if (imbalance_ <= rebalance_threshold_) return false;
  }
  const double per_cost = timed && counted > 0.0 ? busy[me] / counted : 1.0;
  std::vector<double> weight(static_cast<std::size_t>(layout.blocks()), 0.0);
  for (std::size_t i = 0; i < n_owned_; ++i) {
    weight[static_cast<std::size_t>(layout.block_at(p_.pos(i)))] += cost_[i] * per_cost;
  }
  c.max(std::span<double>(weight));  // a block's particles are all on its owner: the maximum is its weight
  const std::vector<int> before = layout.owners();
  domain_->layout().assign(weight, c.size());
  if (layout.owners() == before) return false;
  ++rebalances_;
  return true;
}

template <int Dim>
void DemSolver<Dim>::permute_wall_roll(const std::vector<std::size_t>& order) {
  constexpr std::size_t nw = 2 * Dim;
  if (!wall_roll_.empty()) select_slots(wall_roll_, order, nw);
}

template <int Dim>
bool DemSolver<Dim>::link_sorted_mirrors(std::span<const std::uint32_t> visit) {
  // Every list holds its partners in the canonical order (ascending order key and id: build_neighbor_list), which
  // after a sorting rebuild on one rank is the slots' own (visit empty). Taken in that order, the particles that
  // evaluate a pair with j (its partners in lower slots) come in the order j's list holds them, so each finds its
  // mirror at the next of j's entries that names a lower slot, with no search: one pass over the list (serial: the
  // cursor per partner is a running one), the entries of j's own pairs stepped over once. On one rank after a
  // sorting rebuild j's lower partners are its list's head and nothing is stepped over. Any entry out of that
  // order sends the list to the search instead.
  const std::size_t n = p_.size();
  std::vector<std::uint32_t>& cursor = carry_first_;  // free until the springs are carried
  cursor.assign(nbr_.offset.begin(), nbr_.offset.begin() + static_cast<std::ptrdiff_t>(n));
  const std::uint32_t* partner = nbr_.partner.data();
  for (std::size_t c = 0; c < n; ++c) {
    const std::size_t i = visit.empty() ? c : visit[c];
    std::size_t u = upper_offset_[i];
    for (std::size_t k = nbr_.offset[i]; k < nbr_.offset[i + 1]; ++k) {
      const std::size_t j = partner[k];
      if (j <= i) continue;
      std::size_t q = cursor[j];
      const std::size_t end = nbr_.offset[j + 1];
      while (q < end && partner[q] > j) ++q;
      if (q == end || partner[q] != i) return false;
      cursor[j] = static_cast<std::uint32_t>(q + 1);
      upper_entry_[u] = static_cast<std::uint32_t>(k);
      upper_mirror_[u] = static_cast<std::uint32_t>(q);
      ++u;
    }
  }
  return true;
}

template <int Dim>
void DemSolver<Dim>::sync_list_springs() const {
  if (!marked_ || entry_contact_.size() != nbr_.entries()) return;
  // The springs are where they were, only written out as well: callers holding a const solver may ask for it.
  List& list = const_cast<DemSolver&>(*this).nbr_;
  const std::size_t m = list.entries();
  const bool rolling = config_.contact.needs_rolling_history() && roll_spring_.size() == spring_.size();
  list.history.resize(m);
  if (rolling) list.rolling.resize(m);
  const auto sm = static_cast<std::ptrdiff_t>(m);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t qq = 0; qq < sm; ++qq) {
    const auto q = static_cast<std::size_t>(qq);
    list.history[q] = entry_spring(q);
    if (rolling) list.rolling[q] = entry_roll(q);
  }
}

template <int Dim>
void DemSolver<Dim>::link_mirrors() {
  // The list the records number (an insertion adds rows without entries and keeps it): its springs into its
  // entries, read by the next evaluation as on any list linked anew.
  sync_list_springs();
  const std::size_t n = p_.size();
  if (nbr_.entries() > std::numeric_limits<std::uint32_t>::max()) {
    throw_simulation_error("neighbour list too long for 32-bit entry links");
  }
  // The half list: each particle's entries of higher-slot partners (the pairs it evaluates), with the partner's
  // entry of the same pair; counted first, so the half list is in list order.
  upper_offset_.assign(n + 1, 0);
  const auto sn = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    std::size_t c = 0;
    for (std::size_t k = nbr_.offset[i]; k < nbr_.offset[i + 1]; ++k) c += nbr_.partner[k] > i ? 1 : 0;
    upper_offset_[i + 1] = static_cast<std::uint32_t>(c);
  }
  for (std::size_t i = 0; i < n; ++i) upper_offset_[i + 1] += upper_offset_[i];
  resize_with_room(upper_entry_, upper_offset_[n]);
  resize_with_room(upper_mirror_, upper_offset_[n]);
  int missing = 0;
  // The lists are in the canonical order when a build sorted them; elsewhere (a restored or grown list) the order
  // may be any, and the search finds the mirrors.
  bool linked = false;
  if (!domain_ && key_sorted_) {
    linked = link_sorted_mirrors({});
  } else if (canonical_generation_ == generation_ && canonical_.size() == n) {
    linked = link_sorted_mirrors(canonical_);
  }
  if (!linked) {
#pragma omp parallel for schedule(static) reduction(max : missing)
    for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      std::size_t u = upper_offset_[i];
      for (std::size_t k = nbr_.offset[i]; k < nbr_.offset[i + 1]; ++k) {
        const std::size_t j = nbr_.partner[k];
        if (j <= i) continue;
        bool found = false;
        for (std::size_t q = nbr_.offset[j]; q < nbr_.offset[j + 1]; ++q) {
          if (nbr_.partner[q] == i) {
            upper_entry_[u] = static_cast<std::uint32_t>(k);
            upper_mirror_[u] = static_cast<std::uint32_t>(q);
            found = true;
            break;
          }
        }
        ++u;
        if (!found) missing = 1;
      }
    }
  }
  // Every upper entry has its partner's entry, and those are all the other entries: the list is symmetric.
  if (missing != 0 || 2 * upper_offset_[n] != nbr_.entries()) {
    throw_simulation_error("neighbour list is not symmetric (internal error)");
  }
  linked_entries_ = nbr_.entries();
  marked_ = false;  // the records marked entries of the old list
  // A new list: no entry has a force yet (compute_forces relies on zeros in the entries not in contact).
  // With room for growth: assign() beyond the capacity allocates the exact size, which a list growing as the bed
  // compacts would pay (in page faults) at every rebuild.
  const std::size_t m = nbr_.entries();
  reserve_with_room(entry_contact_, m);
  entry_contact_.assign(m, 0);
  adopt_entry_springs();
}

template <int Dim>
double DemSolver<Dim>::compute_forces(double dt) {
  // Periodic axes take the minimum image of each separation; the closed box keeps its loop without that test. Each
  // kind is compiled in a unit of its own per dimension (forces_*.cpp): the pass's 90 instantiations per
  // dimension in one unit made it the build's longest compile by far.
  return periodic_.any() ? compute_forces_on<true>(dt) : compute_forces_on<false>(dt);
}

template <int Dim>
DemStepInfo DemSolver<Dim>::step() {
  DemStepInfo info = advance(config_.dt);
  // Whole steps from the clock origin: n dt carries one rounding, a running sum of dt one per step.
  time_ = time_origin_ + static_cast<double>(steps_ - steps_origin_) * config_.dt;
  if (config_.insertion.enabled()) info.inserted = insert_due();
  return info;
}

template <int Dim>
DemStepInfo DemSolver<Dim>::step(double h) {
  if (h == config_.dt) return step();
  DemStepInfo info = advance(h);
  time_ += h;
  time_origin_ = time_;
  steps_origin_ = steps_;
  if (config_.insertion.enabled()) info.inserted = insert_due();
  return info;
}

template <int Dim>
DemStepInfo DemSolver<Dim>::advance(double dt) {
  DemStepInfo info;
  if (domain_) {
    step_start_ = std::chrono::steady_clock::now();
    step_comm_s_ = domain_->comm().seconds_communicating();
  }
  step_built_ = need_rebuild_ || list_stale_;
  if (need_rebuild_) {
    rebuild(true);
    info.rebuilt = true;
  } else if (list_stale_) {
    rebuild(false);
  }
  info.max_overlap = compute_forces(dt);

  // Eq. 10: explicit update, new velocity first, then position with the new velocity. The drag
  // drag_k (ug - v) is taken implicitly in v so that light or fine particles do not limit the time step;
  // with drag_k = 0 this is exactly Eq. 10. Owned particles only: the ghosts follow their owners.
  const std::size_t n = n_owned_;
  const Vec<Dim> g = config_.domain.gravity_vector<Dim>();
  const double half_skin2 = 0.25 * config_.skin * config_.skin;
  const DomainTest in_domain = domain_test();
  const PeriodicBox<Dim> box = periodic_;
  const bool wrap = box.any();
  const AxisPtrs<Dim> X = axis_ptrs<Dim>([&](int a) -> auto& { return p_.coord(a); }, Dim);
  const AxisPtrs<Dim> V = axis_ptrs<Dim>([&](int a) -> auto& { return p_.velocity(a); }, Dim);
  const AxisPtrs<Dim> F = axis_ptrs<Dim>([&](int a) -> auto& { return p_.force(a); }, Dim);
  const AxisPtrs<Dim> FE = axis_ptrs<Dim>([&](int a) -> auto& { return p_.force_ext(a); }, Dim);
  const AxisPtrs<Dim> UG = axis_ptrs<Dim>([&](int a) -> auto& { return p_.gas_velocity(a); }, Dim);
  const AxisPtrs<Dim> B = axis_ptrs<Dim>([&](int a) -> auto& { return build_[static_cast<std::size_t>(a)]; }, Dim);
  constexpr int NS = kSpinComponents<Dim>;
  const AxisPtrs<NS> W = axis_ptrs<NS>([&](int c) -> auto& { return p_.spin_component(c); }, NS);
  const AxisPtrs<NS> T = axis_ptrs<NS>([&](int c) -> auto& { return p_.torque_component(c); }, NS);
  const double* drag_k = p_.drag_k.data();
  const double* inv_mass = p_.inv_mass.data();
  const double* inv_inertia = p_.inv_inertia.data();
  int moved_far = 0;
  int bad = 0;
  int escaped = 0;
  const auto sn = static_cast<std::ptrdiff_t>(n);
  // A DEM-only run reads none of the fluid arrays (7 of the 3D pass's 27): with them at zero the coupled form adds
  // exact zeros and relaxes by exactly 1, so both forms give the same bits.
  auto update = [&]<bool Fluid>() {
#pragma omp parallel for schedule(static) reduction(max : moved_far, bad, escaped)
    for (std::ptrdiff_t ii = 0; ii < sn; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const double im = inv_mass[i];
      const double k = Fluid ? drag_k[i] : 0.0;
      const double relax = Fluid ? 1.0 / (1.0 + dt * k * im) : 1.0;
      // The new state is kept in locals for the tests below: the domain test through the store's accessors would
      // reload every array it reads.
      double moved2 = 0.0;
      bool ok = true;
      for (int a = 0; a < Dim; ++a) {
        double v;
        if constexpr (Fluid) {
          v = (V[a][i] + ((F[a][i] + FE[a][i] + k * UG[a][i]) * im + g[a]) * dt) * relax;
        } else {
          v = V[a][i] + ((F[a][i] + 0.0) * im + g[a]) * dt;  // + 0.0: a -0 force gives +0, as F + FE did
        }
        double x = X[a][i] + v * dt;
        double dd = x - B[a][i];
        if (wrap) {
          // Re-enter through the opposite side; the distance moved since the list build is the nearest image's.
          x = box.wrap(a, x);
          dd = box.min_image(a, x - B[a][i]);
        }
        V[a][i] = v;
        X[a][i] = x;
        moved2 += dd * dd;
        ok = ok && in_domain.inside(a, x) && std::isfinite(v);
        if (in_domain.any_outflow && in_domain.escaped(a, x)) escaped = 1;
      }
      // Eq. 9 (a sphere: isotropic inertia, so each spin component follows its torque component)
      for (int c = 0; c < NS; ++c) {
        const double w = W[c][i] + T[c][i] * inv_inertia[i] * dt;
        W[c][i] = w;
        ok = ok && std::isfinite(w);
      }
      if (moved2 >= half_skin2) moved_far = 1;
      if (!ok) bad = 1;
    }
  };
  if (fluid_) {
    update.template operator()<true>();
  } else {
    update.template operator()<false>();
  }
  if (domain_) finish_step_distributed(moved_far, bad, escaped);
  info.max_overlap = max_overlap_;
  need_rebuild_ = moved_far != 0;
  ++steps_;
  if (bad != 0) check_particles();
  if (escaped != 0) info.removed = domain_ ? remove_escaped_distributed() : remove_escaped();
  return info;
}

template <int Dim>
void DemSolver<Dim>::finish_step_distributed(int& moved_far, int& bad, int& escaped) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  // The step's own work: its wall time less what it spent in communication (the waits for other ranks among it).
  const double busy = std::chrono::duration<double>(t0 - step_start_).count() -
                      (domain_->comm().seconds_communicating() - step_comm_s_);
  busy_s_ += busy;
  comm_stats_.busy_s += busy;
  domain_->forward(p_, plan_);
  const auto t1 = Clock::now();
  // One reduction a step: the rebuild trigger, a failure, an escape and the largest overlaps, over every rank.
  double v[5] = {static_cast<double>(moved_far), static_cast<double>(bad), static_cast<double>(escaped), max_overlap_,
                 max_overlap_fraction_};
  domain_->comm().max(std::span<double>(v));
  const auto t2 = Clock::now();
  DemParallelStats& c = comm_stats_;
  ++c.steps;
  c.forward_s += std::chrono::duration<double>(t1 - t0).count();
  if (step_built_) c.forward_after_build_s += std::chrono::duration<double>(t1 - t0).count();
  c.reduce_s += std::chrono::duration<double>(t2 - t1).count();
  for (const std::vector<double>& b : plan_.send_buf) {
    c.forward_bytes += b.size() * sizeof(double);
    c.forward_messages += b.empty() ? 0 : 1;
  }
  moved_far = v[0] != 0.0 ? 1 : 0;
  bad = v[1] != 0.0 ? 1 : 0;
  escaped = v[2] != 0.0 ? 1 : 0;
  max_overlap_ = v[3];
  max_overlap_fraction_ = v[4];
}

template <int Dim>
std::size_t DemSolver<Dim>::remove_escaped() {
  const std::size_t n = p_.size();
  const DomainTest in_domain = domain_test();
  constexpr auto kGone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> keep, new_slot(n, kGone);
  keep.reserve(n);
  std::size_t removed = 0;
  ExactSum mass;  // the step's removed mass, in no order: the same bits as on any split over ranks
  for (std::size_t i = 0; i < n; ++i) {
    bool gone = false;
    for (int a = 0; a < Dim; ++a) gone = gone || in_domain.escaped(a, p_.coord(a)[i]);
    if (gone) {
      ++removed;
      mass.add(p_.mass[i]);
    } else {
      new_slot[i] = keep.size();
      keep.push_back(i);
    }
  }
  removed_count_ += removed;
  removed_mass_ += mass.value();
  if (!list_springs_ || nbr_.offset.size() != n + 1) {
    // No current list (none built yet): the held springs go with their particles, the list is built before the
    // next force evaluation.
    select_owned(keep);
    list_stale_ = true;
    return removed;
  }
  // The neighbour list of the particles that stay, in the same order, with their springs: the remaining pairs
  // are still within reach of their last build, so the list stays valid without a rebuild.
  sync_list_springs();
  List list;
  list.offset.assign(keep.size() + 1, 0);
  list.partner.reserve(nbr_.partner.size());
  list.history.reserve(nbr_.history.size());
  const bool rolling = nbr_.rolling.size() == nbr_.history.size() && !nbr_.rolling.empty();
  if (rolling) list.rolling.reserve(nbr_.rolling.size());
  for (std::size_t k = 0; k < keep.size(); ++k) {
    const std::size_t i = keep[k];
    for (std::size_t q = nbr_.offset[i]; q < nbr_.offset[i + 1]; ++q) {
      const std::size_t j = new_slot[nbr_.partner[q]];
      if (j == kGone) continue;
      list.partner.push_back(static_cast<std::uint32_t>(j));
      list.history.push_back(nbr_.history[q]);
      if (rolling) list.rolling.push_back(nbr_.rolling[q]);
    }
    list.offset[k + 1] = list.partner.size();
  }
  select_owned(keep);  // the store and what goes with it (it forgets the list: restored below)
  nbr_ = std::move(list);
  link_mirrors();
  return removed;
}

template <int Dim>
std::size_t DemSolver<Dim>::remove_escaped_distributed() {
  // As on one rank, but the ghosts of the removed particles are on other ranks: every rank drops its escaped owned
  // particles and builds its list and ghosts anew (not counted: the same list, without them).
  if (list_springs_) gather_held_springs();
  list_springs_ = false;
  const DomainTest in_domain = domain_test();
  std::vector<std::size_t> keep;
  keep.reserve(n_owned_);
  ExactSum mass;
  std::int64_t removed[1] = {0};
  for (std::size_t i = 0; i < n_owned_; ++i) {
    bool gone = false;
    for (int a = 0; a < Dim; ++a) gone = gone || in_domain.escaped(a, p_.coord(a)[i]);
    if (gone) {
      ++removed[0];
      mass.add(p_.mass[i]);
    } else {
      keep.push_back(i);
    }
  }
  select_owned(keep);
  const Comm& c = domain_->comm();
  c.sum(std::span<std::int64_t>(removed));
  removed_count_ += static_cast<std::uint64_t>(removed[0]);
  removed_mass_ += c.sum(mass);
  rebuild(false);
  return static_cast<std::size_t>(removed[0]);
}

namespace {
/// splitmix64 (Steele, Lea and Flood 2014) of (seed, n): the n-th number of a stream that needs no state but its
/// counter, so a restart continues it from the counter alone. Uniform in [0, 1).
double feed_uniform(std::uint64_t seed, std::uint64_t n) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + (n + 1) * 0xD1B54A32D192ED69ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}
}  // namespace

template <int Dim>
std::size_t DemSolver<Dim>::insert_due() {
  const InsertionConfig& in = config_.insertion;
  if (time_ < in.t_start) return 0;
  // Due by now: the whole particles of rate (t - t_start), the feed stopping at t_end.
  const double t = std::min(time_, in.t_end) - in.t_start;
  const auto due = static_cast<std::uint64_t>(std::floor(in.rate * t));
  if (due <= feed_.inserted) return 0;
  const Species& species = config_.species[static_cast<std::size_t>(in.species)];
  Vec<Dim> vel;
  for (int a = 0; a < Dim; ++a) vel[a] = in.velocity[a];
  // The particles a new one could touch: all of them on one rank; on several, every rank's particles near the
  // region, gathered, so that every rank draws and tests the same way and adds the new particles in its blocks.
  std::vector<Vec<Dim>> near_x;
  std::vector<double> near_r;
  if (domain_) gather_near_region(near_x, near_r);
  std::size_t added = 0;
  std::vector<std::pair<std::int64_t, Vec<Dim>>> mine;  // distributed: the new particles in this rank's blocks
  std::vector<Species> mine_species;
  std::uint64_t tries = static_cast<std::uint64_t>(std::max(in.attempts_per_particle, 1)) * (due - feed_.inserted);
  while (feed_.inserted < due && tries-- > 0) {
    // A species with a size distribution: the k-th fed particle's size from a counter-based stream of its own
    // (k = feed_.inserted, in the checkpoint), so a restart feeds the same sizes.
    const Species sp = species.sized() ? species.of_diameter(size_quantile(
                                             species.size, feed_uniform(in.seed ^ 0x5bd1e995ull, feed_.inserted)))
                                       : species;
    const double r = sp.radius();
    Vec<Dim> x;
    for (int a = 0; a < Dim; ++a) {
      const double u = feed_uniform(in.seed, feed_.draws++);
      x[a] = periodic_.wrap(a, in.region_lo[a] + u * (in.region_hi[a] - in.region_lo[a]));
    }
    // Clear of every particle (their nearest images on periodic axes): a new particle starts out of contact.
    bool clear = true;
    if (!domain_) {
      for (std::size_t i = 0; i < p_.size() && clear; ++i) {
        const Vec<Dim> d = periodic_.min_image(p_.pos(i) - x);
        const double reach = p_.radius[i] + r;
        clear = dot(d, d) >= reach * reach;
      }
    } else {
      for (std::size_t i = 0; i < near_x.size() && clear; ++i) {
        const Vec<Dim> d = periodic_.min_image(near_x[i] - x);
        const double reach = near_r[i] + r;
        clear = dot(d, d) >= reach * reach;
      }
    }
    if (!clear) continue;
    if (domain_) {
      near_x.push_back(x);
      near_r.push_back(r);
      if (domain_->owner_of(x) == domain_->rank()) {
        mine.emplace_back(feed_.next_id, x);
        mine_species.push_back(sp);
      }
      ++feed_.next_id;
    } else {
      const bool list_valid = nbr_.offset.size() == p_.size() + 1;
      p_.add(feed_.next_id++, in.species, sp, x, vel);
      // The list stays that of the old particles, the new one without partners, so the next rebuild carries the
      // springs of the old contacts over as after any other step.
      if (list_valid) nbr_.offset.push_back(nbr_.offset.back());
      // Its wall rolling springs start relaxed; the others' stay (a size mismatch would reset them all).
      if (!wall_roll_.empty()) wall_roll_.resize(wall_roll_.size() + 2 * Dim, Spin<Dim>{});
      walls_.push_back();
      for (int a = 0; a < Dim; ++a) build_[static_cast<std::size_t>(a)].push_back(x[a]);
      if (held_.particles() == n_owned_) held_.add_particle();
      ++n_owned_;
      ++generation_;
      key_sorted_ = false;  // its key (0) is no larger than the others': sorted again at the next sorting rebuild
    }
    ++feed_.inserted;
    feed_.mass += sp.mass();
    ++added;
  }
  if (added > 0) need_rebuild_ = true;
  if (added > 0 && species.sized()) sized_ = true;
  if (domain_ && added > 0) {
    // The new particles join their owners' stores, then the list and the ghosts are built again so that the next
    // deposition sees them on every rank (not counted: the counted rebuild comes at the next step, as on one rank).
    if (list_springs_) gather_held_springs();
    list_springs_ = false;
    drop_ghosts();
    for (std::size_t k = 0; k < mine.size(); ++k) {
      p_.add(mine[k].first, in.species, mine_species[k], mine[k].second, vel);
      if (!wall_roll_.empty()) wall_roll_.resize(wall_roll_.size() + 2 * Dim, Spin<Dim>{});
      walls_.push_back();
      for (int a = 0; a < Dim; ++a) build_[static_cast<std::size_t>(a)].push_back(mine[k].second[a]);
      held_.add_particle();
      ++n_owned_;
    }
    rebuild(false);
  }
  return added;
}

template <int Dim>
void DemSolver<Dim>::gather_near_region(std::vector<Vec<Dim>>& x, std::vector<double>& r) const {
  const InsertionConfig& in = config_.insertion;
  // A particle can touch a new one only within its own and the new one's radius of the region: the cell size
  // (largest diameter + skin) is more than that.
  const double margin = cell_size_;
  Bytes out;
  for (std::size_t i = 0; i < n_owned_; ++i) {
    bool near = true;
    for (int a = 0; a < Dim && near; ++a) {
      const double xi = p_.coord(a)[i];
      const double lo = in.region_lo[a], hi = in.region_hi[a];
      double d = std::max({lo - xi, xi - hi, 0.0});
      if (periodic_.periodic(a)) {
        const double L = periodic_.length[a];
        d = std::min({d, std::max({lo - (xi + L), (xi + L) - hi, 0.0}), std::max({lo - (xi - L), (xi - L) - hi, 0.0})});
      }
      near = d <= margin;
    }
    if (!near) continue;
    pack(out, p_.pos(i));
    pack(out, p_.radius[i]);
  }
  const Bytes all = domain_->comm().allgather_concat(out);
  Unpacker u(all);
  while (!u.done()) {
    x.push_back(u.get<Vec<Dim>>());
    r.push_back(u.get<double>());
  }
}

template <int Dim>
void DemSolver<Dim>::check_particles() const {
  // The offending particle with the smallest id over every rank, so the message depends neither on the threads
  // nor on the split of the domain; every rank stops with it.
  const auto mine = particle_failure();
  const std::optional<std::string> what =
      domain_ ? comm().first_failure(mine ? std::optional<std::string>(mine->second) : std::nullopt,
                                     mine ? static_cast<double>(mine->first) : 0.0)
              : (mine ? std::optional<std::string>(mine->second) : std::nullopt);
  if (what) throw_simulation_error(*what);
}

template <int Dim>
std::optional<std::pair<std::int64_t, std::string>> DemSolver<Dim>::particle_failure() const {
  const std::size_t n = n_owned_;
  const double W = config_.domain.width;
  const double H = config_.domain.height;
  const DomainTest in_domain = domain_test();
  std::size_t worst = n;
  for (std::size_t i = 0; i < n; ++i) {
    if (!in_domain(p_, i) && (worst == n || p_.id[i] < p_.id[worst])) worst = i;
  }
  if (worst == n) return std::nullopt;
  bool finite = true;
  for (int a = 0; a < Dim; ++a) finite = finite && std::isfinite(p_.coord(a)[worst]) && std::isfinite(p_.velocity(a)[worst]);
  for (int c = 0; c < kSpinComponents<Dim>; ++c) finite = finite && std::isfinite(p_.spin_component(c)[worst]);
  bool inside_across = p_.x[worst] >= 0.0 && p_.x[worst] <= W;
  if constexpr (Dim == 3) inside_across = inside_across && p_.z[worst] >= 0.0 && p_.z[worst] <= config_.domain.depth;
  const std::int64_t id = p_.id[worst];
  if (finite && p_.y[worst] > H && inside_across) {
    return std::pair{id, fmt::format(
        "t = {:.6g} s: particle {} left through the open top of the domain (y = {:.6g} m > {} m, velocity "
        "({:.6g}, {:.6g}) m/s). The top is open to the gas but particles may not leave: likely cause, the gas lifts "
        "the bed (a plug or a burst at the surface); remedy: domain.particle_top = \"outflow\" removes and counts "
        "the particles that leave (monitor.csv particles_lost, mass_lost_kg), domain.particle_top = \"wall\" keeps "
        "them in, or make the domain taller or ramp the inlet up (inlet.ramp_time).",
        time_, id, p_.y[worst], H, p_.vx[worst], p_.vy[worst])};
  }
  if constexpr (Dim == 2) {
    return std::pair{id, fmt::format(
        "t = {:.6g} s: particle {} left the domain [0, {}] x [0, {}] m or its state is not finite: position "
        "({:.6g}, {:.6g}) m, velocity ({:.6g}, {:.6g}) m/s. Likely cause: the time step is too large for the "
        "stiffness (check `fluidbed check`); remedy: reduce dem.time_step.",
        time_, id, W, H, p_.x[worst], p_.y[worst], p_.vx[worst], p_.vy[worst])};
  } else {
    return std::pair{id, fmt::format(
        "t = {:.6g} s: particle {} left the domain [0, {}] x [0, {}] x [0, {}] m or its state is not finite: "
        "position ({:.6g}, {:.6g}, {:.6g}) m, velocity ({:.6g}, {:.6g}, {:.6g}) m/s. Likely cause: the time step is "
        "too large for the stiffness (check `fluidbed check`); remedy: reduce dem.time_step.",
        time_, id, W, H, config_.domain.depth, p_.x[worst], p_.y[worst], p_.z[worst], p_.vx[worst],
        p_.vy[worst], p_.vz[worst])};
  }
}

template <int Dim>
double DemSolver<Dim>::kinetic_energy() const {
  ExactSum e;
  for (std::size_t i = 0; i < n_owned_; ++i) {
    e.add(0.5 * p_.mass[i] * norm2(p_.vel(i)) + 0.5 * spin_norm2<Dim>(p_.spin(i)) / p_.inv_inertia[i]);
  }
  return comm().sum(e);
}

template <int Dim>
double DemSolver<Dim>::total_mass() const {
  ExactSum m;
  for (std::size_t i = 0; i < n_owned_; ++i) m.add(p_.mass[i]);
  return comm().sum(m);
}

template <int Dim>
typename DemSolver<Dim>::State DemSolver<Dim>::state() const {
  if (domain_) throw std::logic_error("DemSolver::state: a distributed solver gives portable_state()");
  sync_list_springs();
  State st{p_,           nbr_,         walls_,        build_,        time_,         steps_,       rebuilds_,
           need_rebuild_, time_origin_, steps_origin_, removed_count_, removed_mass_, feed_,
           wall_roll_};
  if (!list_springs_) {
    st.neighbors = List{};  // no current list: the springs are the held ones
    st.held = held_;
  }
  return st;
}

template <int Dim>
const HeldSprings<Dim>& DemSolver<Dim>::current_held_springs() const {
  // Gathered into held_ itself: a copy beside it would be the largest array of a settled bed's checkpoint.
  if (list_springs_) const_cast<DemSolver&>(*this).gather_held_springs();
  return held_;
}

template <int Dim>
typename DemSolver<Dim>::State DemSolver<Dim>::clock_state() const {
  State st;
  st.time = time_;
  st.steps = steps_;
  st.rebuilds = rebuilds_;
  st.need_rebuild = need_rebuild_;
  st.time_origin = time_origin_;
  st.steps_origin = steps_origin_;
  st.removed_count = removed_count_;
  st.removed_mass = removed_mass_;
  st.feed = feed_;
  st.held.clear(0, config_.contact.needs_rolling_history());
  return st;
}

namespace {
/// The slots of a store's particles in ascending id.
template <int Dim>
std::vector<std::size_t> ascending_id_order(const ParticleStore<Dim>& p) {
  std::vector<std::size_t> order(p.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
  return order;
}
}  // namespace

template <int Dim>
typename DemSolver<Dim>::CheckpointView DemSolver<Dim>::checkpoint_view() const {
  CheckpointView v;
  if (domain_) {
    v.state = portable_state();
    v.order.resize(v.state.particles.size());
    for (std::size_t k = 0; k < v.order.size(); ++k) v.order[k] = static_cast<std::uint32_t>(k);
    return v;
  }
  // One process: the arrays where they are, read in ascending id.
  v.state = clock_state();
  v.order = p_.slots_in_id_order();
  const HeldSprings<Dim>& held = current_held_springs();
  if (held.particles() == n_owned_) {
    v.own_held = &held;
  } else {
    v.state.held.clear(n_owned_, config_.contact.needs_rolling_history());
  }
  v.own_particles = &p_;
  v.own_walls = &walls_;
  v.own_wall_roll = &wall_roll_;
  for (int a = 0; a < Dim; ++a) {
    const std::vector<double>& b = build_[static_cast<std::size_t>(a)];
    v.own_build[static_cast<std::size_t>(a)] = b.size() == n_owned_ ? &b : &p_.coord(a);
  }
  return v;
}

template <int Dim>
typename DemSolver<Dim>::State DemSolver<Dim>::portable_state() const {
  // Every owned particle with its springs by partner id (from the list when it is current), gathered on rank 0.
  const HeldSprings<Dim>* held = &current_held_springs();
  State st = clock_state();
  if (!domain_) {
    // One rank: the arrays themselves (no ghosts), without a message between.
    st.particles = p_;
    st.walls = walls_;
    st.wall_roll = wall_roll_;
    for (int a = 0; a < Dim; ++a) {
      const std::vector<double>& b = build_[static_cast<std::size_t>(a)];
      st.build[static_cast<std::size_t>(a)] = b.size() == n_owned_ ? b : p_.coord(a);
    }
    st.held = held->particles() == n_owned_ ? *held : HeldSprings<Dim>{};
    if (st.held.particles() != n_owned_) st.held.clear(n_owned_, config_.contact.needs_rolling_history());
  } else {
    Bytes mine;
    std::vector<std::uint32_t> slots(n_owned_);
    for (std::size_t i = 0; i < n_owned_; ++i) slots[i] = static_cast<std::uint32_t>(i);
    pack_records<Dim>(mine, p_, walls_, wall_roll_, build_, *held, slots, n_owned_);
    const std::vector<Bytes> all = comm().gather(mine, 0);
    if (all.empty()) return st;
    for (const Bytes& b : all) {
      Unpacker u(b);
      while (!u.done()) unpack_records<Dim>(u, st.particles, st.walls, st.wall_roll, st.build, st.held);
    }
  }
  // Ascending id: the same file whatever the storage order and the number of ranks.
  const std::vector<std::size_t> order = ascending_id_order(st.particles);
  st.particles.permute(order);
  st.walls.permute(order);
  if (!st.wall_roll.empty()) {
    std::vector<Spin<Dim>> r(st.wall_roll.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      for (std::size_t w = 0; w < 2 * Dim; ++w) r[k * 2 * Dim + w] = st.wall_roll[order[k] * 2 * Dim + w];
    }
    st.wall_roll.swap(r);
  }
  for (auto& b : st.build) {
    std::vector<double> nb(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) nb[k] = b[order[k]];
    b.swap(nb);
  }
  st.held.select(order);
  return st;
}

template <int Dim>
void DemSolver<Dim>::restore(State s) {
  const bool portable = s.neighbors.offset.empty() && s.neighbors.partner.empty();
  p_ = std::move(s.particles);
  p_.hold_fluid_arrays(fluid_);  // a state saved with or without them (a DEM-only run's has none)
  nbr_ = std::move(s.neighbors);
  walls_ = std::move(s.walls);
  if (walls_.size() == 0) walls_.reset(p_.size());  // a state without wall springs: none held
  if (walls_.size() != p_.size()) throw std::invalid_argument("DemSolver::restore: the wall springs do not match the particles");
  build_ = std::move(s.build);
  time_ = s.time;
  steps_ = s.steps;
  rebuilds_ = s.rebuilds;
  time_origin_ = s.time_origin;
  steps_origin_ = s.steps_origin;
  // A restart that changes dem.time_step (--allow-changed): the saved origin counts steps of the old step, so the
  // clock would jump back; it restarts from the saved time. With the same step the origin is kept, so the restart
  // continues the uninterrupted run's clock bit for bit.
  const double clock = time_origin_ + static_cast<double>(steps_ - steps_origin_) * config_.dt;
  if (std::abs(clock - time_) > 1e-12 * (std::abs(time_) + config_.dt)) {
    time_origin_ = time_;
    steps_origin_ = steps_;
  }
  removed_count_ = s.removed_count;
  removed_mass_ = s.removed_mass;
  feed_ = s.feed;
  // A state from before the feed: the next id follows the largest present (all particles: before a distributed
  // solver keeps its own).
  for (std::int64_t id : p_.id) feed_.next_id = std::max(feed_.next_id, id + 1);
  wall_roll_ = std::move(s.wall_roll);
  n_owned_ = p_.size();
  for (auto& b : build_) {
    if (b.size() != n_owned_) b.clear();
  }
  for (int a = 0; a < Dim; ++a) {
    if (build_[static_cast<std::size_t>(a)].empty()) build_[static_cast<std::size_t>(a)] = p_.coord(a);
  }
  upper_offset_.clear();  // linked again at the next force evaluation
  marked_ = false;
  ++generation_;
  key_sorted_ = false;  // a state in id order: the canonical order is sorted out when asked for
  if (portable) {
    // The springs by partner id; the list is built before the next force evaluation, without counting it (the
    // rebuild trigger keeps the saved schedule: the positions of the last counted build are part of the state).
    held_ = std::move(s.held);
    if (held_.particles() != n_owned_) held_.clear(n_owned_, config_.contact.needs_rolling_history());
    need_rebuild_ = s.need_rebuild;
    list_springs_ = false;
    list_stale_ = true;
  } else {
    need_rebuild_ = s.need_rebuild || nbr_.offset.size() != p_.size() + 1;
    list_springs_ = true;
    list_stale_ = false;
    held_.clear(n_owned_, config_.contact.needs_rolling_history());
    // The carry-over reads each partner's id from the store, so every slot must name a particle (a checkpoint's
    // are checked when it is read).
    for (const std::uint32_t j : nbr_.partner) {
      if (j >= p_.size()) throw std::invalid_argument("DemSolver::restore: a neighbour entry names no particle");
    }
  }
  sized_ = p_.has_own_sizes(config_.species);
  double d_max = p_.max_diameter();
  for (const Species& sp : config_.species) d_max = std::max(d_max, sp.d_max());
  cell_size_ = d_max + config_.skin;
  if (domain_) {
    if (!portable) throw std::invalid_argument("DemSolver::restore: a distributed solver takes a portable state");
    // The blocks dealt by the restored particles' counts (every rank holds all of them here), then each rank keeps
    // its own: a state written on any number of ranks continues on this one.
    BlockLayout<Dim>& layout = domain_->layout();
    std::vector<double> weight(static_cast<std::size_t>(layout.blocks()), 0.0);
    for (std::size_t i = 0; i < p_.size(); ++i) weight[static_cast<std::size_t>(layout.block_at(p_.pos(i)))] += 1.0;
    layout.assign(weight, domain_->size());
    std::vector<std::size_t> keep;
    for (std::size_t i = 0; i < n_owned_; ++i) {
      if (domain_->owner_of(p_.pos(i)) == domain_->rank()) keep.push_back(i);
    }
    select_owned(keep);
  }
}

template class DemSolver<2>;
template class DemSolver<3>;

}  // namespace fluidbed
