#pragma once
// What the solvers ask of the processes they run on: global reductions, the exchange of ghost layers between
// sub-domains, and the movement of packed records (particles, their contact history) between ranks. The serial
// implementation owns the whole domain, so a halo exchange has no neighbour to talk to (the physical boundary
// conditions fill every ghost cell), a reduction is the value itself and an exchange is a copy to itself; the MPI
// implementation (mpi_comm.hpp) replaces it without touching the solvers, which already call it at the points where
// ranks meet. A sum that must not depend on the number of ranks is accumulated exactly (ExactSum) on each rank and
// reduced exactly: sum(const ExactSum&).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "core/field.hpp"
#include "parallel/exact_sum.hpp"

namespace fluidbed {

/// A packed message: records of plain values, appended and read back in the same order (pack, Unpacker).
using Bytes = std::vector<std::byte>;

/// Appends the bytes of plain values (trivially copyable) to a message.
template <class T>
void pack(Bytes& b, const T& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::size_t at = b.size();
  b.resize(at + sizeof(T));
  std::memcpy(b.data() + at, &v, sizeof(T));
}
template <class T>
void pack_span(Bytes& b, std::span<const T> v) {
  static_assert(std::is_trivially_copyable_v<T>);
  pack(b, static_cast<std::uint64_t>(v.size()));
  const std::size_t at = b.size();
  b.resize(at + v.size_bytes());
  if (!v.empty()) std::memcpy(b.data() + at, v.data(), v.size_bytes());
}

/// Reads a message back in the order it was packed.
class Unpacker {
 public:
  explicit Unpacker(std::span<const std::byte> b) : b_(b) {}
  template <class T>
  T get() {
    T v;
    std::memcpy(&v, take(sizeof(T)), sizeof(T));
    return v;
  }
  template <class T>
  std::vector<T> get_vector() {
    const auto n = static_cast<std::size_t>(get<std::uint64_t>());
    std::vector<T> v(n);
    if (n > 0) std::memcpy(v.data(), take(n * sizeof(T)), n * sizeof(T));
    return v;
  }
  bool done() const { return at_ == b_.size(); }
  /// The next n bytes, as they are (a block of values packed at once).
  const std::byte* take(std::size_t n);

 private:
  std::span<const std::byte> b_;
  std::size_t at_ = 0;
};

/// Which ghosts a halo exchange fills: all of them (edges and corners too), or those beyond the box's faces.
enum class HaloCells { All, Faces };

class Comm {
 public:
  virtual ~Comm() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Sum, maximum and minimum over all ranks (the same answer on every rank, in a fixed order of ranks).
  virtual double sum(double local) const = 0;
  virtual double max(double local) const = 0;
  virtual double min(double local) const = 0;
  /// Element-wise sum over ranks, in place.
  virtual void sum(std::span<double> values) const = 0;
  /// Element-wise maximum over ranks, in place (a maximum is exact: no order of ranks changes it).
  virtual void max(std::span<double> values) const = 0;
  /// Element-wise sum of integers over ranks, in place (exact).
  virtual void sum(std::span<std::int64_t> values) const = 0;
  /// The exact sum over ranks of every rank's exact partial sum, rounded once: the same bits for any number of
  /// ranks and any split of the terms among them.
  virtual double sum(const ExactSum& local) const = 0;
  /// Fill the ghost cells of f that lie inside the domain from the ranks that own them.
  virtual void exchange_halo(Field<2>& f) const = 0;
  virtual void exchange_halo(Field<3>& f) const = 0;
  /// The same when the caller knows every rank's box of f (boxes[r] = f.box() on rank r, from all_boxes): no
  /// collective call, only the ranks whose boxes touch talk. A solver that exchanges the same kind of field many
  /// times gathers the boxes once. HaloCells::Faces fills only the ghosts beyond a face of the box (outside it
  /// along one axis): all a (2 Dim + 1)-point stencil reads, from the face neighbours only (6 ranks in 3D, not 26).
  virtual void exchange_halo_among(Field<2>& f, std::span<const IndexBox<2>> boxes, HaloCells cells) const = 0;
  virtual void exchange_halo_among(Field<3>& f, std::span<const IndexBox<3>> boxes, HaloCells cells) const = 0;

  /// Every rank's bytes, in rank order, on every rank.
  virtual std::vector<Bytes> allgather(const Bytes& local) const = 0;
  /// Every rank's bytes, in rank order, on rank `root` (an empty list on the others).
  virtual std::vector<Bytes> gather(const Bytes& local, int root) const = 0;
  /// Rank root's bytes on every rank.
  virtual void broadcast(Bytes& data, int root) const = 0;
  /// An irregular exchange: send[r] goes to rank r (send has size() entries, most of them empty); returns what
  /// every rank sent to this one (received[r] from rank r).
  virtual std::vector<Bytes> exchange(const std::vector<Bytes>& send) const = 0;
  /// An irregular exchange among neighbours: send[k] goes to ranks[k]; returns what ranks[k] sent to this one.
  /// The relation must be symmetric (every rank in `ranks` lists this one): then only neighbours talk, in
  /// messages of any size, and the cost does not grow with the number of ranks as exchange()'s does.
  virtual std::vector<Bytes> exchange_among(std::span<const int> ranks, const std::vector<Bytes>& send) const = 0;
  /// A regular exchange with known partners: send[k] goes to ranks[k] and recv[k], sized by the caller to what
  /// ranks[k] sends, is filled from it (both sides know the sizes, as after a ghost set-up).
  virtual void exchange_with(std::span<const int> ranks, const std::vector<std::vector<double>>& send,
                             std::vector<std::vector<double>>& recv) const = 0;
  /// Wait for every rank.
  virtual void barrier() const = 0;
  /// Whether every rank calls this within `timeout_s` of the first (on a channel of its own, so that ranks waiting
  /// in another collective do not match it): how a rank that has met a failure learns whether the others have met
  /// it too, or are waiting for it. One rank: true at once.
  virtual bool all_arrive_within(double timeout_s) const = 0;
  /// Ends every rank of the run at once with this exit code (a failure one rank cannot share through a
  /// collective: it would leave the others waiting).
  [[noreturn]] virtual void abort(int code) const = 0;
  /// Seconds this process has spent inside communication calls so far, waits for the other ranks included (the
  /// performance figures split a step's time by it); zero on one process.
  virtual double seconds_communicating() const { return 0.0; }

  /// The collective verdict on a failure that some ranks may have met: nullopt when no rank failed, else the
  /// message of the failing rank with the smallest key (ties: the lowest rank), the same on every rank. A failure
  /// found by a rule on the state (a particle with the smallest id) keys on it, so that the message does not
  /// depend on how the domain was split.
  std::optional<std::string> first_failure(const std::optional<std::string>& local, double key = 0.0) const;
  /// Bytes of every rank, in rank order, as one message on every rank (allgather, concatenated).
  Bytes allgather_concat(const Bytes& local) const;
};

/// One process: no neighbour, a reduction is the value itself (not final: a test may count the exchanges).
class SerialComm : public Comm {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  double sum(double local) const override { return local; }
  double max(double local) const override { return local; }
  double min(double local) const override { return local; }
  void sum(std::span<double>) const override {}
  void max(std::span<double>) const override {}
  void sum(std::span<std::int64_t>) const override {}
  double sum(const ExactSum& local) const override { return local.value(); }
  void exchange_halo(Field<2>&) const override {}
  void exchange_halo(Field<3>&) const override {}
  void exchange_halo_among(Field<2>&, std::span<const IndexBox<2>>, HaloCells) const override {}
  void exchange_halo_among(Field<3>&, std::span<const IndexBox<3>>, HaloCells) const override {}
  std::vector<Bytes> allgather(const Bytes& local) const override { return {local}; }
  std::vector<Bytes> gather(const Bytes& local, int) const override { return {local}; }
  void broadcast(Bytes&, int) const override {}
  std::vector<Bytes> exchange(const std::vector<Bytes>& send) const override { return send; }
  std::vector<Bytes> exchange_among(std::span<const int>, const std::vector<Bytes>& send) const override {
    return send;
  }
  void exchange_with(std::span<const int> ranks, const std::vector<std::vector<double>>& send,
                     std::vector<std::vector<double>>& recv) const override {
    // Only rank 0 exists: what goes to it comes back.
    for (std::size_t k = 0; k < ranks.size(); ++k) recv[k] = send[k];
  }
  void barrier() const override {}
  bool all_arrive_within(double) const override { return true; }
  [[noreturn]] void abort(int code) const override { std::_Exit(code); }
};

/// Every rank's `mine`, in rank order, on every rank (one collective: each rank fills its own slots of a zeroed
/// table, and the integer sum over ranks is the table).
template <int Dim>
std::vector<IndexBox<Dim>> all_boxes(const Comm& comm, const IndexBox<Dim>& mine) {
  const auto p = static_cast<std::size_t>(comm.size()), me = static_cast<std::size_t>(comm.rank());
  std::vector<std::int64_t> table(2 * Dim * p, 0);
  for (int a = 0; a < Dim; ++a) {
    table[2 * Dim * me + static_cast<std::size_t>(a)] = mine.lo[a];
    table[2 * Dim * me + static_cast<std::size_t>(Dim + a)] = mine.hi[a];
  }
  comm.sum(std::span<std::int64_t>(table));
  std::vector<IndexBox<Dim>> out(p);
  for (std::size_t q = 0; q < p; ++q) {
    for (int a = 0; a < Dim; ++a) {
      out[q].lo[a] = static_cast<int>(table[2 * Dim * q + static_cast<std::size_t>(a)]);
      out[q].hi[a] = static_cast<int>(table[2 * Dim * q + static_cast<std::size_t>(Dim + a)]);
    }
  }
  return out;
}

/// Every rank's part `mine` of the fields `from` (packed together, field by field), written into `into` at the same
/// indices: on every rank (root < 0) or on rank `root` only (the others receive nothing). `into` may be `from`, each
/// rank completing its own fields, or fields over a larger box (the whole domain) that holds every rank's part.
template <int Dim>
void gather_parts(const Comm& comm, const IndexBox<Dim>& mine, std::span<const Field<Dim>* const> from,
                  std::span<Field<Dim>* const> into, int root = -1) {
  // Copied a line along axis 0 at a time (contiguous in every field).
  auto line_starts = [](IndexBox<Dim> b) {
    if (b.count() > 0) b.hi[0] = b.lo[0] + 1;
    return b;
  };
  Bytes msg;
  pack(msg, mine);
  const std::size_t line = static_cast<std::size_t>(mine.extent(0)) * sizeof(double);
  msg.reserve(msg.size() + from.size() * mine.count() * sizeof(double));
  for (const Field<Dim>* f : from) {
    for_each(line_starts(mine), [&](const Index<Dim>& c) {
      const std::size_t at = msg.size();
      msg.resize(at + line);
      std::memcpy(msg.data() + at, f->data().data() + f->index(c), line);
    });
  }
  for (const Bytes& part : root < 0 ? comm.allgather(msg) : comm.gather(msg, root)) {
    Unpacker in(part);
    const auto box = in.get<IndexBox<Dim>>();
    const std::size_t bytes = static_cast<std::size_t>(box.extent(0)) * sizeof(double);
    for (Field<Dim>* f : into) {
      double* v = f->data().data();
      for_each(line_starts(box), [&](const Index<Dim>& c) { std::memcpy(v + f->index(c), in.take(bytes), bytes); });
    }
  }
}

/// The communicator of a run on one process.
inline const Comm& serial_comm() {
  static const SerialComm comm;
  return comm;
}

}  // namespace fluidbed
