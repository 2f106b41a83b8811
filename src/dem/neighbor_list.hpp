#pragma once
// O(N) neighbour search: a cell list with particles sorted by cell, and a full (both-partner) Verlet list.
// Each particle owns the list of its partners, so force loops write only their own particle and the result
// does not depend on how particles are split among threads.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec2.hpp"
#include "dem/particle_store.hpp"

namespace fluidbed {

struct NeighborList {
  std::vector<std::size_t> offset;  ///< CSR: partners of slot i are entries offset[i] .. offset[i+1]
  std::vector<std::uint32_t> partner;  ///< storage slot of the partner
  std::vector<Vec2> history;           ///< tangential spring of the contact, mirrored in the partner's entry

  std::size_t entries() const { return partner.size(); }
};

/// Bin particles into square cells of side >= `cell_size` covering their bounding box; returns the storage
/// order that sorts them by cell (row-major, stable), so neighbours sit together in memory.
std::vector<std::size_t> sort_by_cell(const ParticleStore& p, double cell_size);

/// Build the full list of pairs with centre distance < r_i + r_j + skin. Particles must be sorted by
/// `sort_by_cell` with the same cell size (>= max diameter + skin). Deterministic order.
void build_neighbor_list(const ParticleStore& p, double cell_size, double skin, NeighborList& out);

/// Brute-force O(N^2) set of touching pairs (i < j by id), for tests.
std::vector<std::pair<std::int64_t, std::int64_t>> brute_force_contacts(const ParticleStore& p, double skin);

}  // namespace fluidbed
