#pragma once
// The tangential springs of the particles against the plane walls (Eq. 9's history, one per wall), held in a record
// only for the particles that hold one: most of a bed never touches a wall, so a dense array of 2 Dim springs per
// particle cost 64 bytes (2D) or 144 (3D) of every particle. A particle without a record holds +0 in every
// component, exactly what the dense array held for it; a record is kept while any of its components is not +0 (a
// -0 included), so dense and sparse hold the same bits and a checkpoint (written dense) restarts bit for bit.
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "core/vec.hpp"
#include "dem/selection.hpp"

namespace fluidbed {

template <int Dim>
class WallSprings {
 public:
  static constexpr int kWalls = 2 * Dim;  ///< low and high side of each axis, Wall<Dim> order
  using Springs = std::array<Vec<Dim>, kWalls>;

  /// Particles covered (one slot each, in the store's order).
  std::size_t size() const { return record_.size(); }
  /// Records held (at most one per particle; compact() drops those that returned to +0).
  std::size_t records() const { return springs_.size(); }
  /// The record of particle i, or -1 when every one of its springs is +0.
  std::int32_t record(std::size_t i) const { return record_[i]; }
  Springs& springs(std::int32_t r) { return springs_[static_cast<std::size_t>(r)]; }
  const Springs& springs(std::int32_t r) const { return springs_[static_cast<std::size_t>(r)]; }

  /// Spring of particle i against wall w.
  Vec<Dim> get(std::size_t i, int w) const {
    const std::int32_t r = record_[i];
    return r < 0 ? Vec<Dim>{} : springs_[static_cast<std::size_t>(r)][static_cast<std::size_t>(w)];
  }
  /// Sets it, giving particle i a record when it needs one. Not for concurrent use.
  void set(std::size_t i, int w, const Vec<Dim>& v) {
    if (record_[i] < 0) {
      if (is_plus_zero(v)) return;
      record_[i] = static_cast<std::int32_t>(springs_.size());
      springs_.push_back(Springs{});
    }
    springs_[static_cast<std::size_t>(record_[i])][static_cast<std::size_t>(w)] = v;
  }

  /// n particles, no springs.
  void reset(std::size_t n) {
    record_.assign(n, -1);
    springs_.clear();
  }
  /// One more particle (the last slot), without springs.
  void push_back() { record_.push_back(-1); }
  /// New slot k takes old slot order[k]; slots order does not name are dropped with their records (a selection).
  void permute(const std::vector<std::size_t>& order) {
    select_slots(record_, order);
    compact();
  }
  /// Keeps the records that some slot names and that hold a component other than +0, laid out in slot order.
  void compact() {
    std::vector<Springs> kept;
    kept.reserve(records());
    for (std::int32_t& r : record_) {
      if (r < 0) continue;
      const Springs& s = springs_[static_cast<std::size_t>(r)];
      bool held = false;
      for (const Vec<Dim>& v : s) held = held || !is_plus_zero(v);
      if (held) {
        r = static_cast<std::int32_t>(kept.size());
        kept.push_back(s);
      } else {
        r = -1;
      }
    }
    springs_.swap(kept);
  }

  /// Every component of v is +0 (the bits of 0.0, not -0.0).
  static bool is_plus_zero(const Vec<Dim>& v) {
    bool zero = true;
    for (int c = 0; c < Dim; ++c) zero = zero && std::bit_cast<std::uint64_t>(v[c]) == 0;
    return zero;
  }

 private:
  std::vector<std::int32_t> record_;  ///< per particle slot
  std::vector<Springs> springs_;
};

}  // namespace fluidbed
