#include "parallel/mpi_comm.hpp"

#ifdef FLUIDBED_HAVE_MPI

#include <mpi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <thread>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace fluidbed {

namespace {

// Adds the time of the enclosing call to the process's communication seconds.
class Inside {
 public:
  explicit Inside(double& total) : total_(total), t0_(std::chrono::steady_clock::now()) {}
  ~Inside() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
  Inside(const Inside&) = delete;
  Inside& operator=(const Inside&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point t0_;
};

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw_simulation_error(std::string("MPI: ") + what + " failed");
}

// The entries of `region` outside `own` (with HaloCells::Faces: outside it along exactly one axis), in storage order
// (axis 0 fastest): what one rank sends another for the other's ghosts, enumerated alike on both sides.
template <int Dim, class F>
void for_each_outside(const IndexBox<Dim>& region, const IndexBox<Dim>& own, HaloCells cells, F&& f) {
  for_each(region, [&](const Index<Dim>& c) {
    int out = 0;
    for (int a = 0; a < Dim; ++a) out += (c[a] < own.lo[a] || c[a] >= own.hi[a]) ? 1 : 0;
    if (out > 0 && (cells == HaloCells::All || out == 1)) f(c);
  });
}

// A contiguous stretch of a field's storage: what a halo copies with one memcpy (a line along axis 0 at least).
struct Run {
  std::size_t offset = 0, length = 0;
};

// Appends offset k to runs, extending the last run where k follows it.
void add_to_runs(std::vector<Run>& runs, std::size_t k) {
  if (!runs.empty() && runs.back().offset + runs.back().length == k) {
    ++runs.back().length;
  } else {
    runs.push_back({k, 1});
  }
}

// What one kind of halo exchange (a field's layout, every rank's box, the cells wanted) sends to and receives from
// each other rank, worked out once: the per-cell enumeration of the boxes is then no longer in the step's path,
// and a field's halo is a few memcpy's and one message per neighbour.
template <int Dim>
struct HaloPlan {
  IndexBox<Dim> allocated, box;
  HaloCells cells = HaloCells::All;
  std::vector<IndexBox<Dim>> boxes;
  struct Peer {
    int rank = 0;
    std::vector<Run> send, receive;
    std::vector<double> send_buffer, receive_buffer;
  };
  std::vector<Peer> peers;  // the ranks with something to send or receive, in rank order
  std::vector<MPI_Request> requests;

  bool fits(const Field<Dim>& f, std::span<const IndexBox<Dim>> b, HaloCells c) const {
    return f.allocated() == allocated && f.box() == box && c == cells && std::ranges::equal(b, boxes);
  }

  HaloPlan(const Field<Dim>& f, std::span<const IndexBox<Dim>> b, HaloCells c, int me)
      : allocated(f.allocated()), box(f.box()), cells(c), boxes(b.begin(), b.end()) {
    const int g = f.ghost();
    for (int q = 0; q < static_cast<int>(boxes.size()); ++q) {
      if (q == me) continue;
      const IndexBox<Dim>& bq = boxes[static_cast<std::size_t>(q)];
      Peer peer;
      peer.rank = q;
      for_each_outside<Dim>(intersect(bq.grown(g), f.box()), bq, cells,
                            [&](const Index<Dim>& i) { add_to_runs(peer.send, f.index(i)); });
      for_each_outside<Dim>(intersect(f.allocated(), bq), f.box(), cells,
                            [&](const Index<Dim>& i) { add_to_runs(peer.receive, f.index(i)); });
      if (peer.send.empty() && peer.receive.empty()) continue;
      auto total = [](const std::vector<Run>& runs) {
        std::size_t n = 0;
        for (const Run& r : runs) n += r.length;
        return n;
      };
      peer.send_buffer.resize(total(peer.send));
      peer.receive_buffer.resize(total(peer.receive));
      peers.push_back(std::move(peer));
    }
    requests.reserve(2 * peers.size());
  }

  // Fills f's ghosts inside the domain from the ranks whose boxes hold them (the same kind of field and ghost
  // width on every rank), both sides enumerating the cells in storage order.
  void exchange(MPI_Comm comm, Field<Dim>& f) {
    double* v = f.data().data();
    requests.clear();
    for (Peer& p : peers) {
      if (p.receive_buffer.empty()) continue;
      requests.emplace_back();
      check(MPI_Irecv(p.receive_buffer.data(), static_cast<int>(p.receive_buffer.size()), MPI_DOUBLE, p.rank, 0, comm,
                      &requests.back()),
            "receive of a halo");
    }
    for (Peer& p : peers) {
      if (p.send_buffer.empty()) continue;
      double* out = p.send_buffer.data();
      for (const Run& r : p.send) out = std::copy_n(v + r.offset, r.length, out);
      requests.emplace_back();
      check(MPI_Isend(p.send_buffer.data(), static_cast<int>(p.send_buffer.size()), MPI_DOUBLE, p.rank, 0, comm,
                      &requests.back()),
            "send of a halo");
    }
    check(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE), "halo exchange");
    for (const Peer& p : peers) {
      const double* in = p.receive_buffer.data();
      for (const Run& r : p.receive) {
        std::copy_n(in, r.length, v + r.offset);
        in += r.length;
      }
    }
  }
};

// The plans met so far (a run uses a handful: the cell and face fields of the solvers and the multigrid levels);
// forgotten all at once past a bound, as after many rebalancing deals.
template <int Dim>
HaloPlan<Dim>& plan_for(std::vector<HaloPlan<Dim>>& plans, const Field<Dim>& f, std::span<const IndexBox<Dim>> boxes,
                        HaloCells cells, int me) {
  for (HaloPlan<Dim>& p : plans)
    if (p.fits(f, boxes, cells)) return p;
  constexpr std::size_t kMostPlans = 64;
  if (plans.size() == kMostPlans) plans.clear();
  plans.emplace_back(f, boxes, cells, me);
  return plans.back();
}

}  // namespace

struct MpiComm::Impl {
  MPI_Comm comm = MPI_COMM_NULL;
  MPI_Comm control = MPI_COMM_NULL;  // failure verdicts only (all_arrive_within)
  bool own_mpi = false;
  int rank = 0;
  int size = 1;
  double inside_s = 0.0;  // seconds inside the calls below (seconds_communicating)
  std::vector<HaloPlan<2>> plans2;
  std::vector<HaloPlan<3>> plans3;
};

MpiComm::MpiComm() : impl_(std::make_unique<Impl>()) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "initialisation");
    impl_->own_mpi = true;
  }
  check(MPI_Comm_dup(MPI_COMM_WORLD, &impl_->comm), "duplicate of the world communicator");
  check(MPI_Comm_dup(MPI_COMM_WORLD, &impl_->control), "duplicate of the world communicator");
  MPI_Comm_rank(impl_->comm, &impl_->rank);
  MPI_Comm_size(impl_->comm, &impl_->size);
}

MpiComm::~MpiComm() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (finalised) return;
  MPI_Comm_free(&impl_->comm);
  MPI_Comm_free(&impl_->control);
  if (impl_->own_mpi) MPI_Finalize();
}

int MpiComm::rank() const { return impl_->rank; }
int MpiComm::size() const { return impl_->size; }

double MpiComm::sum(double local) const { return sum(ExactSum(local)); }

double MpiComm::sum(const ExactSum& local) const {
  const Inside inside(impl_->inside_s);
  // Integer sums of the limbs: associative, so the reduction tree of MPI cannot change the result.
  const std::array<std::int64_t, ExactSum::kWords> mine = local.words();
  std::array<std::int64_t, ExactSum::kWords> total{};
  check(MPI_Allreduce(mine.data(), total.data(), ExactSum::kWords, MPI_INT64_T, MPI_SUM, impl_->comm), "exact sum");
  return ExactSum::from_words(total).value();
}

double MpiComm::max(double local) const {
  const Inside inside(impl_->inside_s);
  double out = local;
  check(MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, impl_->comm), "maximum");
  return out;
}

double MpiComm::min(double local) const {
  const Inside inside(impl_->inside_s);
  double out = local;
  check(MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MIN, impl_->comm), "minimum");
  return out;
}

void MpiComm::sum(std::span<double> values) const {
  const Inside inside(impl_->inside_s);
  const std::size_t n = values.size();
  std::vector<std::int64_t> mine(n * ExactSum::kWords), total(mine.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto w = ExactSum(values[i]).words();
    std::copy(w.begin(), w.end(), mine.begin() + static_cast<std::ptrdiff_t>(i * ExactSum::kWords));
  }
  check(MPI_Allreduce(mine.data(), total.data(), static_cast<int>(mine.size()), MPI_INT64_T, MPI_SUM, impl_->comm),
        "element-wise exact sum");
  for (std::size_t i = 0; i < n; ++i) {
    values[i] = ExactSum::from_words(std::span<const std::int64_t, ExactSum::kWords>(
                                         total.data() + i * ExactSum::kWords, ExactSum::kWords))
                    .value();
  }
}

void MpiComm::max(std::span<double> values) const {
  const Inside inside(impl_->inside_s);
  std::vector<double> out(values.size());
  check(MPI_Allreduce(values.data(), out.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MAX, impl_->comm),
        "element-wise maximum");
  std::copy(out.begin(), out.end(), values.begin());
}

void MpiComm::sum(std::span<std::int64_t> values) const {
  const Inside inside(impl_->inside_s);
  std::vector<std::int64_t> out(values.size());
  check(MPI_Allreduce(values.data(), out.data(), static_cast<int>(values.size()), MPI_INT64_T, MPI_SUM, impl_->comm),
        "integer sum");
  std::copy(out.begin(), out.end(), values.begin());
}

namespace {
int count_of(std::size_t n) {
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw_simulation_error("MPI: a message of more than 2^31 - 1 bytes");
  }
  return static_cast<int>(n);
}
}  // namespace

std::vector<Bytes> MpiComm::allgather(const Bytes& local) const {
  const Inside inside(impl_->inside_s);
  const int p = impl_->size;
  const auto mine = static_cast<std::int64_t>(local.size());
  std::vector<std::int64_t> sizes(static_cast<std::size_t>(p));
  check(MPI_Allgather(&mine, 1, MPI_INT64_T, sizes.data(), 1, MPI_INT64_T, impl_->comm), "allgather of sizes");
  std::vector<int> counts(static_cast<std::size_t>(p)), displs(static_cast<std::size_t>(p));
  std::size_t total = 0;
  for (int q = 0; q < p; ++q) {
    counts[static_cast<std::size_t>(q)] = count_of(static_cast<std::size_t>(sizes[static_cast<std::size_t>(q)]));
    displs[static_cast<std::size_t>(q)] = count_of(total);
    total += static_cast<std::size_t>(sizes[static_cast<std::size_t>(q)]);
  }
  Bytes all(total);
  check(MPI_Allgatherv(local.data(), count_of(local.size()), MPI_BYTE, all.data(), counts.data(), displs.data(),
                       MPI_BYTE, impl_->comm),
        "allgather");
  std::vector<Bytes> out(static_cast<std::size_t>(p));
  for (int q = 0; q < p; ++q) {
    const auto b = all.begin() + displs[static_cast<std::size_t>(q)];
    out[static_cast<std::size_t>(q)].assign(b, b + counts[static_cast<std::size_t>(q)]);
  }
  return out;
}

std::vector<Bytes> MpiComm::gather(const Bytes& local, int root) const {
  const Inside inside(impl_->inside_s);
  const int p = impl_->size;
  const bool me = impl_->rank == root;
  const auto mine = static_cast<std::int64_t>(local.size());
  std::vector<std::int64_t> sizes(me ? static_cast<std::size_t>(p) : 0);
  check(MPI_Gather(&mine, 1, MPI_INT64_T, sizes.data(), 1, MPI_INT64_T, root, impl_->comm), "gather of sizes");
  std::vector<int> counts(sizes.size()), displs(sizes.size());
  std::size_t total = 0;
  for (std::size_t q = 0; q < sizes.size(); ++q) {
    counts[q] = count_of(static_cast<std::size_t>(sizes[q]));
    displs[q] = count_of(total);
    total += static_cast<std::size_t>(sizes[q]);
  }
  Bytes all(total);
  check(MPI_Gatherv(local.data(), count_of(local.size()), MPI_BYTE, all.data(), counts.data(), displs.data(),
                    MPI_BYTE, root, impl_->comm),
        "gather");
  std::vector<Bytes> out(sizes.size());
  for (std::size_t q = 0; q < sizes.size(); ++q) {
    const auto b = all.begin() + displs[q];
    out[q].assign(b, b + counts[q]);
  }
  return out;
}

void MpiComm::broadcast(Bytes& data, int root) const {
  const Inside inside(impl_->inside_s);
  auto n = static_cast<std::int64_t>(data.size());
  check(MPI_Bcast(&n, 1, MPI_INT64_T, root, impl_->comm), "broadcast of a size");
  data.resize(static_cast<std::size_t>(n));
  check(MPI_Bcast(data.data(), count_of(data.size()), MPI_BYTE, root, impl_->comm), "broadcast");
}

std::vector<Bytes> MpiComm::exchange(const std::vector<Bytes>& send) const {
  const Inside inside(impl_->inside_s);
  const int p = impl_->size;
  if (send.size() != static_cast<std::size_t>(p)) throw_simulation_error("MpiComm::exchange: one message per rank");
  std::vector<std::int64_t> out_sizes(static_cast<std::size_t>(p)), in_sizes(static_cast<std::size_t>(p));
  for (int q = 0; q < p; ++q) out_sizes[static_cast<std::size_t>(q)] = static_cast<std::int64_t>(send[static_cast<std::size_t>(q)].size());
  check(MPI_Alltoall(out_sizes.data(), 1, MPI_INT64_T, in_sizes.data(), 1, MPI_INT64_T, impl_->comm),
        "exchange of sizes");
  std::vector<Bytes> in(static_cast<std::size_t>(p));
  std::vector<MPI_Request> requests;
  requests.reserve(2 * static_cast<std::size_t>(p));
  for (int q = 0; q < p; ++q) {
    const auto k = static_cast<std::size_t>(q);
    if (q == impl_->rank) {
      in[k] = send[k];
      continue;
    }
    if (in_sizes[k] > 0) {
      in[k].resize(static_cast<std::size_t>(in_sizes[k]));
      requests.emplace_back();
      check(MPI_Irecv(in[k].data(), count_of(in[k].size()), MPI_BYTE, q, 1, impl_->comm, &requests.back()),
            "receive of an exchange");
    }
    if (!send[k].empty()) {
      requests.emplace_back();
      check(MPI_Isend(send[k].data(), count_of(send[k].size()), MPI_BYTE, q, 1, impl_->comm, &requests.back()),
            "send of an exchange");
    }
  }
  check(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE), "exchange");
  return in;
}

std::vector<Bytes> MpiComm::exchange_among(std::span<const int> ranks, const std::vector<Bytes>& send) const {
  const Inside inside(impl_->inside_s);
  if (send.size() != ranks.size()) throw_simulation_error("MpiComm::exchange_among: one message per partner");
  const std::size_t n = ranks.size();
  // The sizes first, partner to partner, then the messages (tags of their own: an exchange() may follow at once).
  std::vector<std::int64_t> out_sizes(n), in_sizes(n, 0);
  std::vector<MPI_Request> requests;
  requests.reserve(2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    out_sizes[k] = static_cast<std::int64_t>(send[k].size());
    if (ranks[k] == impl_->rank) {
      in_sizes[k] = out_sizes[k];
      continue;
    }
    requests.emplace_back();
    check(MPI_Irecv(&in_sizes[k], 1, MPI_INT64_T, ranks[k], 3, impl_->comm, &requests.back()),
          "receive of a neighbour's size");
    requests.emplace_back();
    check(MPI_Isend(&out_sizes[k], 1, MPI_INT64_T, ranks[k], 3, impl_->comm, &requests.back()),
          "send of a size to a neighbour");
  }
  check(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE), "neighbours' sizes");
  requests.clear();
  std::vector<Bytes> in(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (ranks[k] == impl_->rank) {
      in[k] = send[k];
      continue;
    }
    if (in_sizes[k] > 0) {
      in[k].resize(static_cast<std::size_t>(in_sizes[k]));
      requests.emplace_back();
      check(MPI_Irecv(in[k].data(), count_of(in[k].size()), MPI_BYTE, ranks[k], 4, impl_->comm, &requests.back()),
            "receive of a neighbour's message");
    }
    if (!send[k].empty()) {
      requests.emplace_back();
      check(MPI_Isend(send[k].data(), count_of(send[k].size()), MPI_BYTE, ranks[k], 4, impl_->comm, &requests.back()),
            "send of a message to a neighbour");
    }
  }
  check(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE), "neighbour exchange");
  return in;
}

void MpiComm::exchange_with(std::span<const int> ranks, const std::vector<std::vector<double>>& send,
                            std::vector<std::vector<double>>& recv) const {
  const Inside inside(impl_->inside_s);
  std::vector<MPI_Request> requests;
  requests.reserve(2 * ranks.size());
  for (std::size_t k = 0; k < ranks.size(); ++k) {
    if (ranks[k] == impl_->rank) {
      recv[k] = send[k];
      continue;
    }
    if (!recv[k].empty()) {
      requests.emplace_back();
      check(MPI_Irecv(recv[k].data(), count_of(recv[k].size()), MPI_DOUBLE, ranks[k], 2, impl_->comm, &requests.back()),
            "receive of a neighbour exchange");
    }
    if (!send[k].empty()) {
      requests.emplace_back();
      check(MPI_Isend(send[k].data(), count_of(send[k].size()), MPI_DOUBLE, ranks[k], 2, impl_->comm, &requests.back()),
            "send of a neighbour exchange");
    }
  }
  check(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE), "neighbour exchange");
}

void MpiComm::barrier() const {
  const Inside inside(impl_->inside_s);
  check(MPI_Barrier(impl_->comm), "barrier");
}

bool MpiComm::all_arrive_within(double timeout_s) const {
  MPI_Request r;
  check(MPI_Ibarrier(impl_->control, &r), "barrier of a verdict");
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int done = 0;
  while (true) {
    check(MPI_Test(&r, &done, MPI_STATUS_IGNORE), "barrier of a verdict");
    if (done) return true;
    if (std::chrono::steady_clock::now() > until) return false;  // the request is left: the run ends with abort()
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

void MpiComm::abort(int code) const {
  MPI_Abort(impl_->comm, code);
  std::abort();
}

void MpiComm::exchange_halo(Field<2>& f) const {
  if (impl_->size > 1) exchange_halo_among(f, all_boxes<2>(*this, f.box()), HaloCells::All);
}
void MpiComm::exchange_halo(Field<3>& f) const {
  if (impl_->size > 1) exchange_halo_among(f, all_boxes<3>(*this, f.box()), HaloCells::All);
}
void MpiComm::exchange_halo_among(Field<2>& f, std::span<const IndexBox<2>> boxes, HaloCells cells) const {
  const Inside inside(impl_->inside_s);
  if (impl_->size > 1) plan_for<2>(impl_->plans2, f, boxes, cells, impl_->rank).exchange(impl_->comm, f);
}
void MpiComm::exchange_halo_among(Field<3>& f, std::span<const IndexBox<3>> boxes, HaloCells cells) const {
  const Inside inside(impl_->inside_s);
  if (impl_->size > 1) plan_for<3>(impl_->plans3, f, boxes, cells, impl_->rank).exchange(impl_->comm, f);
}

double MpiComm::seconds_communicating() const { return impl_->inside_s; }

}  // namespace fluidbed

#endif  // FLUIDBED_HAVE_MPI
