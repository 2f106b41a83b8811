#pragma once
// The contact history a particle holds, keyed by its partners' ids: the tangential springs (and rolling springs)
// of its list entries that are not +0. It is what survives a rebuild of the neighbour list, what travels with the
// particle to another rank, and what a checkpoint keeps (docs/parallel.md), so that none of these depends on
// where either partner is stored. A spring of -0 is held too: a rebuilt list then holds the same bits as the
// list it replaces.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec.hpp"

namespace fluidbed {

template <int Dim>
struct HeldSprings {
  std::vector<std::size_t> offset{0};  ///< CSR over the particles, in the store's order
  std::vector<std::int64_t> partner_id;
  std::vector<Vec<Dim>> xi;      ///< tangential spring, as the particle sees the contact
  std::vector<Spin<Dim>> roll;   ///< rolling spring (laws with one; else empty)

  std::size_t particles() const { return offset.size() - 1; }
  std::size_t entries() const { return partner_id.size(); }
  void clear(std::size_t n, bool rolling) {
    offset.assign(n + 1, 0);
    partner_id.clear();
    xi.clear();
    roll.clear();
    rolling_ = rolling;
  }
  /// Appends one entry to the last particle (call add_particle() first).
  void add(std::int64_t partner, const Vec<Dim>& x, const Spin<Dim>& r) {
    partner_id.push_back(partner);
    xi.push_back(x);
    if (rolling_) roll.push_back(r);
    ++offset.back();
  }
  void add_particle() { offset.push_back(offset.back()); }
  /// New particle k takes old particle order[k]'s entries; particles order does not name are dropped.
  void select(const std::vector<std::size_t>& order) {
    HeldSprings out;
    out.clear(0, rolling_);
    for (std::size_t k : order) {
      out.add_particle();
      for (std::size_t q = offset[k]; q < offset[k + 1]; ++q) out.add(partner_id[q], xi[q], rolling_ ? roll[q] : Spin<Dim>{});
    }
    *this = std::move(out);
  }
  bool keeps_rolling() const { return rolling_; }

  /// Every bit of v is +0 (a -0 is a spring to keep).
  static bool plus_zero(const Vec<Dim>& v) {
    std::uint64_t bits = 0;  // or-ed, not tested one by one: no branch
    for (int a = 0; a < Dim; ++a) bits |= std::bit_cast<std::uint64_t>(v[a]);
    return bits == 0;
  }
  static bool plus_zero(const Spin<Dim>& s)
    requires(Dim == 2)
  {
    return std::bit_cast<std::uint64_t>(s) == 0;
  }

 private:
  bool rolling_ = false;
};

}  // namespace fluidbed
