#pragma once
// The contact history a particle holds, keyed by its partners' ids: the tangential springs (and rolling springs)
// of its list entries that are not +0. It is what survives a rebuild of the neighbour list, what travels with the
// particle to another rank, and what a checkpoint keeps (docs/parallel.md), so that none of these depends on
// where either partner is stored. A spring of -0 is held too: a rebuilt list then holds the same bits as the
// list it replaces.
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/vec.hpp"
#include "dem/selection.hpp"

namespace fluidbed {

template <int Dim>
struct HeldSprings {
  // 32-bit, as the list's entries it is a part of (build_neighbor_list refuses a longer list).
  std::vector<std::uint32_t> offset{0};  ///< CSR over the particles, in the store's order
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
    if (offset.back() == std::numeric_limits<std::uint32_t>::max()) {
      throw std::length_error("too many held springs for 32-bit offsets");
    }
    ++offset.back();
  }
  void add_particle() {
    const std::uint32_t end = offset.back();  // a copy: push_back may move the element it would read
    offset.push_back(end);
  }
  /// New particle k takes old particle order[k]'s entries; particles order does not name are dropped. The new
  /// arrays are sized exactly (counted first): appended one by one they would hold up to twice their entries.
  void select(const std::vector<std::size_t>& order) {
    if (is_ascending_selection(order)) {
      // Each kept particle's entries move towards the front (never past their old place): in place.
      std::size_t to = 0;
      for (std::size_t k = 0; k < order.size(); ++k) {
        const std::size_t from = offset[order[k]], count = offset[order[k] + 1] - from;
        if (from != to) {
          const auto f = static_cast<std::ptrdiff_t>(from), t = static_cast<std::ptrdiff_t>(to);
          const auto c = static_cast<std::ptrdiff_t>(count);
          std::copy(partner_id.begin() + f, partner_id.begin() + f + c, partner_id.begin() + t);
          std::copy(xi.begin() + f, xi.begin() + f + c, xi.begin() + t);
          if (rolling_) std::copy(roll.begin() + f, roll.begin() + f + c, roll.begin() + t);
        }
        offset[k] = static_cast<std::uint32_t>(to);
        to += count;
      }
      offset[order.size()] = static_cast<std::uint32_t>(to);
      offset.resize(order.size() + 1);
      partner_id.resize(to);
      xi.resize(to);
      roll.resize(rolling_ ? to : 0);
      return;
    }
    HeldSprings out;
    out.rolling_ = rolling_;
    out.offset = std::vector<std::uint32_t>(order.size() + 1, 0u);
    for (std::size_t k = 0; k < order.size(); ++k) out.offset[k + 1] = out.offset[k] + offset[order[k] + 1] - offset[order[k]];
    const std::size_t m = out.offset[order.size()];
    out.partner_id.resize(m);
    out.xi.resize(m);
    out.roll.resize(rolling_ ? m : 0);
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::size_t from = offset[order[k]], count = offset[order[k] + 1] - from, to = out.offset[k];
      std::copy_n(partner_id.begin() + static_cast<std::ptrdiff_t>(from), count, out.partner_id.begin() + static_cast<std::ptrdiff_t>(to));
      std::copy_n(xi.begin() + static_cast<std::ptrdiff_t>(from), count, out.xi.begin() + static_cast<std::ptrdiff_t>(to));
      if (rolling_) std::copy_n(roll.begin() + static_cast<std::ptrdiff_t>(from), count, out.roll.begin() + static_cast<std::ptrdiff_t>(to));
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
