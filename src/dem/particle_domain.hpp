#pragma once
// A DEM split over ranks (docs/parallel.md): each rank owns the particles whose centres lie in its blocks
// (parallel/block_layout.hpp) and holds copies, ghosts, of the other ranks' particles within reach of its blocks:
// the contact reach (largest diameter + skin) and the coupling kernel's reach. Ghosts are set up when the neighbour
// list is built and follow their owners every step (forward()); particles change owner only then (migration), taking
// with them what is theirs: the attributes of the store and, packed by the solver, their springs.
//
// The records are the store's own arrays (ParticleStore::for_each_array), so adding an attribute to the store adds
// it to migration and ghosts alike.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "core/error.hpp"
#include "core/periodic.hpp"
#include "core/vec.hpp"
#include "dem/particle_store.hpp"
#include "parallel/block_layout.hpp"
#include "parallel/comm.hpp"

namespace fluidbed {

/// Appends particles `slots` of p (every attribute) to a message: their count, whether the fluid's arrays come,
/// then attribute after attribute.
template <int Dim>
void pack_particles(Bytes& b, const ParticleStore<Dim>& p, std::span<const std::uint32_t> slots) {
  pack(b, static_cast<std::uint64_t>(slots.size()));
  pack(b, static_cast<std::uint64_t>(p.holds_fluid_arrays()));
  p.for_each_array([&](const std::string&, const auto& a, ArrayRole) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    const std::size_t at = b.size();
    b.resize(at + slots.size() * sizeof(T));
    T* out = reinterpret_cast<T*>(b.data() + at);  // memcpy per value: the message need not be aligned
    for (std::size_t k = 0; k < slots.size(); ++k) std::memcpy(out + k, &a[slots[k]], sizeof(T));
  });
}
/// Appends the particles of such a message to p; returns how many. An empty p takes the message's arrays (with
/// or without the fluid's); a store that holds particles must hold the same arrays.
template <int Dim>
std::size_t unpack_particles(Unpacker& u, ParticleStore<Dim>& p) {
  const auto n = static_cast<std::size_t>(u.get<std::uint64_t>());
  const bool fluid = u.get<std::uint64_t>() != 0;
  if (p.size() == 0) p.hold_fluid_arrays(fluid);
  if (fluid != p.holds_fluid_arrays()) throw_simulation_error("particle message without the store's fluid arrays (internal error)");
  p.for_each_array([&](const std::string&, auto& a, ArrayRole) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    const std::size_t at = a.size();
    a.resize(at + n);
    if (n > 0) std::memcpy(a.data() + at, u.take(n * sizeof(T)), n * sizeof(T));
  });
  return n;
}

/// Who sends which owned particles to whom as ghosts, and where the ghosts received are stored.
struct GhostPlan {
  std::vector<int> ranks;                          ///< partners, ascending
  std::vector<std::vector<std::uint32_t>> send;    ///< per partner: owned slots sent, in order
  std::vector<std::size_t> recv_first, recv_count; ///< per partner: the ghost slots its particles fill
  std::vector<std::vector<double>> send_buf, recv_buf;
  std::size_t ghosts() const {
    std::size_t n = 0;
    for (std::size_t c : recv_count) n += c;
    return n;
  }
  std::size_t sent() const {
    std::size_t n = 0;
    for (const auto& s : send) n += s.size();
    return n;
  }
};

template <int Dim>
class ParticleDomain {
 public:
  ParticleDomain(const Comm& comm, BlockLayout<Dim> layout, const PeriodicBox<Dim>& periodic)
      : comm_(&comm), layout_(std::move(layout)), periodic_(periodic) {}

  const Comm& comm() const { return *comm_; }
  int rank() const { return comm_->rank(); }
  int size() const { return comm_->size(); }
  BlockLayout<Dim>& layout() { return layout_; }
  const BlockLayout<Dim>& layout() const { return layout_; }

  /// Reaches of a ghost: a particle is another rank's ghost when it lies within `contact` (Euclidean) of one of
  /// that rank's blocks, or within kernel[a] of it along every axis a (the coupling kernel's cells).
  void set_reach(double contact, const Vec<Dim>& kernel) {
    contact_ = contact;
    kernel_ = kernel;
  }
  double contact_reach() const { return contact_; }
  const Vec<Dim>& kernel_reach() const { return kernel_; }
  /// The widest reach along axis a: a block must be at least this wide for the 3^Dim blocks around a particle's
  /// own to hold every rank that needs it.
  double reach(int a) const { return std::max(contact_, kernel_[a]); }

  int owner_of(const Vec<Dim>& x) const { return layout_.owner(layout_.block_at(x)); }

  /// The ranks other than this one that need a particle at x, which lies in block `block` (block_at(x)), as a
  /// ghost, ascending, into `out` (cleared first).
  void ghost_ranks(const Vec<Dim>& x, int block, std::vector<int>& out) const {
    out.clear();
    const auto b = static_cast<std::size_t>(block);
    const Foreign& f = foreign();
    for (std::uint32_t k = f.offset[b]; k < f.offset[b + 1]; ++k) {
      const int r = f.owner[k];
      if (std::find(out.begin(), out.end(), r) == out.end() && near(x, f.lo[k], f.hi[k])) out.push_back(r);
    }
    std::sort(out.begin(), out.end());
  }

  /// The ranks that own a block next to one of this rank's (periodic images included), ascending: the only ranks
  /// a ghost goes to, or a particle moving less than a block between list builds. Symmetric: each of them lists
  /// this rank.
  const std::vector<int>& neighbour_ranks() const { return foreign().neighbours; }

  /// Ghost positions, velocities and spins from their owners (after every step), by the plan of the last set-up.
  void forward(ParticleStore<Dim>& p, GhostPlan& plan) const {
    constexpr int NS = kSpinComponents<Dim>;
    constexpr std::size_t stride = 2 * Dim + NS;
    const std::size_t nr = plan.ranks.size();
    plan.send_buf.resize(nr);
    plan.recv_buf.resize(nr);
    for (std::size_t k = 0; k < nr; ++k) {
      std::vector<double>& out = plan.send_buf[k];
      out.resize(plan.send[k].size() * stride);
      double* o = out.data();
      for (const std::uint32_t i : plan.send[k]) {
        for (int a = 0; a < Dim; ++a) *o++ = p.coord(a)[i];
        for (int a = 0; a < Dim; ++a) *o++ = p.velocity(a)[i];
        for (int c = 0; c < NS; ++c) *o++ = p.spin_component(c)[i];
      }
      plan.recv_buf[k].resize(plan.recv_count[k] * stride);
    }
    comm_->exchange_with(plan.ranks, plan.send_buf, plan.recv_buf);
    for (std::size_t k = 0; k < nr; ++k) {
      const double* in = plan.recv_buf[k].data();
      for (std::size_t g = plan.recv_first[k]; g < plan.recv_first[k] + plan.recv_count[k]; ++g) {
        for (int a = 0; a < Dim; ++a) p.coord(a)[g] = *in++;
        for (int a = 0; a < Dim; ++a) p.velocity(a)[g] = *in++;
        for (int c = 0; c < NS; ++c) p.spin_component(c)[g] = *in++;
      }
    }
  }

  /// Sets up the ghosts of the owned particles p[0, owned): sends each to the ranks that need it (whole records)
  /// and appends the ones received, partner by partner in rank order; returns the plan that forward() follows.
  /// `block`, when it holds `owned` entries, gives each particle's block (block_at of its position), known already.
  GhostPlan exchange_ghosts(ParticleStore<Dim>& p, std::size_t owned, std::span<const int> block = {}) const {
    // Only the neighbours talk (ghost_ranks names no other rank).
    const std::vector<int>& nbr = neighbour_ranks();
    std::vector<std::vector<std::uint32_t>> to(nbr.size());
    std::vector<int> ranks;
    const bool known = block.size() == owned;
    for (std::size_t i = 0; i < owned; ++i) {
      const Vec<Dim> x = p.pos(i);
      ghost_ranks(x, known ? block[i] : layout_.block_at(x), ranks);
      for (int r : ranks) {
        const auto k = static_cast<std::size_t>(std::lower_bound(nbr.begin(), nbr.end(), r) - nbr.begin());
        to[k].push_back(static_cast<std::uint32_t>(i));
      }
    }
    std::vector<Bytes> out(nbr.size());
    for (std::size_t k = 0; k < nbr.size(); ++k) {
      if (!to[k].empty()) pack_particles<Dim>(out[k], p, to[k]);
    }
    const std::vector<Bytes> in = comm_->exchange_among(nbr, out);
    GhostPlan plan;
    for (std::size_t k = 0; k < nbr.size(); ++k) {
      const int r = nbr[k];
      if (to[k].empty() && in[k].empty()) continue;
      plan.ranks.push_back(r);
      plan.send.push_back(std::move(to[k]));
      plan.recv_first.push_back(p.size());
      Unpacker u(in[k]);
      std::size_t got = 0;
      while (!u.done()) got += unpack_particles(u, p);
      plan.recv_count.push_back(got);
    }
    return plan;
  }

 private:
  /// Point x within reach of the box [lo, hi] (a block's image, shifted by whole periods).
  bool near(const Vec<Dim>& x, const Vec<Dim>& lo, const Vec<Dim>& hi) const {
    double d2 = 0.0;
    bool in_kernel = true;
    for (int a = 0; a < Dim; ++a) {
      const double d = std::max({lo[a] - x[a], x[a] - hi[a], 0.0});
      d2 += d * d;
      in_kernel = in_kernel && d <= kernel_[a];
    }
    return d2 <= contact_ * contact_ || in_kernel;
  }

  /// Per block, its neighbours (the 3^Dim blocks around it, periodic images included) that other ranks own: a
  /// particle in a block without any (most blocks, inside a rank's region) is nobody's ghost, found without a test.
  struct Foreign {
    std::uint64_t version = ~std::uint64_t{0};
    std::vector<std::uint32_t> offset;  ///< per block, into the arrays below
    std::vector<int> owner;
    std::vector<Vec<Dim>> lo, hi;  ///< the block's box, shifted to the image next to the block it neighbours
    std::vector<int> neighbours;  ///< the owners of the blocks next to this rank's, ascending
  };
  const Foreign& foreign() const {
    Foreign& f = foreign_;
    if (f.version == layout_.version() && f.offset.size() == static_cast<std::size_t>(layout_.blocks()) + 1) return f;
    const int me = rank();
    f.offset.assign(1, 0);
    f.owner.clear();
    f.lo.clear();
    f.hi.clear();
    f.neighbours.clear();
    for (int b = 0; b < layout_.blocks(); ++b) {
      Index<Dim> off{};
      for (int a = 0; a < Dim; ++a) off[a] = -1;
      while (true) {
        Index<Dim> shift{};
        const int nb = layout_.neighbour(b, off, shift);
        if (nb >= 0 && layout_.owner(nb) != me) {
          f.owner.push_back(layout_.owner(nb));
          Vec<Dim> lo = layout_.lo(nb), hi = layout_.hi(nb);
          for (int a = 0; a < Dim; ++a) {
            const double period = shift[a] * layout_.length(a);
            lo[a] = lo[a] + period;
            hi[a] = hi[a] + period;
          }
          f.lo.push_back(lo);
          f.hi.push_back(hi);
        }
        int a = 0;
        while (a < Dim && off[a] == 1) off[a++] = -1;
        if (a == Dim) break;
        ++off[a];
      }
      f.offset.push_back(static_cast<std::uint32_t>(f.owner.size()));
      if (layout_.owner(b) == me) {
        f.neighbours.insert(f.neighbours.end(), f.owner.begin() + f.offset[static_cast<std::size_t>(b)], f.owner.end());
      }
    }
    std::sort(f.neighbours.begin(), f.neighbours.end());
    f.neighbours.erase(std::unique(f.neighbours.begin(), f.neighbours.end()), f.neighbours.end());
    f.version = layout_.version();
    return f;
  }

  const Comm* comm_;
  BlockLayout<Dim> layout_;
  mutable Foreign foreign_;  // a cache of the deal, filled on first use after it changes (never inside threads)
  PeriodicBox<Dim> periodic_;
  double contact_ = 0.0;
  Vec<Dim> kernel_{};
};

}  // namespace fluidbed
