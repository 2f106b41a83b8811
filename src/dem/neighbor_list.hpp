#pragma once
// O(N) neighbour search: a cell list with particles sorted by cell (3^Dim cells searched), and a full
// (both-partner) Verlet list. Each particle owns the list of its partners, so force loops write only their own
// particle and the result does not depend on how particles are split among threads.
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/periodic.hpp"
#include "core/vec.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

template <int Dim>
struct NeighborList {
  /// CSR: partners of slot i are entries offset[i] .. offset[i+1]; 32-bit, as the entries they count (a list of
  /// more than 2^32 - 1 entries is refused when it is linked).
  std::vector<std::uint32_t> offset;
  /// Storage slot of the partner (what the force loop reads). Its id, p.id[partner], is the key the contact
  /// history is carried by across rebuilds; it is read from the store, not kept per entry (8 bytes an entry).
  std::vector<std::uint32_t> partner;
  /// Tangential spring of the contact, mirrored in the partner's entry: the per-entry form of a list's springs
  /// (a saved state, a test's view); a stepping DemSolver keeps them by contact and leaves this empty.
  std::vector<Vec<Dim>> history;
  /// Rolling spring torque of the contact (laws with a rolling spring only, else empty), mirrored like history.
  std::vector<Spin<Dim>> rolling;

  std::size_t entries() const { return partner.size(); }
};

/// Per-thread partner buffers of build_neighbor_list, kept between rebuilds by their owner: for 100,000 spheres
/// they are ~6 MB, over malloc's mmap threshold, so a fresh allocation per rebuild costs page faults each time.
/// The first thread's buffer is the list's own partner array (found[0] stays empty).
struct NeighborScratch {
  std::vector<std::vector<std::uint32_t>> found;
};

/// Bin particles into cubic cells of side >= `cell_size` covering their bounding box; returns the storage
/// order that sorts them by cell (x fastest, then y, then z; stable), so neighbours sit together in memory.
template <int Dim>
std::vector<std::size_t> sort_by_cell(const ParticleStore<Dim>& p, double cell_size);

/// Build the full list of pairs with centre distance < (r_i + r_j) + skin, each particle's entries in ascending
/// slot of the partner; springs zero. The cell size must be at least the largest diameter + skin.
template <int Dim>
void build_neighbor_list(const ParticleStore<Dim>& p, double cell_size, double skin, NeighborList<Dim>& out);
/// The same, reusing the buffers of `scratch` (the result does not depend on what they held).
template <int Dim>
void build_neighbor_list(const ParticleStore<Dim>& p, double cell_size, double skin, NeighborList<Dim>& out,
                         NeighborScratch& scratch);

/// The same across periodic axes: the particles (inside [0, L) on each periodic axis) are binned with their images
/// within `cell_size` of each periodic side, so a pair is found once, through its nearest image (the partner's
/// entry names its own slot). Needs L > 2 cell_size on each periodic axis, else a pair could meet twice.
template <int Dim>
void build_neighbor_list(const ParticleStore<Dim>& p, double cell_size, double skin, NeighborList<Dim>& out,
                         NeighborScratch& scratch, const PeriodicBox<Dim>& periodic);

/// The same for a store whose slots from `owned` on are ghosts (copies of other ranks' particles): only the owned
/// particles are searched, each ghost gets the mirror entries of its owned partners, and pairs of two ghosts are
/// left out. Every particle's entries are in ascending rank[partner] (the partners' places in the canonical order,
/// DemSolver::canonical_order), or in ascending slot when `rank` is empty (slots in that order). No springs per
/// entry (history and rolling empty): the solver keeps them by contact.
template <int Dim>
void build_neighbor_list(const ParticleStore<Dim>& p, std::size_t owned, double cell_size, double skin,
                         NeighborList<Dim>& out, NeighborScratch& scratch, const PeriodicBox<Dim>& periodic,
                         std::span<const std::uint32_t> rank);

/// Brute-force O(N^2) set of touching pairs (i < j by id), for tests.
template <int Dim>
std::vector<std::pair<std::int64_t, std::int64_t>> brute_force_contacts(const ParticleStore<Dim>& p, double skin);
/// The same with minimum-image separations on the periodic axes.
template <int Dim>
std::vector<std::pair<std::int64_t, std::int64_t>> brute_force_contacts(const ParticleStore<Dim>& p, double skin,
                                                                        const PeriodicBox<Dim>& periodic);

}  // namespace fluidbed
